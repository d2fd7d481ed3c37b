#include "data/report/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

namespace kelvin {

void InitLogging(Verbosity verbosity) {
  auto logger = spdlog::stderr_color_mt("kelvin");
  logger->set_pattern("[%H:%M:%S.%e] %^%l%$ %v");
  switch (verbosity) {
    case Verbosity::kQuiet: logger->set_level(spdlog::level::warn); break;
    case Verbosity::kNormal: logger->set_level(spdlog::level::info); break;
    case Verbosity::kVerbose: logger->set_level(spdlog::level::debug); break;
  }
  spdlog::set_default_logger(logger);
}

}  // namespace kelvin
