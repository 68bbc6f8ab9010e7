#include "synth/detail/stitch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "synth/detail/cost.hpp"

namespace tw::detail {

std::vector<int> align_edges(const std::uint32_t* right, const std::uint32_t* left, int count,
                             bool binary_alpha, std::int64_t penalty) {
  const int C = count;
  std::vector<std::int64_t> M(std::size_t(C) * C);
  auto at = [&](int s, int t) -> std::int64_t& { return M[std::size_t(s) * C + t]; };
  auto cell = [&](int s, int t) { return std::int64_t(xi(right[t], left[s], binary_alpha)); };
  auto beta = [&](int s, int t) {
    return (alpha_of(left[s]) > 0 || alpha_of(right[t]) > 0) ? penalty : 0;
  };
  for (int s = 0; s < C; ++s) {
    for (int t = 0; t < C; ++t) {
      std::int64_t best = std::numeric_limits<std::int64_t>::max();
      if (s == 0 && t == 0) best = 0;
      if (s > 0 && t > 0) best = std::min(best, at(s - 1, t - 1));
      if (s > 0) best = std::min(best, at(s - 1, t) + beta(s, t));
      if (t > 0) best = std::min(best, at(s, t - 1) + beta(s, t));
      at(s, t) = best + cell(s, t);
    }
  }
  // Backtrack; per row keep the cheapest cell visited.
  std::vector<int> T(std::size_t(C), -1);
  std::vector<std::int64_t> T_cost(std::size_t(C), std::numeric_limits<std::int64_t>::max());
  int s = C - 1, t = C - 1;
  while (true) {
    const std::int64_t c = cell(s, t);
    if (c < T_cost[s] || (c == T_cost[s] && t < T[s])) T_cost[s] = c, T[s] = t;
    if (s == 0 && t == 0) break;
    const std::int64_t here = at(s, t) - c;
    if (s > 0 && t > 0 && at(s - 1, t - 1) == here) {
      --s, --t;
    } else if (s > 0 && at(s - 1, t) + beta(s, t) == here) {
      --s;
    } else {
      --t;
    }
  }
  return T;
}

Vec2 placement_to_relative(const Placement& p, const Piece& piece, Vec2 world, bool stitched) {
  auto rel = [&](Vec2 w) {
    const Vec2 d = w - p.origin;
    return Vec2{p.scale * dot(d, p.along), p.scale * dot(d, p.across)};  // without the +0.5
  };
  Vec2 q = rel(world);
  if (stitched && !p.stitch.empty()) {
    const double left_length = rel(piece.bottom_left).y;
    const Vec2 top = rel(piece.top_right), bottom = rel(piece.bottom_right);
    const Vec2 edge = bottom - top;
    const double f = std::clamp(q.y / left_length, 0.0, 1.0);
    const Vec2 direction = lerp(top, bottom - Vec2{0.0, left_length}, f);
    const double denominator = cross(edge, direction);
    if (std::fabs(denominator) > 1e-12 && std::fabs(direction.x) > 1e-12) {
      const double mu = cross(q - top, direction) / denominator;
      const double lambda = cross(q - top, edge) / denominator;  // to the right edge
      const double kappa = q.x / direction.x;                    // from the left edge
      if (kappa + lambda > 1e-12) {
        const double weight = std::clamp(kappa / (kappa + lambda), 0.0, 1.0);
        const int C = int(p.stitch.size());
        const double i = std::clamp(mu * left_length - 0.5, 0.0, double(C - 1));
        const int i0 = std::min(int(i), C - 1), i1 = std::min(i0 + 1, C - 1);
        const double ti = p.stitch[i0] + (p.stitch[i1] - p.stitch[i0]) * (i - i0);
        q += edge * (weight * (ti - i) / left_length);
      }
    }
  }
  return {q.x + 0.5, q.y};
}

Vec2 placement_to_exemplar(const Placement& p, const Piece& piece, Vec2 world, bool stitched) {
  return placement_to_relative(p, piece, world, stitched) + Vec2{double(p.ux), double(p.uy)};
}

}  // namespace tw::detail
