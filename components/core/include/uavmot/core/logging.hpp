#pragma once
// One log format for every process: "[time] [component] [level] message".
// Logs go to stderr so stdout stays free for data and tables.

#include <string>

#include <spdlog/spdlog.h>

namespace uavmot {

// `level`: trace, debug, info, warn, error, off. Throws InvalidArgument on anything else.
void init_logging(const std::string& component, const std::string& level = "info");

}  // namespace uavmot
