// Exact Euclidean distance transform against brute force.
#include "raster/distance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/error.hpp"

namespace tw {
namespace {

TEST(DistanceToMask, MatchesBruteForceOnNonSquarePixels) {
  std::mt19937 rng(11);
  std::bernoulli_distribution on(0.03);
  Raster<std::uint8_t> mask(53, 31, 0);
  for (auto& v : mask.pixels) v = on(rng) ? 1 : 0;
  const double pw = 1.5, ph = 0.7;
  const auto d = distance_to_mask(mask, pw, ph);
  for (int r = 0; r < mask.height; ++r)
    for (int c = 0; c < mask.width; ++c) {
      double best = std::numeric_limits<double>::infinity();
      for (int rr = 0; rr < mask.height; ++rr)
        for (int cc = 0; cc < mask.width; ++cc)
          if (mask.at(cc, rr)) best = std::min(best, std::hypot((c - cc) * pw, (r - rr) * ph));
      EXPECT_NEAR(d.at(c, r), best, 1e-5 * (1.0 + best)) << c << "," << r;
      if (mask.at(c, r)) {
        EXPECT_EQ(d.at(c, r), 0.0f);
      }
    }
}

// Squared metres summed in the transform's own order, so the minimum is the same double: the
// column scans and the row envelope must find exactly the nearest pixel, not a close one.
TEST(DistanceToMask, EqualsBruteForceBitForBitAcrossColumnChunks) {
  std::mt19937 rng(5);
  for (const double density : {0.0005, 0.004, 0.05}) {
    std::bernoulli_distribution on(density);
    Raster<std::uint8_t> mask(300, 170, 0);  // wider than one column chunk (256)
    std::vector<std::pair<int, int>> points;
    for (int r = 0; r < mask.height; ++r)
      for (int c = 0; c < mask.width; ++c)
        if (on(rng)) mask.at(c, r) = 1, points.emplace_back(c, r);
    const double pw = 4.0, ph = 3.0;
    const auto d = distance_to_mask(mask, pw, ph);
    for (int r = 0; r < mask.height; ++r)
      for (int c = 0; c < mask.width; ++c) {
        double best = std::numeric_limits<double>::infinity();
        for (const auto& [pc, pr] : points) {
          const double dx = double(c - pc), dy = double(r - pr);
          best = std::min(best, pw * pw * dx * dx + ph * ph * dy * dy);
        }
        ASSERT_EQ(d.at(c, r), float(std::sqrt(best))) << c << "," << r << " at " << density;
      }
  }
}

TEST(DistanceToMask, EmptyMaskIsInfiniteAndBadPixelSizeThrows) {
  const Raster<std::uint8_t> empty(5, 4, 0);
  for (float v : distance_to_mask(empty, 1.0, 1.0).pixels) EXPECT_TRUE(std::isinf(v));
  EXPECT_THROW(distance_to_mask(empty, 0.0, 1.0), Error);
}

TEST(DistanceToMask, SinglePixelGivesExactRadialDistances) {
  Raster<std::uint8_t> mask(9, 9, 0);
  mask.at(0, 0) = 1;
  const auto d = distance_to_mask(mask, 3.0, 4.0);
  EXPECT_FLOAT_EQ(d.at(1, 1), 5.0f);
  EXPECT_FLOAT_EQ(d.at(8, 0), 24.0f);
  EXPECT_FLOAT_EQ(d.at(0, 8), 32.0f);
}

}  // namespace
}  // namespace tw
