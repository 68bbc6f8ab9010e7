#pragma once
// Progress of a long stage: a redrawn bar when stderr is a terminal, otherwise a few plain
// log lines (every 10 %, and only once the stage has run for a couple of seconds), so CI and
// nightly logs stay readable: a demo of 19 short features prints none. Lines between 0 and
// 100 % end with the estimated time left, "(ETA 12 s)". Our own: Debian bookworm packages no C++
// progress-bar library (docs/cli.md, "Global options").
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

namespace tw {

struct ProgressStyle {
  bool terminal = false;  // redraw a bar on stderr instead of logging lines
  // Log lines start only once the stage has run this long; a stage that logged also logs 100 %.
  std::chrono::milliseconds quiet{2000};
  static ProgressStyle for_stderr();  // a bar when stderr is a terminal, else lines
};

// "ETA 42 s", "ETA 3 min 05 s", "ETA 2 h 07 min": the time left when `done` of `total` items
// took `elapsed_seconds` at a steady rate ("ETA ?" before the first item).
std::string eta_text(std::int64_t done, std::int64_t total, double elapsed_seconds);

class Progress {
 public:
  Progress(std::string label, std::int64_t total,
           ProgressStyle style = ProgressStyle::for_stderr());
  // Countable items (`noun`: "tile", "feature"): once the quiet period has passed, every item
  // logs "<label>: <noun> <i> of <N>, ETA ..." (items are coarse: tiles, features).
  Progress(std::string label, std::int64_t total, std::string noun,
           ProgressStyle style = ProgressStyle::for_stderr());
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void advance(std::int64_t steps = 1);

 private:
  void report(std::int64_t done);
  std::string eta(std::int64_t done) const;

  void report_item(std::int64_t done);

  std::string label_;
  std::string noun_;  // "" = percent steps
  std::int64_t total_;
  std::atomic<std::int64_t> done_{0};
  std::atomic<int> last_decile_{-1};
  std::atomic<bool> logged_{false};
  std::chrono::steady_clock::time_point start_;
  ProgressStyle style_;
};

}  // namespace tw
