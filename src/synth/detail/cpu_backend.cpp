#include "synth/detail/cpu_backend.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>

#include "synth/detail/cost.hpp"
#include "synth/detail/edge_bound.hpp"
#include "synth/detail/group_scan.hpp"
#include "synth/detail/mask_groups.hpp"
#include "synth/detail/opaque_count.hpp"

namespace tw::detail {
namespace {

constexpr std::int64_t kNoCost = std::numeric_limits<std::int64_t>::max();
constexpr std::int32_t kNoIndex = std::numeric_limits<std::int32_t>::max();

int column_count(const ColumnSet& set) {
  return set.column > 0 ? int(set.samples.size() / std::size_t(set.column)) : 0;
}

// The exemplar surrounded by a transparent black border wide enough for every read of a stage,
// so the per-position loops need no bounds checks (texel_at's "outside reads as transparent
// black" holds by construction).
template <class T>
struct PaddedPlane {
  int left = 0, top = 0, stride = 0;  // border widths and row length
  std::vector<T> values;
  const T* at(int x, int y) const {
    return values.data() + std::size_t(y + top) * stride + (x + left);
  }
};

// Reads at texel (ux + dx, uy + dy) for ux in [0, W), uy in [-C, H) and dx in [dx0, dx1],
// dy in [dy0, dy1]; `value` converts a packed texel.
template <class T, class Convert>
PaddedPlane<T> padded_plane(const CostTexels& texels, const PositionSpace& space, int dx0, int dx1,
                            int dy0, int dy1, Convert value) {
  PaddedPlane<T> plane;
  plane.left = std::max(0, -dx0);
  plane.top = std::max(0, space.column - dy0);
  const int right = std::max(0, space.width - 1 + dx1 - (texels.width - 1));
  const int bottom = std::max(0, space.height - 1 + dy1 - (texels.height - 1));
  plane.stride = plane.left + texels.width + right;
  plane.values.assign(std::size_t(plane.stride) * (plane.top + texels.height + bottom), T{});
  for (int y = 0; y < texels.height; ++y)
    for (int x = 0; x < texels.width; ++x)
      plane.values[std::size_t(y + plane.top) * plane.stride + x + plane.left] =
          value(texels.rgba[std::size_t(y) * texels.width + x]);
  return plane;
}

// A texel's channels spread over 32-bit lanes (R, G in `low`; B, A in `high`), so that one 64-bit
// multiply weighs two channels: weight * channel <= 65536 * 255 < 2^32 never carries over.
struct SpreadTexel {
  std::uint64_t low = 0, high = 0;
};
SpreadTexel spread(std::uint32_t t) {
  return {std::uint64_t(t & 255u) | std::uint64_t((t >> 8) & 255u) << 32,
          std::uint64_t((t >> 16) & 255u) | std::uint64_t(t >> 24) << 32};
}

// One right-edge sample of a piece relative to its position: the top-left texel of its 2 x 2
// (as an offset in the padded plane) and the four weights, the same for every position since
// positions are whole texels.
struct BilinearTap {
  std::ptrdiff_t offset = 0;
  std::uint64_t w00 = 0, w10 = 0, w01 = 0, w11 = 0;
};

BilinearTap bilinear_tap(const PaddedPlane<SpreadTexel>& plane, std::int32_t X, std::int32_t Y) {
  const std::uint64_t fx = std::uint64_t(X & 255), fy = std::uint64_t(Y & 255);
  return {std::ptrdiff_t(Y >> 8) * plane.stride + (X >> 8), (256 - fx) * (256 - fy),
          fx * (256 - fy), (256 - fx) * fy, fx * fy};
}

// sample_bilinear of cost.hpp on a padded plane, `row0` at the position's texel: the same
// fixed-point formula, bit for bit (each channel (sum of weight * value + 2^15) >> 16), two
// channels per multiply.
std::uint32_t bilinear_padded(const SpreadTexel* row0, std::ptrdiff_t stride,
                              const BilinearTap& tap) {
  row0 += tap.offset;
  const SpreadTexel* row1 = row0 + stride;
  const std::uint64_t w00 = tap.w00, w10 = tap.w10, w01 = tap.w01, w11 = tap.w11;
  constexpr std::uint64_t kHalf = 32768u | std::uint64_t(32768u) << 32;
  const std::uint64_t low =
      (row0[0].low * w00 + row0[1].low * w10 + row1[0].low * w01 + row1[1].low * w11 + kHalf) >> 16;
  const std::uint64_t high =
      (row0[0].high * w00 + row0[1].high * w10 + row1[0].high * w01 + row1[1].high * w11 + kHalf) >>
      16;
  return std::uint32_t((low & 255u) | ((low >> 32) & 255u) << 8 | (high & 255u) << 16 |
                       ((high >> 32) & 255u) << 24);
}

template <class Offsets, class Dx, class Dy>
void offset_extent(const Offsets& offsets, Dx dx, Dy dy, int& dx0, int& dx1, int& dy0, int& dy1) {
  for (const auto& o : offsets) {
    dx0 = std::min(dx0, dx(o)), dx1 = std::max(dx1, dx(o));
    dy0 = std::min(dy0, dy(o)), dy1 = std::max(dy1, dy(o));
  }
}

class CpuBackend final : public Backend {
 public:
  std::string name() const override { return "cpu"; }

