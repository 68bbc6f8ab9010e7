#include "geo/detail/gradient_noise.hpp"

#include <algorithm>

namespace tw::detail {
namespace {

// Floor division for negative coordinates too (lattices extend west and north of the origin).
constexpr std::int64_t floor_div(std::int64_t a, std::int64_t b) {
  return a / b - ((a % b != 0) && ((a < 0) != (b < 0)));
}

// 6t^5 - 15t^4 + 10t^3 in Q16: zero slope at the lattice lines, so octaves show no creases.
constexpr std::int64_t fade(std::int64_t t) {
  const std::int64_t t2 = (t * t) >> 16;
  const std::int64_t t3 = (t2 * t) >> 16;
  const std::int64_t inner = ((t * (6 * t - 15 * kNoiseOne)) >> 16) + 10 * kNoiseOne;
  return (t3 * inner) >> 16;
}

constexpr std::int64_t lerp_q16(std::int64_t a, std::int64_t b, std::int64_t t) {
  return a + (((b - a) * t) >> 16);
}

// Dot product of the lattice point's gradient with the offset (dx, dy) in Q16. The eight
// gradients (axes and diagonals, the diagonals scaled by ~1/sqrt 2 = 46341/65536) have
// about unit length.
std::int64_t corner(std::int64_t ix, std::int64_t iy, std::int64_t dx, std::int64_t dy,
                    std::uint64_t seed) {
  const std::uint64_t h =
      mix64(seed ^ mix64(std::uint64_t(ix) * 0x8CB92BA72F3D8DD7ull + std::uint64_t(iy)));
  constexpr std::int64_t d = 46341;
  switch (h >> 61) {
    case 0:
      return dx;
    case 1:
      return -dx;
    case 2:
      return dy;
    case 3:
      return -dy;
    case 4:
      return ((dx + dy) * d) >> 16;
    case 5:
      return ((dx - dy) * d) >> 16;
    case 6:
      return ((-dx + dy) * d) >> 16;
    default:
      return ((-dx - dy) * d) >> 16;
  }
}

}  // namespace

std::int64_t gradient_noise(std::int64_t col, std::int64_t row, std::int64_t cell,
                            std::uint64_t seed) {
  const std::int64_t ix = floor_div(col, cell);
  const std::int64_t iy = floor_div(row, cell);
  const std::int64_t fx = ((col - ix * cell) * kNoiseOne) / cell;
  const std::int64_t fy = ((row - iy * cell) * kNoiseOne) / cell;
  const std::int64_t n00 = corner(ix, iy, fx, fy, seed);
  const std::int64_t n10 = corner(ix + 1, iy, fx - kNoiseOne, fy, seed);
  const std::int64_t n01 = corner(ix, iy + 1, fx, fy - kNoiseOne, seed);
  const std::int64_t n11 = corner(ix + 1, iy + 1, fx - kNoiseOne, fy - kNoiseOne, seed);
  const std::int64_t u = fade(fx);
  const std::int64_t v = fade(fy);
  // 2-D gradient noise peaks near +-0.7; doubling spreads it over about [-1, 1].
  return 2 * lerp_q16(lerp_q16(n00, n10, u), lerp_q16(n01, n11, u), v);
}

std::int64_t fractal_noise(std::int64_t col, std::int64_t row, std::int64_t largest_cell,
                           std::uint64_t seed) {
  std::int64_t sum = 0;
  std::int64_t amplitude_sum = 0;
  std::int64_t amplitude = kNoiseOne;
  std::uint64_t octave_seed = mix64(seed);
  for (std::int64_t cell = std::max<std::int64_t>(largest_cell, 2); cell >= 2; cell /= 2) {
    sum += (gradient_noise(col, row, cell, octave_seed) * amplitude) >> 16;
    amplitude_sum += amplitude;
    amplitude /= 2;
    octave_seed = mix64(octave_seed);
  }
  return std::clamp<std::int64_t>((sum * kNoiseOne) / amplitude_sum, -kNoiseOne, kNoiseOne);
}

}  // namespace tw::detail
