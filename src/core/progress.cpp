#include "core/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include "core/log.hpp"

namespace tw {

Progress::Progress(std::string label, std::int64_t total)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      start_(std::chrono::steady_clock::now()),
      terminal_(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (terminal_ && last_decile_ >= 0) std::fputc('\n', stderr);
}

void Progress::advance(std::int64_t steps) {
  report(done_ += steps);
}

void Progress::report(std::int64_t done) {
  const int permille = int(std::min<std::int64_t>(1000, done * 1000 / total_));
  const int decile = permille / 100;
  if (terminal_) {
    static constexpr int kWidth = 40;
    const int filled = permille * kWidth / 1000;
    std::fprintf(stderr, "\r%-24s [%.*s%*s] %5.1f%%", label_.c_str(), filled,
                 "########################################", kWidth - filled, "", permille / 10.0);
    last_decile_ = decile;
    return;
  }
  int previous = last_decile_.load();
  while (decile > previous && !last_decile_.compare_exchange_weak(previous, decile)) {
  }
  if (decile <= previous) return;
  // Stages shorter than this say nothing; a stage that did log also logs its end.
  constexpr auto kQuiet = std::chrono::seconds(2);
  if (decile < 10 && std::chrono::steady_clock::now() - start_ < kQuiet) return;
  if (decile == 10 && !logged_) return;
  logged_ = true;
  logger().info("{}: {}%", label_, decile * 10);
}

}  // namespace tw
