#pragma once
// Small generated exemplars and canvases shared by the synth tests.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/grid.hpp"
#include "ribbon/ribbon.hpp"
#include "synth/exemplar.hpp"

namespace tw::test {

// A horizontal band (rows row0..row1) of random colours, with transparent gaps every `gap`
// columns (0: none), on a transparent background. Channels R, G, B, A, height.
inline Exemplar band_exemplar(int W, int H, int row0, int row1, unsigned seed, int gap = 0) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.1f, 0.9f);
  std::vector<float> t(std::size_t(W) * H * 5, 0.0f);
  for (int x = 0; x < W; ++x) {
    if (gap > 0 && x % gap == gap - 1) continue;
    const float r = u(rng), g = u(rng), b = u(rng);
    for (int y = row0; y <= row1; ++y) {
      float* p = t.data() + (std::size_t(y) * W + x) * 5;
      p[0] = r, p[1] = g, p[2] = b, p[3] = 1.0f, p[4] = 0.25f * float(y);
    }
  }
  return make_exemplar(W, H, {"R", "G", "B", "A", "height"}, std::move(t), "band(test)");
}

// A chain: alternating ring links (seen from above) and flat links (seen from the side)
// along the middle row, `period` texels per pair of links. Channels R, G, B, A.
inline Exemplar chain_exemplar(int W, int H, int period = 24) {
  std::vector<float> t(std::size_t(W) * H * 4, 0.0f);
  const double cy = H / 2.0;
  for (int y = 0; y < H; ++y) {
    for (int x = 0; x < W; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      float* p = t.data() + (std::size_t(y) * W + x) * 4;
      for (int link = -1; link <= W / (period / 2) + 1; ++link) {
        const double cx = link * period / 2.0;
        const double rx = period * 0.42, ry = link % 2 == 0 ? H * 0.30 : H * 0.08;
        const double d = std::hypot((px - cx) / rx, (py - cy) / ry);
        const bool ring = link % 2 == 0 ? (d <= 1.0 && d >= 0.55) : d <= 1.0;
        if (ring && px > 2 && px < W - 2) {
          const float shade = link % 2 == 0 ? 0.75f : 0.45f;
          p[0] = shade, p[1] = shade * 0.95f, p[2] = shade * 0.85f + 0.1f * float(py / H), p[3] = 1;
        }
      }
    }
  }
  return make_exemplar(W, H, {"R", "G", "B", "A"}, std::move(t), "chain(test)");
}

// A canvas of square pixels covering the ribbon with a margin.
inline GridSpec canvas_around(const Ribbon& ribbon, double pixel, double margin) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const Piece& p : ribbon.pieces)
    for (Vec2 v : {p.top_left, p.bottom_left, p.bottom_right, p.top_right}) {
      x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
      y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    }
  GridSpec g;
  g.origin_x = x0 - margin;
  g.origin_y = y1 + margin;
  g.pixel_width = g.pixel_height = pixel;
  g.width = int(std::ceil((x1 - x0 + 2 * margin) / pixel));
  g.height = int(std::ceil((y1 - y0 + 2 * margin) / pixel));
  return g;
}

}  // namespace tw::test
