#include "core/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace tw {

spdlog::logger& logger() {
  static std::shared_ptr<spdlog::logger> instance = [] {
    auto l = spdlog::stderr_color_mt("terraweave");
    l->set_pattern("%^[%l]%$ %v");
    l->set_level(spdlog::level::info);
    return l;
  }();
  return *instance;
}

void set_log_level(spdlog::level::level_enum level) { logger().set_level(level); }

}  // namespace tw
