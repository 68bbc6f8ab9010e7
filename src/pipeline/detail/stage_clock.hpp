#pragma once
// The stage timings of report.json (`timings.stages`): every stage that takes time is one
// entry, and what no stage measured is the stage `untimed`, so the stages add up to the total.
#include <chrono>
#include <string>
#include <vector>

#include "pipeline/run.hpp"

namespace tw::detail {

// The name of the remainder stage: total_seconds minus every other stage.
inline constexpr const char* kUntimedStage = "untimed";

// Times one stage after another into `timings` and logs "<stage>..." and "<stage>: 1.234 s".
class StageClock {
 public:
  explicit StageClock(std::vector<StageTiming>& timings) : timings_(timings) {}

  void start(std::string stage);
  void stop();

 private:
  std::vector<StageTiming>& timings_;
  std::string stage_;
  std::chrono::steady_clock::time_point started_;
};

// Appends `untimed` (total_seconds minus the stages' sum) when that is positive.
void add_untimed_stage(std::vector<StageTiming>& timings, double total_seconds);

}  // namespace tw::detail
