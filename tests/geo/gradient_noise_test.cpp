#include "geo/detail/gradient_noise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace tw::detail {
namespace {

TEST(GradientNoise, VanishesOnLatticePointsIncludingNegativeOnes) {
  for (std::int64_t cell : {2, 8, 64}) {
    for (std::int64_t i = -3; i <= 3; ++i) {
      for (std::int64_t j = -3; j <= 3; ++j) {
        EXPECT_EQ(gradient_noise(i * cell, j * cell, cell, 42), 0) << cell << " " << i << " " << j;
      }
    }
  }
}

TEST(GradientNoise, IsContinuousAcrossCells) {
  // A cell of 64 pixels: one pixel step changes the noise by far less than its range.
  std::int64_t largest_step = 0;
  for (std::int64_t x = -200; x < 200; ++x) {
    largest_step = std::max(
        largest_step, std::abs(gradient_noise(x + 1, 37, 64, 9) - gradient_noise(x, 37, 64, 9)));
  }
  EXPECT_LT(largest_step, kNoiseOne / 10);
  EXPECT_GT(largest_step, 0);
}

TEST(FractalNoise, StaysWithinPlusMinusOneAndUsesTheRange) {
  std::int64_t low = kNoiseOne;
  std::int64_t high = -kNoiseOne;
  for (std::int64_t y = 0; y < 128; y += 3) {
    for (std::int64_t x = 0; x < 128; x += 3) {
      const std::int64_t n = fractal_noise(x, y, 32, 5);
      low = std::min(low, n);
      high = std::max(high, n);
    }
  }
  EXPECT_GE(low, -kNoiseOne);
  EXPECT_LE(high, kNoiseOne);
  EXPECT_GT(high - low, kNoiseOne / 2);
}

TEST(FractalNoiseRow, MatchesThePointwiseNoiseBitForBit) {
  for (std::int64_t row : {-70, -1, 0, 5, 129}) {
    std::vector<std::int64_t> out(300);
    fractal_noise_row(row, -37, out, 64, 11);
    for (std::size_t i = 0; i < out.size(); ++i) {
      ASSERT_EQ(out[i], fractal_noise(-37 + std::int64_t(i), row, 64, 11)) << row << " " << i;
    }
  }
}

// Rows narrower than the largest cell (a HeightSampler's 16-cell blocks of a generated world)
// compute their offsets without the per-cell tables: the same values, across cell borders too.
TEST(FractalNoiseRow, NarrowRowsMatchThePointwiseNoise) {
  for (const std::int64_t col0 : {-37, 0, 50, 1000}) {
    for (const std::size_t width : {std::size_t(1), std::size_t(7), std::size_t(16)}) {
      std::vector<std::int64_t> out(width);
      fractal_noise_row(9, col0, out, 256, 3);
      for (std::size_t i = 0; i < width; ++i)
        ASSERT_EQ(out[i], fractal_noise(col0 + std::int64_t(i), 9, 256, 3)) << col0 << " " << i;
    }
  }
}

}  // namespace
}  // namespace tw::detail
