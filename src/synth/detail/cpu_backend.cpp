#include "synth/detail/cpu_backend.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

#include "synth/detail/cost.hpp"
#include "synth/detail/edge_bound.hpp"

namespace tw::detail {
namespace {

constexpr std::int64_t kNoCost = std::numeric_limits<std::int64_t>::max();
constexpr std::int32_t kNoIndex = std::numeric_limits<std::int32_t>::max();
constexpr int kChunk = 64;  // previous positions bounded together (a vectorizable loop)

int column_count(const ColumnSet& set) {
  return set.column > 0 ? int(set.samples.size() / std::size_t(set.column)) : 0;
}

// Lexicographic (cost, index) improvement.
bool improves(std::int64_t cost, std::int32_t index, std::int64_t best, std::int32_t best_index) {
  return cost < best || (cost == best && index < best_index);
}

// D with early exit: returns a value > limit as soon as the partial sum exceeds it.
std::int64_t edge_cost_capped(const std::uint32_t* right, const std::uint32_t* left, int count,
                              bool binary_alpha, std::int64_t limit) {
  std::int64_t sum = 0;
  for (int k0 = 0; k0 < count; k0 += kBoundBlock) {
    const int k1 = std::min(count, k0 + kBoundBlock);
    std::int32_t block = 0;
    for (int k = k0; k < k1; ++k) block += xi(right[k], left[k], binary_alpha);
    sum += block;
    if (sum > limit) return sum;
  }
  return sum;
}

// Lower bounds on D for `length` previous positions from r0 against current position j.
// Vectorized (clones for AVX-512 / AVX2); the bound only decides what to skip, so the
// instruction set cannot change any result.
__attribute__((target_clones("avx512f", "avx2", "default"), optimize("O3", "no-math-errno"))) void
chunk_bounds(const EdgeStats& right, const EdgeStats& left, int r0, int length, int j, bool binary,
             float* bound) {
  for (int r = 0; r < length; ++r) bound[r] = 0.0f;
  for (int b = 0; b < right.blocks; ++b) {
    const std::size_t base = std::size_t(b) * right.count + r0;
    const std::size_t at = std::size_t(b) * left.count + j;
    const float lo = left.opaque[at], lr = left.red[at], lg = left.green[at], lb = left.blue[at];
    const float size = right.block_size[b];
    const float* ro = right.opaque.data() + base;
    const float* rr = right.red.data() + base;
    const float* rg = right.green.data() + base;
    const float* rb = right.blue.data() + base;
    if (binary) {
      for (int r = 0; r < length; ++r) {
        const float dr = rr[r] - lr, dg = rg[r] - lg, db = rb[r] - lb;
        const float colour = 16.0f * std::sqrt(dr * dr + dg * dg + db * db) - size;
        const float mismatch = std::fabs(ro[r] - lo);
        bound[r] += std::max(float(kGamma) * mismatch, colour + kMismatchExtra * mismatch);
      }
    } else {
      for (int r = 0; r < length; ++r) {
        const float dr = rr[r] - lr, dg = rg[r] - lg, db = rb[r] - lb;
        bound[r] += std::max(16.0f * std::sqrt(dr * dr + dg * dg + db * db) - size, 0.0f);
      }
    }
  }
}

class CpuBackend final : public Backend {
 public:
  std::string name() const override { return "cpu"; }

  void find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                            const PieceFootprint& piece,
                            std::vector<std::uint8_t>& flags) override {
    flags.assign(std::size_t(space.count()), 0);
    tbb::parallel_for(tbb::blocked_range<std::int64_t>(0, space.count(), 256), [&](auto range) {
      for (std::int64_t index = range.begin(); index < range.end(); ++index) {
        const int ux = space.ux(index), uy = space.uy(index);
        bool valid = true;
        for (const TexelOffset& o : piece.must_be_clear) {
          if (is_opaque(texel_at(texels, ux + o.dx, uy + o.dy))) {
            valid = false;
            break;
          }
        }
        if (!valid) continue;
        bool any_opaque = false;
        for (const TexelOffset& o : piece.interior) {
          if (is_opaque(texel_at(texels, ux + o.dx, uy + o.dy))) {
            any_opaque = true;
            break;
          }
        }
        flags[std::size_t(index)] = any_opaque ? 1 : 0;
      }
    });
  }

