#pragma once
// The integer matching cost xi of Zhou et al. 2013 (Section "Input exemplars, comparing
// pixels") and the fixed-point bilinear read of right-edge samples. Both backends use exactly
// these formulas so their DP tables agree bit for bit (see docs/synthesis.md, "Costs").
#include <cmath>
#include <cstdint>

#include "synth/detail/stages.hpp"

namespace tw::detail {

// Colour distances are scaled by 16 before flooring: xi = floor(16 * ||p - q||).
inline constexpr std::int32_t kColourScale = 16;
// The paper's gamma = 1024 colour units, in the same scale. It exceeds any colour term
// (16 * 255 * sqrt(3) < 7068), which the pruning bound relies on.
inline constexpr std::int32_t kGamma = 1024 * kColourScale;
// The largest possible colour term floor(16 * sqrt(3 * 255^2)).
inline constexpr std::int32_t kMaxColourTerm = 7066;
// A texel is opaque for validity and binary costs when its alpha is at least this.
inline constexpr std::uint32_t kOpaqueAlphaMin = 128;

constexpr std::uint32_t channel_of(std::uint32_t rgba, int c) {
  return (rgba >> (8 * c)) & 255u;
}
constexpr std::uint32_t alpha_of(std::uint32_t rgba) {
  return rgba >> 24;
}
constexpr bool is_opaque(std::uint32_t rgba) {
  return alpha_of(rgba) >= kOpaqueAlphaMin;
}
constexpr std::uint32_t pack_rgba(std::uint32_t r, std::uint32_t g, std::uint32_t b,
                                  std::uint32_t a) {
  return r | (g << 8) | (b << 16) | (a << 24);
}

// floor(16 * ||p - q||) over RGB. Equals floor(sqrt(256 * d2)) exactly: d2 <= 195075, so the
// gap between 16 sqrt(d2) and the next integer (>= 1 / 14000) dwarfs double rounding.
inline std::int32_t colour_term(std::uint32_t p, std::uint32_t q) {
  const int dr = int(channel_of(p, 0)) - int(channel_of(q, 0));
  const int dg = int(channel_of(p, 1)) - int(channel_of(q, 1));
  const int db = int(channel_of(p, 2)) - int(channel_of(q, 2));
  const int d2 = dr * dr + dg * dg + db * db;
  return std::int32_t(16.0 * std::sqrt(double(d2)));
}

// xi(p, q). Binary alpha: the colour term when both are opaque or both transparent, gamma
// otherwise. Continuous alpha (a, b in 0..255): floor((w_same * colour + w_diff * gamma) /
// 255^2) with w_same = a b + (255 - a)(255 - b), w_diff = a (255 - b) + (255 - a) b.
inline std::int32_t xi(std::uint32_t p, std::uint32_t q, bool binary_alpha) {
  const std::int32_t colour = colour_term(p, q);
  if (binary_alpha) return is_opaque(p) == is_opaque(q) ? colour : kGamma;
  const std::int64_t a = alpha_of(p), b = alpha_of(q);
  const std::int64_t same = a * b + (255 - a) * (255 - b);
  const std::int64_t diff = a * (255 - b) + (255 - a) * b;
  return std::int32_t((same * colour + diff * kGamma) / (255 * 255));
}

// D: the sum of xi over the C samples of two edges.
inline std::int64_t edge_cost(const std::uint32_t* right, const std::uint32_t* left, int count,
                              bool binary_alpha) {
  std::int64_t sum = 0;
  for (int k = 0; k < count; ++k) sum += xi(right[k], left[k], binary_alpha);
  return sum;
}

// The packed texel (x, y); transparent black outside the exemplar.
inline std::uint32_t texel_at(const CostTexels& texels, int x, int y) {
  if (x < 0 || y < 0 || x >= texels.width || y >= texels.height) return 0u;
  return texels.rgba[std::size_t(y) * texels.width + x];
}

// Bilinear read at fixed-point (X, Y) = 256 * (continuous coordinate - 0.5), so that integer
// multiples of 256 land on texel centres. Each channel: (sum of weight * value + 2^15) >> 16
// with weights (256 - fx)(256 - fy), fx (256 - fy), (256 - fx) fy, fx fy.
inline std::uint32_t sample_bilinear(const CostTexels& texels, std::int32_t X, std::int32_t Y) {
  const int x0 = X >> 8, y0 = Y >> 8;  // arithmetic shift = floor
  const std::uint32_t fx = std::uint32_t(X & 255), fy = std::uint32_t(Y & 255);
  const std::uint32_t t00 = texel_at(texels, x0, y0), t10 = texel_at(texels, x0 + 1, y0);
  const std::uint32_t t01 = texel_at(texels, x0, y0 + 1), t11 = texel_at(texels, x0 + 1, y0 + 1);
  const std::uint32_t w00 = (256 - fx) * (256 - fy), w10 = fx * (256 - fy);
  const std::uint32_t w01 = (256 - fx) * fy, w11 = fx * fy;
  std::uint32_t out = 0;
  for (int c = 0; c < 4; ++c) {
    const std::uint32_t v = channel_of(t00, c) * w00 + channel_of(t10, c) * w10 +
                            channel_of(t01, c) * w01 + channel_of(t11, c) * w11;
    out |= ((v + 32768u) >> 16) << (8 * c);
  }
  return out;
}

}  // namespace tw::detail
