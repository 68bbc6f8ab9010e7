#include "synth/render.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "raster/footprint.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/stitch.hpp"

namespace tw {
namespace {

// Bilinear read of every channel at relative coordinates q of a placement (texel centres at
// +0.5, transparent zeros outside): alpha-weighted channel sums into `values` (16 floats,
// overwritten) and the alpha into `alpha_out`.
void read_texels(const Exemplar& e, const Placement& p, Vec2 q, int alpha, float* values,
                 float& alpha_out) {
  const double fx0 = std::floor(q.x - 0.5), fy0 = std::floor(q.y - 0.5);
  const float fx = float(q.x - 0.5 - fx0), fy = float(q.y - 0.5 - fy0);
  const int x0 = int(fx0) + p.ux, y0 = int(fy0) + p.uy;
  const int n = e.channel_count();
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int xs[4] = {x0, x0 + 1, x0, x0 + 1}, ys[4] = {y0, y0, y0 + 1, y0 + 1};
  float a = 0.0f;
  std::fill_n(values, 16, 0.0f);
  for (int t = 0; t < 4; ++t) {
    if (xs[t] < 0 || ys[t] < 0 || xs[t] >= e.width || ys[t] >= e.height || w[t] == 0.0f) continue;
    const float* texel = e.texels.data() + (std::size_t(ys[t]) * e.width + xs[t]) * n;
    const float ta = texel[alpha] * w[t];
    a += ta;
    for (int c = 0; c < n && c < 16; ++c) values[c] += texel[c] * ta;
  }
  alpha_out = a;
}

// The seam after piece i: the line through its right edge, with the unit normal pointing
// forward (into piece i + 1).
struct Seam {
  Vec2 at, normal;
  double signed_distance(Vec2 w) const { return dot(w - at, normal); }
};

Seam seam_after(const Piece& piece) {
  Vec2 normal = normalized(perp(piece.bottom_right - piece.top_right));
  if (dot(normal, piece.top_right - piece.top_left) < 0.0) normal = -normal;
  return {piece.top_right, normal};
}

// Weight of the neighbour across a seam at distance |d| (metres): 1/2 on the seam, falling
// smoothly to 0 at `feather`, so both sides agree on the seam.
double neighbour_weight(double d, double feather) {
  const double s = std::clamp(std::abs(d) / feather, 0.0, 1.0);
  return 0.5 * (1.0 - s * s * (3.0 - 2.0 * s));
}

}  // namespace

RenderedPattern render_pattern(const Exemplar& exemplar, const Ribbon& ribbon,
                               const Synthesis& synthesis, const GridSpec& canvas,
                               const Window& window, bool stitched, double feather) {
  RenderedPattern out;
  out.window = window;
  out.coverage = Raster<float>(window.width, window.height, 0.0f);
  const int channels = std::min(exemplar.channel_count(), 16);
  const int alpha = exemplar.channel_index("A");
  const double scale = synthesis.placements.empty() ? 1.0 : synthesis.placements[0].scale;
  const int n = detail::supersampling(scale, canvas);
  // Which piece owns each pixel's subsamples: the lowest index containing it.
  std::vector<std::int32_t> owner(std::size_t(window.width) * window.height * n * n, -1);
  for (std::size_t i = 0; i < ribbon.pieces.size() && i < synthesis.placements.size(); ++i) {
    const Piece& piece = ribbon.pieces[i];
    const PieceBox box = piece_pixel_box(piece, canvas);
    const double min_x = box.lo.x, min_y = box.lo.y, max_x = box.hi.x, max_y = box.hi.y;
    const int c0 = std::max(window.col0, int(std::floor(min_x)) - 1);
    const int c1 = std::min(window.col_end() - 1, int(std::floor(max_x)) + 1);
    const int r0 = std::max(window.row0, int(std::floor(min_y)) - 1);
    const int r1 = std::min(window.row_end() - 1, int(std::floor(max_y)) + 1);
    for (int row = r0; row <= r1; ++row)
      for (int col = c0; col <= c1; ++col)
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < n; ++k) {
            auto& o =
                owner[((std::size_t(row - window.row0) * window.width + (col - window.col0)) * n +
                       j) *
                          n +
                      k];
            if (o < 0 && detail::piece_winding(
                             piece, detail::subsample_world(canvas, col, row, k, j, n)) != 0)
              o = std::int32_t(i);
          }
  }
  std::vector<Raster<float>> bands(std::size_t(channels),
                                   Raster<float>(window.width, window.height, 0.0f));
  const int pieces = int(std::min(ribbon.pieces.size(), synthesis.placements.size()));
  // The neighbour across a seam, or -1 (curve ends, empty pieces).
  auto neighbour = [&](int i, int step) {
    int j = i + step;
    if (ribbon.closed) j = (j + pieces) % pieces;
    if (j < 0 || j >= pieces || j == i || synthesis.placements[std::size_t(j)].empty) return -1;
    return j;
  };
  tbb::parallel_for(0, window.height, [&](int r) {
    float sums[16], own[16], other[16];
    for (int c = 0; c < window.width; ++c) {
      std::fill_n(sums, 16, 0.0f);
      float alpha_sum = 0.0f;
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          const std::int32_t i = owner[((std::size_t(r) * window.width + c) * n + j) * n + k];
          if (i < 0) continue;
          const Placement& p = synthesis.placements[std::size_t(i)];
          if (p.empty) continue;
          const Vec2 w = detail::subsample_world(canvas, c + window.col0, r + window.row0, k, j, n);
          const Vec2 q =
              detail::placement_to_relative(p, ribbon.pieces[std::size_t(i)], w, stitched);
          float a = 0.0f;
          read_texels(exemplar, p, q, alpha, own, a);
          alpha_sum += a;
          // Feathering: within `feather` metres of a seam the channels (never the coverage)
          // blend with the neighbour's exemplar read on, so heights and colours meet halfway.
          double own_weight = 1.0;
          for (const int step : {-1, 1}) {
            const int m = feather > 0.0 && a > 0.0f ? neighbour(i, step) : -1;
            if (m < 0) continue;
            const Seam seam = seam_after(ribbon.pieces[std::size_t(step < 0 ? m : i)]);
            const double weight = neighbour_weight(seam.signed_distance(w), feather);
            if (weight <= 0.0) continue;
            const Placement& pm = synthesis.placements[std::size_t(m)];
            float am = 0.0f;
            read_texels(
                exemplar, pm,
                detail::placement_to_relative(pm, ribbon.pieces[std::size_t(m)], w, stitched),
                alpha, other, am);
            if (am <= 0.0f) continue;  // transparent there: nothing to meet
            own_weight -= weight;
            const float scale = float(weight) * a / am;  // the neighbour's mean, at our alpha
            for (int ch = 0; ch < channels; ++ch) sums[ch] += other[ch] * scale;
          }
          for (int ch = 0; ch < channels; ++ch) sums[ch] += own[ch] * float(own_weight);
        }
      const float coverage = alpha_sum / float(n * n);
      out.coverage.at(c, r) = coverage;
      for (int ch = 0; ch < channels; ++ch)
        bands[std::size_t(ch)].at(c, r) =
            ch == alpha ? coverage : (alpha_sum > 0.0f ? sums[ch] / alpha_sum : 0.0f);
    }
  });
  out.channels = std::move(bands);
  return out;
}

