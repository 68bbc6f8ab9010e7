#include "pipeline/detail/stage_clock.hpp"

#include "core/log.hpp"

namespace tw::detail {

void StageClock::start(std::string stage) {
  stage_ = std::move(stage);
  logger().info("{}...", stage_);
  started_ = std::chrono::steady_clock::now();
}

void StageClock::stop() {
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  timings_.push_back({stage_, seconds});
  logger().info("{}: {:.3f} s", stage_, seconds);
}

void add_untimed_stage(std::vector<StageTiming>& timings, double total_seconds) {
  double timed = 0.0;
  for (const StageTiming& t : timings) timed += t.seconds;
  if (total_seconds > timed) timings.push_back({kUntimedStage, total_seconds - timed});
}

}  // namespace tw::detail
