#include "network/detail/bearing_cdf.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tw::network_detail {

int BearingCdf::bin_of(Vec2 chord) {
  double b = std::atan2(chord.x, chord.y) * 180.0 / std::numbers::pi;
  b = std::fmod(b + 360.0, 180.0);
  return std::clamp(int(b * kBins / 180.0), 0, kBins - 1);
}

void BearingCdf::add(std::array<double, kBins>& h, double& total, Vec2 chord, double count) {
  if (chord == Vec2{}) return;
  h[std::size_t(bin_of(chord))] += count;
  total += count;
}

double BearingCdf::step_cost(Vec2 chord) const {
  if (chord == Vec2{} || target_total_ <= 0.0 || output_total_ <= 0.0) return 0.0;
  const int at = bin_of(chord);
  double before = 0.0, after = 0.0, have = 0.0, want = 0.0;
  for (int k = 0; k < kBins; ++k) {
    have += output_[std::size_t(k)];
    want += target_[std::size_t(k)] / target_total_;
    before += std::abs(have / output_total_ - want);
    after += std::abs((have + (k >= at ? 1.0 : 0.0)) / (output_total_ + 1.0) - want);
  }
  return (after - before) * output_total_ / kBins;
}

}  // namespace tw::network_detail
