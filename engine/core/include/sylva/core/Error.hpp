#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace sylva {

/**
 * The one exception type of Sylva. The message is a single line that names the file or field at fault and the
 * reason, e.g. `heights.png: truncated PNG data`. The CLI prints it verbatim and exits non-zero.
 */
class Error : public std::runtime_error {
public:
  /** `message`: the whole line, naming the file or field first. */
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/** Throws sylva::Error with a fmt-formatted message. */
template <typename... Args> [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

} // namespace sylva