  // Bit-parallel: 64 positions of a row of u at once. For every offset, the opaque bits of the
  // texels under those 64 positions are one unaligned 64-bit window of a bit row of the padded
  // exemplar; a position is blocked by any clear-required opaque bit and needs one interior one.
  void find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                            const PieceFootprint& piece,
                            std::vector<std::uint8_t>& flags) override {
    flags.assign(std::size_t(space.count()), 0);
    int dx0 = 0, dx1 = 0, dy0 = 0, dy1 = 0;
    auto dx = [](const TexelOffset& o) { return o.dx; };
    auto dy = [](const TexelOffset& o) { return o.dy; };
    offset_extent(piece.must_be_clear, dx, dy, dx0, dx1, dy0, dy1);
    offset_extent(piece.interior, dx, dy, dx0, dx1, dy0, dy1);
    const PaddedPlane<std::uint8_t> opaque = padded_plane<std::uint8_t>(
        texels, space, dx0, dx1 + 64, dy0, dy1,
        [](std::uint32_t t) { return std::uint8_t(is_opaque(t) ? 1 : 0); });
    const int rows = int(opaque.values.size() / std::size_t(opaque.stride));
    const int words = (opaque.stride + 63) / 64 + 1;
    std::vector<std::uint64_t> bits(std::size_t(rows) * words, 0);
    for (int y = 0; y < rows; ++y)
      for (int x = 0; x < opaque.stride; ++x)
        if (opaque.values[std::size_t(y) * opaque.stride + x])
          bits[std::size_t(y) * words + x / 64] |= std::uint64_t(1) << (x % 64);
    // Offsets as (bit row, bit column) of the window of position (0, 0) of a row of u.
    auto windows = [&](const std::vector<TexelOffset>& offsets) {
      std::vector<std::pair<int, int>> out;
      for (const TexelOffset& o : offsets) out.emplace_back(o.dy + opaque.top, o.dx + opaque.left);
      return out;
    };
    const auto clear = windows(piece.must_be_clear), interior = windows(piece.interior);
    // min_opaque > 1: count the opaque interior texels of each remaining candidate (the
    // counter the unary term uses too).
    std::optional<OpaqueCounter> counter;
    if (piece.min_opaque > 1) {
      counter.emplace(texels);
      counter->set_interior(piece.interior);
    }
    const int rows_of_u = space.height + space.column, blocks = (space.width + 63) / 64;
    tbb::parallel_for(tbb::blocked_range<int>(0, rows_of_u, 4), [&](auto range) {
      for (int row = range.begin(); row < range.end(); ++row) {
        const int uy = row - space.column;
        for (int b = 0; b < blocks; ++b) {
          const int in_row = std::min(64, space.width - 64 * b);
          const std::uint64_t all =
              in_row == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << in_row) - 1;
          auto window = [&](const std::pair<int, int>& w) {
            const int x = 64 * b + w.second;
            const std::uint64_t* at = bits.data() + std::size_t(uy + w.first) * words + x / 64;
            const int shift = x % 64;
            return shift ? (at[0] >> shift) | (at[1] << (64 - shift)) : at[0];
          };
          std::uint64_t blocked = 0;
          for (const auto& w : clear)
            if (((blocked |= window(w)) & all) == all) break;
          const std::uint64_t open = all & ~blocked;
          if (!open) continue;
          std::uint64_t any = 0;
          for (const auto& w : interior)
            if (((any |= window(w)) & open) == open) break;
          for (std::uint64_t valid = open & any; valid; valid &= valid - 1) {
            const int ux = 64 * b + std::countr_zero(valid);
            if (counter && counter->count(ux, uy) < piece.min_opaque) continue;
            flags[std::size_t(row) * space.width + ux] = 1;
          }
        }
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
    // Sample k reads texels (x0, y0) .. (x0 + 1, y0 + 1), x0 = ux + ((fx - 128) >> 8).
    int dx0 = 0, dx1 = 0, dy0 = 0, dy1 = 0;
    for (int k = 0; k < C; ++k) {
      dx0 = std::min(dx0, (piece.right_fx[k] - 128) >> 8);
      dx1 = std::max(dx1, ((piece.right_fx[k] - 128) >> 8) + 1);
      dy0 = std::min(dy0, (piece.right_fy[k] - 128) >> 8);
      dy1 = std::max(dy1, ((piece.right_fy[k] - 128) >> 8) + 1);
    }
    const PaddedPlane<SpreadTexel> plane =
        padded_plane<SpreadTexel>(texels, space, dx0, dx1, dy0, dy1, spread);
    std::vector<BilinearTap> taps(static_cast<std::size_t>(C));
    for (int k = 0; k < C; ++k)
      taps[std::size_t(k)] = bilinear_tap(plane, piece.right_fx[k] - 128, piece.right_fy[k] - 128);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, indices.size(), 64), [&](auto range) {
      for (std::size_t j = range.begin(); j < range.end(); ++j) {
        const SpreadTexel* corner = plane.at(space.ux(indices[j]), space.uy(indices[j]));
        std::uint32_t* column = out.samples.data() + j * C;
        for (int k = 0; k < C; ++k)
          column[k] = bilinear_padded(corner, plane.stride, taps[std::size_t(k)]);
      }
    });
  }

