#pragma once

// Running the built `sylva` binary from tests: shell quoting, captured output, whole-file reads.

#include "TempDir.hpp"

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <cstdlib>
#include <string>

namespace sylva::test {

/** Exit status (-1 when killed by a signal) and captured streams of one run. */
struct RunResult {
  int status = -1;
  std::string out;
  std::string err;
};

/** `text` in single quotes for /bin/sh. */
std::string quote(const std::string& text);

/** A whole file as bytes ("" if it cannot be read). */
std::string readAll(const std::filesystem::path& path);

/** Runs `<exe> <args>` (args already shell-quoted) in the current directory, capturing into files in `dir`.
 */
RunResult runProgram(const std::string& exe, const std::filesystem::path& dir, const std::string& args);

#ifdef SYLVA_EXE
/** Runs the `sylva` binary under test (SYLVA_EXE, defined per CLI test target) with `args` in `dir`. */
inline RunResult runSylva(const TempDir& dir, const std::string& args) {
  return runProgram(SYLVA_EXE, dir.path(), args);
}
/** The same with `cwd` as the working directory (output captured in `dir`). */
inline RunResult runSylvaFrom(const std::filesystem::path& cwd, const TempDir& dir, const std::string& args) {
  return runProgram("/bin/sh", dir.path(),
                    "-c " + quote("cd " + quote(cwd.string()) + " && exec " + quote(SYLVA_EXE) + " " + args));
}
#endif

/** `name` in the test's directory, as a quoted shell argument (the command runs elsewhere). */
inline std::string at(const TempDir& dir, const std::string& name) {
  return quote((dir / name).string());
}

/** Lines in `text` (a last line without a newline counts). */
inline std::size_t lineCount(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) +
         (!text.empty() && text.back() != '\n' ? 1 : 0);
}

/** Whether a window can open: false (the test skips) without a display, unless SYLVA_REQUIRE_DISPLAY=1. */
inline bool haveDisplay() {
  return std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
}

/** SYLVA_REQUIRE_DISPLAY=1: a missing display fails the view tests instead of skipping them (CI). */
inline bool displayRequired() {
  const char* required = std::getenv("SYLVA_REQUIRE_DISPLAY");
  return required != nullptr && std::string(required) == "1";
}

} // namespace sylva::test
