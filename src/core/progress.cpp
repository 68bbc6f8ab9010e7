#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/log.hpp"

namespace tw {

ProgressStyle ProgressStyle::for_stderr() {
  ProgressStyle style;
  style.terminal = isatty(STDERR_FILENO);
  return style;
}

Progress::Progress(std::string label, std::int64_t total, ProgressStyle style)
    : label_(std::move(label)),
      total_(total > 0 ? total : 1),
      start_(std::chrono::steady_clock::now()),
      style_(style) {}

Progress::Progress(std::string label, std::int64_t total, std::string noun, ProgressStyle style)
    : Progress(std::move(label), total, style) {
  noun_ = std::move(noun);
}

std::string eta_text(std::int64_t done, std::int64_t total, double elapsed_seconds) {
  if (done <= 0 || !(elapsed_seconds >= 0.0)) return "ETA ?";
  const double left = elapsed_seconds * double(std::max<std::int64_t>(0, total - done)) / done;
  const auto seconds = std::int64_t(std::llround(left));
  if (seconds < 60) return fmt::format("ETA {} s", seconds);
  if (seconds < 3600) return fmt::format("ETA {} min {:02} s", seconds / 60, seconds % 60);
  return fmt::format("ETA {} h {:02} min", seconds / 3600, seconds % 3600 / 60);
}

void Progress::report_item(std::int64_t done) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string text = fmt::format("{}: {} {} of {}, {}", label_, noun_, std::min(done, total_),
                                       total_, eta_text(done, total_, elapsed));
  if (style_.terminal) {
    std::fprintf(stderr, "\r%-60s", text.c_str());
    last_decile_ = 0;
    return;
  }
  if (elapsed * 1000.0 < double(style_.quiet.count()) && !logged_) return;
  logged_ = true;
  logger().info("{}", text);
}

Progress::~Progress() {
  if (style_.terminal && last_decile_ >= 0) std::fputc('\n', stderr);
}

void Progress::advance(std::int64_t steps) {
  report(done_ += steps);
}

// " (ETA 1 min 05 s)": the time left at the rate so far ("" before any step or at the end).
std::string Progress::eta(std::int64_t done) const {
  if (done <= 0 || done >= total_) return "";
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  return " (" + eta_text(done, total_, elapsed) + ")";
}

void Progress::report(std::int64_t done) {
  if (!noun_.empty()) return report_item(done);
  const int permille = int(std::min<std::int64_t>(1000, done * 1000 / total_));
  const int decile = permille / 100;
  if (style_.terminal) {
    static constexpr int kWidth = 40;
    const int filled = permille * kWidth / 1000;
    std::fprintf(stderr, "\r%-24s [%.*s%*s] %5.1f%%%-20s", label_.c_str(), filled,
                 "########################################", kWidth - filled, "", permille / 10.0,
                 eta(done).c_str());
    last_decile_ = decile;
    return;
  }
  int previous = last_decile_.load();
  while (decile > previous && !last_decile_.compare_exchange_weak(previous, decile)) {
  }
  if (decile <= previous) return;
  // Short stages say nothing; a stage that did log also logs its end.
  if (decile < 10 && std::chrono::steady_clock::now() - start_ < style_.quiet) return;
  if (decile == 10 && !logged_) return;
  logged_ = true;
  logger().info("{}: {}%{}", label_, decile * 10, decile > 0 ? eta(done) : "");
}

}  // namespace tw
