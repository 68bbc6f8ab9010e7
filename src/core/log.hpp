#pragma once
// The one logger of terraweave (spdlog). Plain lines on stderr; progress bars only when
// stderr is a terminal (see core/progress.hpp).
#include <spdlog/spdlog.h>

namespace tw {

spdlog::logger& logger();
void set_log_level(spdlog::level::level_enum level);

}  // namespace tw
