#pragma once
// Exemplars that differ in kind from the drawn ones (issue #11): sparse elements, thin lines, a
// band with holes, a soft-edged alpha, a photo-like band. Deterministic on any platform: every
// irregularity comes from an integer hash. bench_quality --write-exemplars DIR saves them as the
// PNGs of samples/exemplars/ (gen_*.png), which the quality tests read.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "synth/exemplar.hpp"

namespace tw::test {

// Uniform in [0, 1) from (a, b, seed).
inline double hash01(std::uint64_t a, std::uint64_t b, std::uint64_t seed) {
  std::uint64_t x =
      a * 0x9e3779b97f4a7c15ull ^ (b + 0x632be59bd9b4e019ull) * 0xbf58476d1ce4e5b9ull ^ seed;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return double((x ^ (x >> 31)) >> 11) / double(1ull << 53);
}

struct GeneratedExemplar {
  std::string name;  // gen_<kind>_<W>x<H>
  Exemplar exemplar;
};

namespace detail_gen {
constexpr int kW = 160, kH = 48;

inline Exemplar finish(std::vector<float> rgba, const std::string& name) {
  return make_exemplar(kW, kH, {"R", "G", "B", "A"}, std::move(rgba), name);
}
inline void set(std::vector<float>& t, int x, int y, double r, double g, double b, double a) {
  if (x < 0 || y < 0 || x >= kW || y >= kH) return;
  float* p = t.data() + (std::size_t(y) * kW + x) * 4;
  p[0] = float(r), p[1] = float(g), p[2] = float(b), p[3] = float(a);
}
}  // namespace detail_gen

inline std::vector<GeneratedExemplar> generated_exemplars() {
  using namespace detail_gen;
  std::vector<GeneratedExemplar> out;
  const std::string size = std::to_string(kW) + "x" + std::to_string(kH);
  {  // sparse elements: small discs (stepping stones) every ~20 texels, jittered
    std::vector<float> t(std::size_t(kW) * kH * 4, 0.0f);
    for (int k = 0; k * 20 < kW; ++k) {
      const double cx = k * 20 + 10 + 4 * (hash01(k, 1, 7) - 0.5);
      const double cy = kH / 2.0 + 6 * (hash01(k, 2, 7) - 0.5);
      const double r = 3.5 + 1.5 * hash01(k, 3, 7), shade = 0.45 + 0.3 * hash01(k, 4, 7);
      for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x)
          if (std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r)
            set(t, x, y, shade, shade, shade * 0.9, 1);
    }
    out.push_back({"gen_sparse_" + size, finish(std::move(t), "gen_sparse")});
  }
  {  // thin lines: two 2-texel rails with 1-texel sleepers every 8 texels between them
    std::vector<float> t(std::size_t(kW) * kH * 4, 0.0f);
    for (int x = 0; x < kW; ++x) {
      for (int y : {15, 16, 31, 32}) set(t, x, y, 0.55, 0.55, 0.6, 1);
      if (x % 8 == 3)
        for (int y = 17; y < 31; ++y) set(t, x, y, 0.5, 0.35, 0.2, 1);
    }
    out.push_back({"gen_lines_" + size, finish(std::move(t), "gen_lines")});
  }
  {  // a band with holes: rows 12..35 opaque but for round holes
    std::vector<float> t(std::size_t(kW) * kH * 4, 0.0f);
    for (int y = 12; y <= 35; ++y)
      for (int x = 0; x < kW; ++x) {
        bool hole = false;
        for (int k = 0; k < 14; ++k) {
          const double hx = kW * hash01(k, 5, 11), hy = 14 + 20 * hash01(k, 6, 11);
          hole = hole || std::hypot(x + 0.5 - hx, y + 0.5 - hy) < 2.5 + 2.5 * hash01(k, 7, 11);
        }
        const double v = 0.5 + 0.15 * std::sin(x * 0.3) + 0.1 * hash01(x, y, 13);
        if (!hole) set(t, x, y, v, v * 0.8, v * 0.6, 1);
      }
    out.push_back({"gen_holes_" + size, finish(std::move(t), "gen_holes")});
  }
  {  // soft-edged alpha: a Gaussian profile across, colour stripes along
    std::vector<float> t(std::size_t(kW) * kH * 4, 0.0f);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        const double a = std::exp(-std::pow((y + 0.5 - kH / 2.0) / 9.0, 2));
        if (a < 0.02) continue;
        const double v = 0.5 + 0.3 * std::sin(x * 2 * 3.14159265 / 32.0);
        set(t, x, y, v, 0.4, 1 - v, a);
      }
    out.push_back({"gen_soft_" + size, finish(std::move(t), "gen_soft")});
  }
  {  // photo-like: value noise over a band with ragged edges
    std::vector<float> t(std::size_t(kW) * kH * 4, 0.0f);
    auto noise = [](double x, double y) {
      const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
      const double fx = x - x0, fy = y - y0;
      auto h = [](int a, int b) {
        return hash01(std::uint64_t(a + 1000), std::uint64_t(b + 1000), 17);
      };
      return (h(x0, y0) * (1 - fx) + h(x0 + 1, y0) * fx) * (1 - fy) +
             (h(x0, y0 + 1) * (1 - fx) + h(x0 + 1, y0 + 1) * fx) * fy;
    };
    for (int x = 0; x < kW; ++x) {
      const int top = 10 + int(6 * noise(x / 9.0, 40.0)),
                bottom = 37 - int(6 * noise(x / 9.0, 80.0));
      for (int y = top; y <= bottom; ++y) {
        const double v = 0.25 + 0.5 * noise(x / 6.0, y / 6.0) + 0.2 * noise(x / 2.0, y / 2.0);
        set(t, x, y, v * 0.9, v * 0.8, v * 0.7, 1);
      }
    }
    out.push_back({"gen_photo_" + size, finish(std::move(t), "gen_photo")});
  }
  return out;
}

}  // namespace tw::test
