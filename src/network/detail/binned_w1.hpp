#pragma once
// The normalized Wasserstein-1 distance (network/stats.hpp, normalized_w1) of a sample held as
// counts in bins against a fixed reference sample: cheap to re-evaluate as a pass changes the
// counts one edge at a time (grower_twigs.cpp, grower_junction_shift.cpp).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace tw::network_detail {

// The W1 distance between a sample held as counts in `bins` bins of `width` from 0 and a
// reference sample, normalized by the reference's spread as normalized_w1 is: exact for integer
// values in bins of 1.
class BinnedW1 {
 public:
  BinnedW1(const std::vector<double>& reference, double width, int bins)
      : width_(width), cdf_(std::size_t(bins), 0.0) {
    double mean = 0.0, var = 0.0;
    for (double v : reference) cdf_[std::size_t(bin(v))] += 1.0, mean += v;
    mean /= double(reference.size());
    for (double v : reference) var += (v - mean) * (v - mean);
    spread_ = std::sqrt(var / double(reference.size()));
    if (!(spread_ > 0.0)) spread_ = 1.0;
    double running = 0.0;
    for (double& c : cdf_) running += c, c = running / double(reference.size());
  }
  int bin(double v) const {
    return std::clamp(int(std::floor(v / width_)), 0, int(cdf_.size()) - 1);
  }
  double apart(const std::vector<double>& counts, double total) const {
    if (!(total > 0.0)) return 1e300;
    double running = 0.0, sum = 0.0;
    for (std::size_t k = 0; k + 1 < cdf_.size(); ++k) {
      running += counts[k];
      sum += std::abs(running / total - cdf_[k]);
    }
    return sum * width_ / spread_;
  }

  // The change of apart() when counts move between bins (`moves`: from, to; the total staying),
  // from the sample's running counts (`running[k]`: the counts of bins 0..k): work in the bins
  // the moves span, not in all bins.
  double apart_change(const std::vector<double>& running, double total,
                      const std::vector<std::pair<int, int>>& moves) const {
    if (moves.empty() || !(total > 0.0)) return 0.0;
    // The bins between each move's two (merged where they overlap): a move of a few degrees
    // spans a few bins whatever the bearings of the others.
    std::vector<std::pair<int, int>> spans;
    for (const auto& [from, to] : moves)
      if (from != to) spans.push_back({std::min(from, to), std::max(from, to)});
    std::sort(spans.begin(), spans.end());
    double change = 0.0;
    int done = 0;
    for (const auto& [lo, hi] : spans)
      for (int k = std::max(lo, done); k < hi && k + 1 < int(cdf_.size()); ++k) {
        double moved = 0.0;  // counts joining (+) or leaving (-) bins 0..k
        for (const auto& [from, to] : moves)
          moved += double(to <= k && k < from) - double(from <= k && k < to);
        done = k + 1;
        if (moved == 0.0) continue;
        const double have = running[std::size_t(k)], want = cdf_[std::size_t(k)];
        change += std::abs((have + moved) / total - want) - std::abs(have / total - want);
      }
    return change * width_ / spread_;
  }

  // How much apart() can change when one count of `total` moves by `by` (in the values' unit).
  double one_count_moved(double by, double total) const {
    return total > 0.0 ? by / (total * spread_) : 0.0;
  }

 private:
  double width_, spread_ = 1.0;
  std::vector<double> cdf_;
};

}  // namespace tw::network_detail
