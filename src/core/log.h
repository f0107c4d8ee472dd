#pragma once
/// Logging through spdlog, to stderr. Messages a user must act on are warnings; progress and
/// summaries go to stdout through the CLI, not through the log.

#include <spdlog/spdlog.h>

namespace rescuesim::log {

/// Sets the global level from a name: trace, debug, info, warn, error, off.
void set_level(const std::string& level);

using spdlog::debug;
using spdlog::error;
using spdlog::info;
using spdlog::warn;

}  // namespace rescuesim::log