  void compact_valid_positions(const std::vector<std::uint8_t>& flags,
                               std::vector<std::int32_t>& indices) override {
    indices.clear();
    for (std::size_t i = 0; i < flags.size(); ++i)
      if (flags[i]) indices.push_back(std::int32_t(i));
  }

  void extract_right_columns(const CostTexels& texels, const PositionSpace& space,
                             const PieceFootprint& piece, const std::vector<std::int32_t>& indices,
                             ColumnSet& out) override {
    const int C = piece.column;
    out.column = C;
    out.binary_alpha = texels.binary_alpha;
    out.samples.resize(indices.size() * std::size_t(C));
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, indices.size(), 64), [&](auto range) {
      for (std::size_t j = range.begin(); j < range.end(); ++j) {
        const std::int32_t X0 = space.ux(indices[j]) * 256 - 128;
        const std::int32_t Y0 = space.uy(indices[j]) * 256 - 128;
        for (int k = 0; k < C; ++k)
          out.samples[j * C + k] =
              sample_bilinear(texels, X0 + piece.right_fx[k], Y0 + piece.right_fy[k]);
      }
    });
  }

  void extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<std::int32_t>& indices, ColumnSet& out) override {
    const int C = space.column;
    out.column = C;
    out.binary_alpha = texels.binary_alpha;
    out.samples.resize(indices.size() * std::size_t(C));
    for (std::size_t j = 0; j < indices.size(); ++j) {
      const int ux = space.ux(indices[j]), uy = space.uy(indices[j]);
      for (int k = 0; k < C; ++k) out.samples[j * C + k] = texel_at(texels, ux, uy + k);
    }
  }

  void update_table_row(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                        const ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override {
    update_table_row_pruned(previous_cost, right, left, cost, argmin);
  }
};

}  // namespace

std::unique_ptr<Backend> make_cpu_backend() {
  return std::make_unique<CpuBackend>();
}

void update_table_row_naive(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                            const ColumnSet& left, std::vector<std::int64_t>& cost,
                            std::vector<std::int32_t>& argmin) {
  const int C = left.column;
  const int count = column_count(left);
  cost.assign(std::size_t(count), kNoCost);
  argmin.assign(std::size_t(count), -1);
  tbb::parallel_for(tbb::blocked_range<int>(0, count, 16), [&](auto range) {
    for (int j = range.begin(); j < range.end(); ++j) {
      std::int64_t best = kNoCost;
      std::int32_t best_index = -1;
      for (std::size_t v = 0; v < previous_cost.size(); ++v) {
        const std::int64_t c =
            previous_cost[v] + edge_cost(right.samples.data() + v * C,
                                         left.samples.data() + std::size_t(j) * C, C,
                                         left.binary_alpha);
        if (c < best) {  // v ascends, so strict < keeps the lowest index on ties
          best = c;
          best_index = std::int32_t(v);
        }
      }
      cost[j] = best;
      argmin[j] = best_index;
    }
  });
}