  void extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<std::int32_t>& indices, ColumnSet& out) override {
    const int C = space.column;
    out.column = C;
    out.binary_alpha = texels.binary_alpha;
    out.samples.resize(indices.size() * std::size_t(C));
    const PaddedPlane<std::uint32_t> plane = padded_plane<std::uint32_t>(
        texels, space, 0, 0, 0, C - 1, [](std::uint32_t t) { return t; });
    // Column-major copy: each left edge is then one contiguous run of C texels.
    const std::size_t rows = plane.values.size() / std::size_t(plane.stride);
    std::vector<std::uint32_t> by_column(plane.values.size());
    for (std::size_t y = 0; y < rows; ++y)
      for (std::size_t x = 0; x < std::size_t(plane.stride); ++x)
        by_column[x * rows + y] = plane.values[y * std::size_t(plane.stride) + x];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, indices.size(), 256), [&](auto range) {
      for (std::size_t j = range.begin(); j < range.end(); ++j) {
        const std::size_t x = std::size_t(space.ux(indices[j]) + plane.left);
        const std::size_t y = std::size_t(space.uy(indices[j]) + plane.top);
        std::copy_n(by_column.data() + x * rows + y, C, out.samples.data() + j * C);
      }
    });
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

namespace {

// The previous positions of a row regrouped for the pruned update: grouped by exact opaque mask
// (alpha >= 128), groups in increasing min P, members in increasing (P, v),
// their samples and statistics contiguous in that "slot" order.
struct PreviousByMask {
  MaskGroups groups;                    // slot order, groups and their masks
  std::vector<std::int64_t> cost;       // slot -> P[v]
  std::vector<std::uint32_t> samples;   // C per slot
  EdgeStats stats;                      // per slot
  std::vector<std::int64_t> group_min;  // P of the first slot of each group
  std::vector<std::int32_t> slot_of;    // v -> slot
};

PreviousByMask group_by_mask(const std::vector<std::int64_t>& previous_cost,
                             const ColumnSet& right) {
  const int previous = int(previous_cost.size());
  const int C = right.column;
  const EdgeStats by_position = make_edge_stats(right);
  PreviousByMask out;
  out.groups =
      tw::detail::group_by_mask(previous_cost, by_position.masks.data(), by_position.words);
  out.cost.resize(out.groups.position.size());
  out.samples.resize(out.groups.position.size() * std::size_t(C));
  out.slot_of.resize(out.groups.position.size());
  for (int s = 0; s < previous; ++s) {
    const std::int32_t v = out.groups.position[std::size_t(s)];
    out.cost[std::size_t(s)] = previous_cost[std::size_t(v)];
    out.slot_of[std::size_t(v)] = s;
    std::copy_n(right.samples.data() + std::size_t(v) * C, C,
                out.samples.data() + std::size_t(s) * C);
  }
  out.stats = permute_edge_stats(by_position, out.groups.position);
  for (int g = 0; g + 1 < int(out.groups.group_begin.size()); ++g)
    out.group_min.push_back(out.cost[std::size_t(out.groups.group_begin[std::size_t(g)])]);
  return out;
}

}  // namespace

