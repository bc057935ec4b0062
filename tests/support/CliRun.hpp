#pragma once

// Running the built `sylva` binary from tests: shell quoting, captured output, whole-file reads.

#include <filesystem>
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

} // namespace sylva::test
