#include <sylva/core/Log.hpp>

#include <sylva/core/Error.hpp>

#include <spdlog/sinks/stdout_color_sinks.h>

namespace sylva::log {

void setLevel(Level level) {
  static const bool kInit = [] {
    auto logger = spdlog::stderr_color_mt("sylva");
    logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)kInit;
  static constexpr spdlog::level::level_enum kMap[] = {spdlog::level::trace, spdlog::level::debug,
                                                       spdlog::level::info,  spdlog::level::warn,
                                                       spdlog::level::err,   spdlog::level::off};
  spdlog::set_level(kMap[static_cast<int>(level)]);
}

Level parseLevel(const std::string& name) {
  if (name == "trace")
    return Level::Trace;
  if (name == "debug")
    return Level::Debug;
  if (name == "info")
    return Level::Info;
  if (name == "warn")
    return Level::Warn;
  if (name == "error")
    return Level::Error;
  if (name == "off")
    return Level::Off;
  fail("--log-level: unknown level '{}' (expected trace|debug|info|warn|error|off)", name);
}

} // namespace sylva::log