void update_table_row_pruned(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                             const ColumnSet& left, std::vector<std::int64_t>& cost,
                             std::vector<std::int32_t>& argmin, std::int64_t* pairs_evaluated) {
  const int C = left.column;
  const int count = column_count(left);
  const int previous = int(previous_cost.size());
  const bool binary = left.binary_alpha;
  const std::int64_t mismatch = mismatch_cost(binary);
  cost.assign(std::size_t(count), kNoCost);
  argmin.assign(std::size_t(count), -1);
  if (pairs_evaluated) *pairs_evaluated = 0;
  if (previous == 0 || count == 0) return;

  const PreviousByMask prev = group_by_mask(previous_cost, right);
  const EdgeStats left_stats = make_edge_stats(left);
  const GroupScan scan(prev.group_min, prev.groups.group_masks, left_stats.words, mismatch);
  const std::int64_t min_cost = prev.cost[0];
  std::atomic<std::int64_t> evaluated{0};

  tbb::parallel_for(tbb::blocked_range<int>(0, count, 32), [&](auto range) {
    std::int64_t local_evaluated = 0;
    std::int32_t neighbour = -1;  // argmin of the previous j in this task
    for (int j = range.begin(); j < range.end(); ++j) {
      const std::uint32_t* left_samples = left.samples.data() + std::size_t(j) * C;
      std::int64_t best = kNoCost;
      std::int32_t best_v = kNoIndex;
      // Considers slot s (m mismatched samples); false once P alone exceeds the best, so that
      // no later slot of an increasing-P walk can win.
      auto consider = [&](int s, int m) {
        const std::int64_t p = prev.cost[std::size_t(s)];
        if (p > best) return false;
        const std::int32_t v = prev.groups.position[std::size_t(s)];
        const std::int64_t limit = best - p - (v > best_v ? 1 : 0);  // ties go to the lowest v
        if (limit < 0) return true;
        if (best_v != kNoIndex) {
          if (mismatch * m > limit) return true;
          if (whole_edge_bound_exceeds(prev.stats, s, left_stats, j, m, limit)) return true;
          if (double(block_colour_bound(prev.stats, s, left_stats, j)) > double(limit)) return true;
        }
        ++local_evaluated;
        const std::int64_t d = edge_cost_capped(prev.samples.data() + std::size_t(s) * C,
                                                left_samples, C, binary, limit);
        if (d <= limit) {  // strictly better, or equal with a lower v
          best = p + d;
          best_v = v;
        }
        return true;
      };
      // A good first guess makes the bounds prune from the start: consecutive current positions
      // are usually exemplar neighbours, and so are their optimal predecessors. Exact
      // regardless: a guess is only a real candidate evaluated early.
      if (neighbour >= 0) {
        for (std::int32_t v : {neighbour, neighbour + 1}) {
          if (v >= previous) continue;
          const int s = prev.slot_of[std::size_t(v)];
          consider(s, mismatched_samples(prev.stats, s, left_stats, j));
        }
      }
      // The group of j's own mask: no mismatched sample (binary alpha: D is colours only).
      const int own =
          group_with_mask(prev.groups, left_stats.masks.data() + std::size_t(j) * left_stats.words);
      if (own >= 0)
        for (int s = prev.groups.group_begin[std::size_t(own)];
             s < prev.groups.group_begin[std::size_t(own) + 1]; ++s)
          if (!consider(s, 0)) break;
      // Every other group has m >= 1 mismatched samples, so D >= mismatch * m: visit groups
      // (in increasing min P) only while min P + mismatch * m can still win, 64 groups tested
      // at a time against the best so far (it only falls, so each test keeps a superset).
      if (own < 0 || best - min_cost >= mismatch) {
        const std::uint64_t* key = left_stats.masks.data() + std::size_t(j) * left_stats.words;
        for (int g0 = 0; g0 < scan.groups(); g0 += 64) {
          if (prev.group_min[std::size_t(g0)] + mismatch > best) break;
          std::uint64_t open = scan.qualifying(key, g0, best);
          if (own >= g0 && own < g0 + 64) open &= ~(std::uint64_t(1) << (own - g0));
          for (; open; open &= open - 1) {
            const int g = g0 + std::countr_zero(open);
            const int begin = prev.groups.group_begin[std::size_t(g)];
            const int end = prev.groups.group_begin[std::size_t(g) + 1];
            if (prev.cost[std::size_t(begin)] + mismatch > best) break;
            const int m = mismatched_samples(prev.stats, begin, left_stats, j);
            const std::int64_t gap = mismatch * m;
            for (int s = begin; s < end && prev.cost[std::size_t(s)] + gap <= best; ++s)
              if (!consider(s, m)) break;
          }
        }
      }
      cost[std::size_t(j)] = best;
      argmin[std::size_t(j)] = best_v;
      neighbour = best_v;
    }
    evaluated += local_evaluated;
  });
  if (pairs_evaluated) *pairs_evaluated = evaluated.load();
}

}  // namespace tw::detail
