// The CLI fuzz target: arguments parsed by the real `sylva` command line. Option parsing, conversions and
// validators (NaN, ranges, member lists, files) all run; then the root's parse-complete callback, which CLI11
// runs before any subcommand's callback, stops the parse, so no command does. (Removing the commands'
// callbacks instead would free the option structs they own while CLI11 still writes into them.)
#include "Commands.hpp"
#include "Harness.hpp"

#include <sylva/core/Error.hpp>
#include <sylva/core/Log.hpp>

#include <string>
#include <vector>

namespace sylva::fuzz {

namespace {

/** Thrown once every option has been parsed and validated, before any command runs. */
struct ParsedOnly {};

} // namespace

/** Input: arguments separated by NUL or newline bytes (at most 64), after the program name. */
void runCliArguments(std::span<const std::uint8_t> bytes) {
  std::vector<std::string> args{"sylva"};
  std::string current;
  for (const std::uint8_t b : bytes) {
    if (b == 0 || b == '\n') {
      args.push_back(current);
      current.clear();
      if (args.size() > 64) {
        break;
      }
    } else {
      current += static_cast<char>(b);
    }
  }
  if (!current.empty() && args.size() <= 64) {
    args.push_back(current);
  }
  std::vector<const char*> argv;
  for (const std::string& a : args) {
    argv.push_back(a.c_str());
  }
  const auto cli = app::makeCli();
  app::Cli* raw = cli.get();
  cli->app->parse_complete_callback([raw] {
    (void)log::parseLevel(raw->logLevel); // validated as `sylva` would, without changing this process's level
    throw ParsedOnly{};
  });
  try {
    cli->app->parse(static_cast<int>(argv.size()), argv.data());
  } catch (const ParsedOnly&) {
  } catch (const CLI::Error&) {
  } catch (const Error&) {
  }
}

} // namespace sylva::fuzz
