#pragma once
// Integer gradient noise (Perlin-style) and its fBm sum, in fixed point so that the same seed
// gives the same bits on every compiler and CPU (no floating point until the final scaling).
#include <cstdint>
#include <span>

namespace tw::detail {

inline constexpr std::int64_t kNoiseOne = 1 << 16;  // 1.0 in the noise's Q16 fixed point

// Gradient noise at the integer pixel (col, row) of a lattice whose cells are `cell` pixels
// wide, in Q16, roughly within [-1, 1].
std::int64_t gradient_noise(std::int64_t col, std::int64_t row, std::int64_t cell,
                            std::uint64_t seed);

// fBm: octaves of gradient noise from `largest_cell` pixels down to 2, each half the size and
// half the amplitude of the one before, normalized to Q16 within [-1, 1].
std::int64_t fractal_noise(std::int64_t col, std::int64_t row, std::int64_t largest_cell,
                           std::uint64_t seed);

// fractal_noise for the pixels (col0 + i, row) of out, bit for bit, hashing each lattice
// cell's gradients once instead of once per pixel.
void fractal_noise_row(std::int64_t row, std::int64_t col0, std::span<std::int64_t> out,
                       std::int64_t largest_cell, std::uint64_t seed);

}  // namespace tw::detail
