#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace sylva {

/** `text` quoted for a POSIX shell: in single quotes, each ' written as '\'' ("a b" → 'a b'). */
std::string shellQuote(std::string_view text);

/** What a program run by runProgram did. */
struct ProgramResult {
  /** Exit status; 128 + the signal when it was killed; 127 when it could not be started. */
  int exitCode = 127;
  std::string out; ///< everything it wrote to stdout
  std::string err; ///< everything it wrote to stderr (or why it could not be started)
};

/**
 * Runs `argv` (argv[0] looked up on $PATH unless it holds a slash) with this process's environment, stdin
 * from /dev/null, and waits for it, collecting stdout and stderr. Never throws for the program's failure:
 * the result says what happened. Throws sylva::Error when argv is empty or pipes cannot be made.
 */
ProgramResult runProgram(const std::vector<std::string>& argv);

} // namespace sylva
