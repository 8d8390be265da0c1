#include "uavmot/core/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include "uavmot/core/error.hpp"

namespace uavmot {

void init_logging(const std::string& component, const std::string& level) {
  const auto parsed = spdlog::level::from_str(level);
  if (parsed == spdlog::level::off && level != "off") {
    throw InvalidArgument("unknown log level '" + level + "' (expected trace, debug, info, warn, error or off)");
  }
  auto logger = spdlog::stderr_color_mt(component);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  logger->set_level(parsed);
  spdlog::set_default_logger(logger);
}

}  // namespace uavmot
