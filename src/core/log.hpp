#pragma once
// The one logger of terraweave (spdlog). Plain lines on stderr; progress bars only when
// stderr is a terminal (see core/progress.hpp). Every message is one line: newlines and
// carriage returns in it (from a key, a --set value, a file name) are escaped, so no input can
// forge a line of its own.
#include <spdlog/spdlog.h>

#include <string>
#include <string_view>

namespace tw {

spdlog::logger& logger();
void set_log_level(spdlog::level::level_enum level);

// `text` on one line: a newline becomes the two characters \n, a carriage return \r. The logger and
// the CLI's error line use it.
std::string single_line(std::string_view text);

}  // namespace tw
