#include "geo/detail/gradient_noise.hpp"

#include <algorithm>
#include <vector>

#include "core/split_mix.hpp"

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

// One of eight gradients (axes and diagonals) for a lattice point.
int gradient_index(std::int64_t ix, std::int64_t iy, std::uint64_t seed) {
  return int(split_mix64(seed ^ split_mix64(std::uint64_t(ix) * 0x8CB92BA72F3D8DD7ull +
                                            std::uint64_t(iy))) >>
             61);
}

// Dot product of a gradient with the offset (dx, dy) in Q16. The diagonals are scaled by
// ~1/sqrt 2 = 46341/65536, so every gradient has about unit length.
constexpr std::int64_t dot_gradient(int gradient, std::int64_t dx, std::int64_t dy) {
  constexpr std::int64_t d = 46341;
  switch (gradient) {
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

struct CellGradients {
  int g00, g10, g01, g11;
};

CellGradients cell_gradients(std::int64_t ix, std::int64_t iy, std::uint64_t seed) {
  return {gradient_index(ix, iy, seed), gradient_index(ix + 1, iy, seed),
          gradient_index(ix, iy + 1, seed), gradient_index(ix + 1, iy + 1, seed)};
}

// The noise at offset (fx, fy) (Q16, in [0, 1)) inside a cell; v = fade(fy).
constexpr std::int64_t noise_in_cell(const CellGradients& g, std::int64_t fx, std::int64_t fy,
                                     std::int64_t v) {
  const std::int64_t n00 = dot_gradient(g.g00, fx, fy);
  const std::int64_t n10 = dot_gradient(g.g10, fx - kNoiseOne, fy);
  const std::int64_t n01 = dot_gradient(g.g01, fx, fy - kNoiseOne);
  const std::int64_t n11 = dot_gradient(g.g11, fx - kNoiseOne, fy - kNoiseOne);
  const std::int64_t u = fade(fx);
  // 2-D gradient noise peaks near +-0.7; doubling spreads it over about [-1, 1].
  return 2 * lerp_q16(lerp_q16(n00, n10, u), lerp_q16(n01, n11, u), v);
}

std::int64_t lattice_offset(std::int64_t coordinate, std::int64_t lattice, std::int64_t cell) {
  return ((coordinate - lattice * cell) * kNoiseOne) / cell;
}

struct Octave {
  std::int64_t cell;
  std::int64_t amplitude;  // Q16
  std::uint64_t seed;
};

std::vector<Octave> octaves(std::int64_t largest_cell, std::uint64_t seed) {
  std::vector<Octave> result;
  std::int64_t amplitude = kNoiseOne;
  std::uint64_t octave_seed = split_mix64(seed);
  for (std::int64_t cell = std::max<std::int64_t>(largest_cell, 2); cell >= 2; cell /= 2) {
    result.push_back({cell, amplitude, octave_seed});
    amplitude /= 2;
    octave_seed = split_mix64(octave_seed);
  }
  return result;
}

std::int64_t normalize(std::int64_t sum, const std::vector<Octave>& all) {
  std::int64_t amplitude_sum = 0;
  for (const Octave& octave : all) amplitude_sum += octave.amplitude;
  return std::clamp<std::int64_t>((sum * kNoiseOne) / amplitude_sum, -kNoiseOne, kNoiseOne);
}

}  // namespace

std::int64_t gradient_noise(std::int64_t col, std::int64_t row, std::int64_t cell,
                            std::uint64_t seed) {
  const std::int64_t ix = floor_div(col, cell);
  const std::int64_t iy = floor_div(row, cell);
  const std::int64_t fy = lattice_offset(row, iy, cell);
  return noise_in_cell(cell_gradients(ix, iy, seed), lattice_offset(col, ix, cell), fy, fade(fy));
}

std::int64_t fractal_noise(std::int64_t col, std::int64_t row, std::int64_t largest_cell,
                           std::uint64_t seed) {
  const std::vector<Octave> all = octaves(largest_cell, seed);
  std::int64_t sum = 0;
  for (const Octave& octave : all) {
    sum += (gradient_noise(col, row, octave.cell, octave.seed) * octave.amplitude) >> 16;
  }
  return normalize(sum, all);
}

namespace {

// The gradient as a Q16 vector: (g . (dx, dy)) >> 16 equals dot_gradient bit for bit, since
// ((dx + dy) * d) >> 16 == (d * dx + d * dy) >> 16 and (65536 * dx) >> 16 == dx exactly.
struct GradientVector {
  std::int64_t x, y;
};
constexpr GradientVector kGradients[8] = {{kNoiseOne, 0},  {-kNoiseOne, 0}, {0, kNoiseOne},
                                          {0, -kNoiseOne}, {46341, 46341},  {46341, -46341},
                                          {-46341, 46341}, {-46341, -46341}};

constexpr std::int64_t dot_q16(GradientVector g, std::int64_t dx, std::int64_t dy) {
  return (g.x * dx + g.y * dy) >> 16;
}

}  // namespace

void fractal_noise_row(std::int64_t row, std::int64_t col0, std::span<std::int64_t> out,
                       std::int64_t largest_cell, std::uint64_t seed) {
  const std::vector<Octave> all = octaves(largest_cell, seed);
  std::fill(out.begin(), out.end(), 0);
  const std::int64_t col_end = col0 + std::int64_t(out.size());
  std::vector<std::int64_t> offsets;  // fx of each column of a cell
  std::vector<std::int64_t> fades;    // fade(fx)
  for (const Octave& octave : all) {
    const std::int64_t cell = octave.cell;
    // A row narrower than the cell (a HeightSampler's small block) computes its few columns'
    // offsets directly instead of tabulating the whole cell: the same values.
    const bool tabulate = cell <= std::int64_t(out.size());
    if (tabulate) {
      offsets.resize(std::size_t(cell));
      fades.resize(std::size_t(cell));
      for (std::int64_t i = 0; i < cell; ++i) {
        offsets[i] = lattice_offset(i, 0, cell);
        fades[i] = fade(offsets[i]);
      }
    }
    const std::int64_t iy = floor_div(row, cell);
    const std::int64_t fy = lattice_offset(row, iy, cell);
    const std::int64_t v = fade(fy);
    // The gradients are hashed once per lattice cell, not once per pixel.
    for (std::int64_t ix = floor_div(col0, cell); ix * cell < col_end; ++ix) {
      const CellGradients g = cell_gradients(ix, iy, octave.seed);
      const GradientVector g00 = kGradients[g.g00], g10 = kGradients[g.g10];
      const GradientVector g01 = kGradients[g.g01], g11 = kGradients[g.g11];
      const std::int64_t first = std::max(col0, ix * cell);
      const std::int64_t last = std::min(col_end, (ix + 1) * cell);
      for (std::int64_t col = first; col < last; ++col) {
        const std::int64_t i = col - ix * cell;
        const std::int64_t fx = tabulate ? offsets[std::size_t(i)] : lattice_offset(i, 0, cell);
        const std::int64_t u = tabulate ? fades[std::size_t(i)] : fade(fx);
        const std::int64_t n00 = dot_q16(g00, fx, fy);
        const std::int64_t n10 = dot_q16(g10, fx - kNoiseOne, fy);
        const std::int64_t n01 = dot_q16(g01, fx, fy - kNoiseOne);
        const std::int64_t n11 = dot_q16(g11, fx - kNoiseOne, fy - kNoiseOne);
        const std::int64_t n = 2 * lerp_q16(lerp_q16(n00, n10, u), lerp_q16(n01, n11, u), v);
        out[std::size_t(col - col0)] += (n * octave.amplitude) >> 16;
      }
    }
  }
  for (std::int64_t& value : out) value = normalize(value, all);
}

}  // namespace tw::detail
