#pragma once
// The output's edge bearings steered towards the exemplar's distribution (histogram matching, as
// texture synthesis does): growth prefers, among candidates of near-equal cost, the one whose
// chord bearing brings the output's cumulative bearing distribution closer to the exemplar's.
#include <array>

#include "core/vec2.hpp"

namespace tw::network_detail {

class BearingCdf {
 public:
  static constexpr int kBins = 36;  // 5° bins over 0..180° (bearings are undirected)

  // The bin of a chord's bearing, from north, modulo 180° (as network_stats counts it).
  static int bin_of(Vec2 chord);

  // `count`: +1 an edge with this chord joins the side, -1 it leaves (a split edge).
  void add_target(Vec2 chord) { add(target_, target_total_, chord, 1.0); }
  void add_output(Vec2 chord, double count) { add(output_, output_total_, chord, count); }

  // How much an edge with this chord would move the output's bearing distribution towards
  // (< 0) or away from (> 0) the exemplar's: the change of the Wasserstein-1 distance between
  // the two binned distributions, scaled by the output's edge count and divided by the number
  // of bins, so about -1..1 (the share of the bins past the chord's where the output falls short
  // of the exemplar, minus the share where it is ahead). 0 before either side has an edge.
  double step_cost(Vec2 chord) const;

 private:
  static void add(std::array<double, kBins>& h, double& total, Vec2 chord, double count);
  std::array<double, kBins> target_{}, output_{};
  double target_total_ = 0.0, output_total_ = 0.0;
};

}  // namespace tw::network_detail
