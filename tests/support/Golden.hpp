#pragma once

#include <sylva/core/Image.hpp>
#include <sylva/render/ImageCompare.hpp>

#include <filesystem>
#include <string>

namespace sylva::test {

/**
 * Compares `actual` with the reference `tests/golden/refs/<device class>/<name>.png` (device class from the
 * current context: "llvmpipe" gates CI, "gpu" for NVIDIA runs). On failure, or when no reference exists,
 * writes
 * `<build>/golden-out/<class>/<name>.actual.png`, `.diff.png` and `.json` and fails the test with their
 * paths; `scripts/promote-goldens.sh` copies reviewed actuals over the references. Keep the tolerance next to
 * the call with a comment naming the effect that needs it.
 */
void expectGolden(const Image& actual, const std::string& name, const render::Tolerance& tolerance);

/** Path of the reference for `name` in the current device class. */
std::filesystem::path goldenReferencePath(const std::string& name);

} // namespace sylva::test