void update_table_row_pruned(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                             const ColumnSet& left, std::vector<std::int64_t>& cost,
                             std::vector<std::int32_t>& argmin, std::int64_t* pairs_evaluated) {
  const int C = left.column;
  const int count = column_count(left);
  const int previous = int(previous_cost.size());
  const bool binary = left.binary_alpha;
  cost.assign(std::size_t(count), kNoCost);
  argmin.assign(std::size_t(count), -1);
  if (previous == 0 || count == 0) return;

  // Groups by the number of opaque samples n (binary alpha; one group otherwise): a pair whose
  // counts differ by d has D >= gamma * d, so for each j groups are visited outward from its
  // own count and dropped once min P + gamma * d cannot win. Inside a group: increasing (P, v).
  auto opaque_count = [C](const std::uint32_t* samples) {
    int n = 0;
    for (int k = 0; k < C; ++k) n += is_opaque(samples[k]) ? 1 : 0;
    return n;
  };
  const int groups = binary ? C + 1 : 1;
  std::vector<int> group_of(static_cast<std::size_t>(previous), 0);
  if (binary)
    for (int v = 0; v < previous; ++v)
      group_of[std::size_t(v)] = opaque_count(right.samples.data() + std::size_t(v) * C);
  std::vector<std::int32_t> order(static_cast<std::size_t>(previous));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    if (group_of[a] != group_of[b]) return group_of[a] < group_of[b];
    return previous_cost[a] != previous_cost[b] ? previous_cost[a] < previous_cost[b] : a < b;
  });
  std::vector<int> group_begin(std::size_t(groups) + 1, previous);
  for (int r = previous - 1; r >= 0; --r) group_begin[std::size_t(group_of[order[r]])] = r;
  for (int g = groups - 1; g >= 0; --g)
    group_begin[std::size_t(g)] =
        std::min(group_begin[std::size_t(g)], group_begin[std::size_t(g) + 1]);
  std::vector<std::int64_t> sorted_cost(static_cast<std::size_t>(previous));
  std::vector<std::uint32_t> sorted_samples(static_cast<std::size_t>(previous) * C);
  std::vector<std::int32_t> rank(static_cast<std::size_t>(previous));  // v -> place in order
  for (int r = 0; r < previous; ++r) {
    sorted_cost[r] = previous_cost[order[r]];
    rank[std::size_t(order[r])] = r;
    std::copy_n(right.samples.data() + std::size_t(order[r]) * C, C,
                sorted_samples.data() + std::size_t(r) * C);
  }
  const std::int64_t min_cost = *std::min_element(previous_cost.begin(), previous_cost.end());
  const EdgeStats right_stats = make_edge_stats(right, order);
  const EdgeStats left_stats = make_edge_stats(left);
  std::atomic<std::int64_t> evaluated{0};

  tbb::parallel_for(tbb::blocked_range<int>(0, count, 32), [&](auto range) {
    float bound[kChunk];
    std::int64_t local_evaluated = 0;
    std::int32_t neighbour = -1;  // argmin of the previous j in this task
    for (int j = range.begin(); j < range.end(); ++j) {
      const std::uint32_t* left_samples = left.samples.data() + std::size_t(j) * C;
      std::int64_t best = kNoCost;
      std::int32_t best_index = kNoIndex;
      auto consider = [&](int r, std::int32_t v) {
        const std::int64_t p = sorted_cost[r];
        const std::int64_t limit = best == kNoCost ? kNoCost : best - p;
        ++local_evaluated;
        const std::int64_t d = edge_cost_capped(sorted_samples.data() + std::size_t(r) * C,
                                                left_samples, C, binary, limit);
        if (d <= limit && improves(p + d, v, best, best_index)) {
          best = p + d;
          best_index = v;
        }
      };
      // A good first guess makes the bounds prune from the start: consecutive current positions
      // are usually exemplar neighbours, and so are their optimal predecessors. Exact
      // regardless: a guess is only a real candidate evaluated early.
      if (neighbour >= 0) {
        if (neighbour + 1 < previous) consider(rank[std::size_t(neighbour) + 1], neighbour + 1);
        consider(rank[std::size_t(neighbour)], neighbour);
      }
      // Visits group g whose opaque count differs from j's by d (gap = gamma * d <= D).
      auto visit_group = [&](int g, std::int64_t gap) {
        const int end = group_begin[std::size_t(g) + 1];
        for (int r0 = group_begin[std::size_t(g)]; r0 < end && sorted_cost[r0] + gap <= best;
             r0 += kChunk) {
          const int length = std::min(kChunk, end - r0);
          chunk_bounds(right_stats, left_stats, r0, length, j, binary, bound);
          for (int r = 0; r < length; ++r) {
            const std::int64_t p = sorted_cost[r0 + r];
            if (p + gap > best) break;
            const std::int32_t v = order[r0 + r];
            const float margin_bound = bound[r] * (1.0f - 1e-5f) - 1.0f;
            const std::int64_t lower =
                p + std::max<std::int64_t>(gap, std::int64_t(std::max(0.0f, margin_bound)));
            if (lower > best || (lower == best && v > best_index)) continue;
            consider(r0 + r, v);
          }
        }
      };
      const int own = binary ? opaque_count(left_samples) : 0;
      for (int d = 0; d < groups; ++d) {
        const std::int64_t gap = binary ? std::int64_t(kGamma) * d : 0;
        if (best != kNoCost && min_cost + gap > best) break;
        if (own - d < 0 && own + d >= groups) break;
        if (own - d >= 0) visit_group(own - d, gap);
        if (d > 0 && own + d < groups) visit_group(own + d, gap);
      }
      cost[j] = best;
      argmin[j] = best_index;
      neighbour = best_index;
    }
    evaluated += local_evaluated;
  });
  if (pairs_evaluated) *pairs_evaluated = evaluated.load();
}

}  // namespace tw::detail
