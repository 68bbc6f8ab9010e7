#include "synth/detail/edge_bound.hpp"

#include <algorithm>
#include <cmath>

#include "synth/detail/cost.hpp"

namespace tw::detail {

EdgeStats make_edge_stats(const ColumnSet& columns, const std::vector<std::int32_t>& order) {
  const int C = columns.column;
  EdgeStats stats;
  stats.count =
      order.empty() ? int(columns.samples.size() / std::size_t(std::max(C, 1))) : int(order.size());
  stats.blocks = (C + kBoundBlock - 1) / kBoundBlock;
  const std::size_t n = std::size_t(stats.count) * stats.blocks;
  stats.opaque.assign(n, 0.0f);
  stats.red.assign(n, 0.0f);
  stats.green.assign(n, 0.0f);
  stats.blue.assign(n, 0.0f);
  for (int b = 0; b < stats.blocks; ++b)
    stats.block_size.push_back(float(std::min(C, (b + 1) * kBoundBlock) - b * kBoundBlock));
  for (int j = 0; j < stats.count; ++j) {
    const std::size_t source = order.empty() ? std::size_t(j) : std::size_t(order[j]);
    const std::uint32_t* samples = columns.samples.data() + source * C;
    for (int b = 0; b < stats.blocks; ++b) {
      int opaque = 0, red = 0, green = 0, blue = 0;
      for (int k = b * kBoundBlock; k < std::min(C, (b + 1) * kBoundBlock); ++k) {
        opaque += is_opaque(samples[k]) ? 1 : 0;
        red += int(channel_of(samples[k], 0));
        green += int(channel_of(samples[k], 1));
        blue += int(channel_of(samples[k], 2));
      }
      const std::size_t at = std::size_t(b) * stats.count + j;
      stats.opaque[at] = float(opaque);
      stats.red[at] = float(red);
      stats.green[at] = float(green);
      stats.blue[at] = float(blue);
    }
  }
  return stats;
}

float edge_cost_bound(const EdgeStats& right, int a, const EdgeStats& left, int b,
                      bool binary_alpha) {
  float bound = 0.0f;
  for (int block = 0; block < right.blocks; ++block) {
    const std::size_t ra = std::size_t(block) * right.count + a;
    const std::size_t lb = std::size_t(block) * left.count + b;
    const float dr = right.red[ra] - left.red[lb], dg = right.green[ra] - left.green[lb];
    const float db = right.blue[ra] - left.blue[lb];
    const float colour = 16.0f * std::sqrt(dr * dr + dg * dg + db * db) - right.block_size[block];
    if (binary_alpha) {
      const float mismatch = std::fabs(right.opaque[ra] - left.opaque[lb]);
      bound += std::max(float(kGamma) * mismatch, colour + kMismatchExtra * mismatch);
    } else {
      bound += std::max(colour, 0.0f);
    }
  }
  return bound * (1.0f - 1e-5f) - 1.0f;
}

}  // namespace tw::detail
