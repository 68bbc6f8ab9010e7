// Growth of a forest of trees (docs/networks.md, "Growth", steps 2 and 5): an exemplar whose
// lines end free (a third of its nodes are dangling ends) and cross rather than end on each
// other. Growth seeds only where the exemplar would leave room between its lines, and a branch
// meeting a line goes on through it, so that the output keeps the exemplar's degrees (ends,
// confluences and crossings) and its confluence angles rather than a dense mesh of
// T-junctions (before: degree 0.22, junction angles 0.22, edge lengths 0.25 at seeds 1-3, against
// halves of 0.14, 0.11 and 0.11).
#include <gtest/gtest.h>

#include <cmath>

#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

constexpr int kForestDegree = 0, kForestEdgeLength = 1, kForestJunctionAngle = 3;

TEST(NetworkForest, StreamTreesKeepTheirDegreesConfluenceAnglesAndEdgeLengths) {
  const Network ex = test::bench_exemplar("drainage");
  const std::vector<Polygon> region = test::extent_region(ex);
  const NetworkStats exemplar = network_stats(ex);
  const auto [a, b] = halves(ex);
  const NetworkStats half_a = network_stats(ex, a), half_b = network_stats(ex, b);
  const auto halves_apart = [&](int p) {
    return normalized_w1(property(half_a, p), property(half_b, p));
  };
  double edge_lengths = 0.0;
  for (std::uint64_t seed : {1, 2, 3}) {
    const Network out =
        grow_network(ex, region, nullptr, nullptr, {.seed = seed, .method = NetworkMethod::grow});
    EXPECT_EQ(check_network(out, region, nullptr).total(), 0) << seed;
    const NetworkStats grown = network_stats(out);
    const auto apart = [&](int p) {
      return normalized_w1(property(exemplar, p), property(grown, p));
    };
    EXPECT_LE(apart(kForestDegree), 1.5 * halves_apart(kForestDegree)) << seed;
    EXPECT_LE(apart(kForestJunctionAngle), 1.5 * halves_apart(kForestJunctionAngle)) << seed;
    EXPECT_LE(grown.dangling_per_km(), 1.5 * exemplar.dangling_per_km()) << seed;
    edge_lengths += apart(kForestEdgeLength) / 3.0;
  }
  EXPECT_LE(edge_lengths, 1.5 * halves_apart(kForestEdgeLength));
}

}  // namespace
}  // namespace tw
