#pragma once

#include <spdlog/spdlog.h>

namespace sylva::log {

/** Verbosity of the process-wide logger (stderr). */
enum class Level { Trace, Debug, Info, Warn, Error, Off };

/** Sets the process-wide log level; safe to call at any time from the main thread. */
void setLevel(Level level);

/** Parses "trace|debug|info|warn|error|off"; throws sylva::Error naming the value otherwise. */
Level parseLevel(const std::string& name);

using spdlog::debug;
using spdlog::error;
using spdlog::info;
using spdlog::trace;
using spdlog::warn;

} // namespace sylva::log
