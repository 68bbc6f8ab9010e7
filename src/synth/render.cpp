#include "synth/render.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "synth/detail/footprint.hpp"
#include "synth/detail/stitch.hpp"

namespace tw {
namespace {

// Bilinear read of every channel at relative coordinates q of a placement (texel centres at
// +0.5, transparent zeros outside), accumulated alpha-weighted into `sums`.
void accumulate(const Exemplar& e, const Placement& p, Vec2 q, int alpha, float* sums,
                float& alpha_sum) {
  const double fx0 = std::floor(q.x - 0.5), fy0 = std::floor(q.y - 0.5);
  const float fx = float(q.x - 0.5 - fx0), fy = float(q.y - 0.5 - fy0);
  const int x0 = int(fx0) + p.ux, y0 = int(fy0) + p.uy;
  const int n = e.channel_count();
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int xs[4] = {x0, x0 + 1, x0, x0 + 1}, ys[4] = {y0, y0, y0 + 1, y0 + 1};
  float a = 0.0f;
  float values[16] = {};
  for (int t = 0; t < 4; ++t) {
    if (xs[t] < 0 || ys[t] < 0 || xs[t] >= e.width || ys[t] >= e.height || w[t] == 0.0f) continue;
    const float* texel = e.texels.data() + (std::size_t(ys[t]) * e.width + xs[t]) * n;
    const float ta = texel[alpha] * w[t];
    a += ta;
    for (int c = 0; c < n && c < 16; ++c) values[c] += texel[c] * ta;
  }
  alpha_sum += a;
  for (int c = 0; c < n && c < 16; ++c) sums[c] += values[c];
}

}  // namespace

RenderedPattern render_pattern(const Exemplar& exemplar, const Ribbon& ribbon,
                               const Synthesis& synthesis, const GridSpec& canvas,
                               const Window& window, bool stitched) {
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
    double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
    for (const Vec2& w : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right}) {
      const Vec2 p = canvas.world_to_pixel(w);
      min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
      min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
    }
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
  tbb::parallel_for(0, window.height, [&](int r) {
    float sums[16];
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
          accumulate(exemplar, p, q, alpha, sums, alpha_sum);
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
                                        const Raster<std::uint8_t>& forbidden) {
  std::int64_t count = 0;
  const Window& w = pattern.window;
  for (int r = 0; r < w.height; ++r)
    for (int c = 0; c < w.width; ++c)
      if (forbidden.inside(c + w.col0, r + w.row0) && forbidden.at(c + w.col0, r + w.row0) &&
          pattern.coverage.at(c, r) >= 0.5f)
        ++count;
  return count;
}

}  // namespace tw
