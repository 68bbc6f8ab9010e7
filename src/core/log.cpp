#include "core/log.hpp"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>

namespace tw {
namespace {

// %* in the pattern: the message through single_line.
class SingleLineMessage : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&,
              spdlog::memory_buf_t& dest) override {
    const std::string line = single_line({msg.payload.data(), msg.payload.size()});
    dest.append(line.data(), line.data() + line.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override {
    return std::make_unique<SingleLineMessage>();
  }
};

}  // namespace

spdlog::logger& logger() {
  static std::shared_ptr<spdlog::logger> instance = [] {
    auto l = spdlog::stderr_color_mt("terraweave");
    auto formatter = std::make_unique<spdlog::pattern_formatter>();
    formatter->add_flag<SingleLineMessage>('*').set_pattern("%^[%l]%$ %*");
    l->set_formatter(std::move(formatter));
    l->set_level(spdlog::level::info);
    return l;
  }();
  return *instance;
}

void set_log_level(spdlog::level::level_enum level) {
  logger().set_level(level);
}

std::string single_line(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace tw
