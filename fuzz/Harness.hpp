#pragma once
// Fuzz harnesses: one function per loader or parser Sylva owns. Each feeds arbitrary bytes to the real entry
// point and accepts exactly one outcome besides success: a sylva::Error (the one-line message users see). Any
// other exception, a crash, a sanitizer report or an oversized allocation is a finding. The same functions
// run under libFuzzer (fuzz/FuzzMain.cpp, preset `fuzz`) and over the committed corpus and regression inputs
// in the unit tests (tests/unit/fuzz), so every crash once found stays fixed.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sylva::fuzz {

/** One fuzz target: its name (also the corpus folder name under fuzz/corpus and fuzz/regressions). */
struct Target {
  std::string_view name;
  std::string_view what;
  void (*run)(std::span<const std::uint8_t> bytes);
};

/** Every target compiled into this build (the CLI target only where the sylva command is built). */
const std::vector<Target>& targets();

/** Runs target `name` on `bytes`; throws std::invalid_argument for an unknown name. */
void runTarget(std::string_view name, std::span<const std::uint8_t> bytes);

} // namespace sylva::fuzz
