#include "Golden.hpp"

#include <sylva/core/Files.hpp>
#include <sylva/gl/ContextInfo.hpp>

#include <gtest/gtest.h>

namespace sylva::test {

namespace {
std::string deviceClass() {
  return gl::queryContextInfo().deviceClass();
}
} // namespace

std::filesystem::path goldenReferencePath(const std::string& name) {
  return std::filesystem::path(SYLVA_SOURCE_DIR) / "tests/golden/refs" / deviceClass() / (name + ".png");
}

void expectGolden(const Image& actual, const std::string& name, const render::Tolerance& tolerance) {
  const std::filesystem::path reference = goldenReferencePath(name);
  const std::filesystem::path outDir = std::filesystem::path(SYLVA_BINARY_DIR) / "golden-out" / deviceClass();
  const std::filesystem::path actualPath = outDir / (name + ".actual.png");
  if (!std::filesystem::exists(reference)) {
    saveImage(actualPath, actual);
    ADD_FAILURE() << "no golden reference " << reference << "; wrote the actual image to " << actualPath
                  << " — review it, then run scripts/promote-goldens.sh";
    return;
  }
  const Image expected = loadImage(reference);
  const render::CompareResult result = render::compareImages(actual, expected, tolerance);
  if (!result.passed) {
    saveImage(actualPath, actual);
    if (!result.diff.empty()) {
      saveImage(outDir / (name + ".diff.png"), result.diff);
    }
    saveJsonFile(outDir / (name + ".json"), result.toJson(tolerance));
    ADD_FAILURE() << "golden '" << name << "' differs: " << (result.sizeMatches ? "" : "size mismatch; ")
                  << result.failingPixels << " of " << result.comparedPixels << " pixels beyond "
                  << tolerance.maxChannelDiff << " (max diff " << result.maxChannelDiff
                  << ", allowed fraction " << tolerance.maxFailingFraction << "); actual: " << actualPath
                  << ", diff: " << (outDir / (name + ".diff.png"));
  } else {
    // A stale actual from an earlier failing run would mislead promote-goldens.sh.
    std::error_code ec;
    std::filesystem::remove(actualPath, ec);
  }
}

} // namespace sylva::test
