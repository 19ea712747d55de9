#include "log/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <stdexcept>

namespace rgnav::log {

void init(const std::string& process_name, const std::string& level)
{
  const auto lvl = spdlog::level::from_str(level);
  if (lvl == spdlog::level::off && level != "off")
    throw std::invalid_argument("unknown log level '" + level + "'");
  spdlog::drop(process_name);  // init may run again (tests, restarts in-process)
  auto logger = spdlog::stderr_color_mt(process_name);
  logger->set_pattern("%H:%M:%S.%e %^%L%$ [%n] %v");
  logger->set_level(lvl);
  spdlog::set_default_logger(logger);
}

}  // namespace rgnav::log