Raster<float> render_cage(const Ribbon& ribbon, const GridSpec& canvas, const Window& window) {
  Raster<float> cage(window.width, window.height, 0.0f);
  auto segment = [&](Vec2 a, Vec2 b) {
    const Vec2 pa = canvas.world_to_pixel(a), pb = canvas.world_to_pixel(b);
    const int steps = std::max(1, int(std::ceil(length(pb - pa) * 2.0)));
    for (int s = 0; s <= steps; ++s) {
      const Vec2 p = lerp(pa, pb, double(s) / steps);
      const int col = int(std::floor(p.x)) - window.col0, row = int(std::floor(p.y)) - window.row0;
      if (cage.inside(col, row)) cage.at(col, row) = 1.0f;
    }
  };
  for (const Piece& p : ribbon.pieces) {
    segment(p.top_left, p.bottom_left);
    segment(p.bottom_left, p.bottom_right);
    segment(p.bottom_right, p.top_right);
    segment(p.top_right, p.top_left);
  }
  return cage;
}

std::int64_t count_avoidance_violations(const RenderedPattern& pattern,
                                        const SparseRaster<std::uint8_t>& forbidden) {
  std::int64_t count = 0;
  const Window& w = pattern.window;
  for (int r = 0; r < w.height; ++r)
    for (int c = 0; c < w.width; ++c)
      if (forbidden.at(c + w.col0, r + w.row0) && pattern.coverage.at(c, r) >= 0.5f) ++count;
  return count;
}

}  // namespace tw
