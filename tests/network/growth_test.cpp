// Growth by example (docs/networks.md): no crossings, inside the region, off forbidden cells,
// deterministic, and the exemplar's style per property.
#include <gtest/gtest.h>

#include <cmath>

#include "network/check.hpp"
#include "network/example_networks.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/stats.hpp"

namespace tw {
namespace {

Network exemplar(const std::string& kind, double size = 800.0) {
  Warnings w;
  return build_planar_network(example_network(kind, size, 3), 1.0, "exemplar", w);
}

std::vector<Polygon> box(double x0, double y0, double x1, double y1) {
  return {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

TEST(NetworkGrowth, GridNeverCrossesStaysInsideAndIsDeterministic) {
  const Network ex = exemplar("grid");
  const auto region = box(0, 0, 1200, 900);
  NetworkGrowthReport report;
  const Network out = grow_network(ex, region, nullptr, nullptr, {.seed = 5}, &report);
  EXPECT_GT(out.edges.size(), 40u);
  const NetworkCheck check = check_network(out, region, nullptr);
  EXPECT_EQ(check.crossings, 0) << check.first;
  EXPECT_EQ(check.outside, 0) << check.first;
  const Network again = grow_network(ex, region, nullptr, nullptr, {.seed = 5});
  ASSERT_EQ(again.edges.size(), out.edges.size());
  for (std::size_t i = 0; i < out.edges.size(); ++i)
    ASSERT_EQ(again.edges[i].points, out.edges[i].points);
  const Network other = grow_network(ex, region, nullptr, nullptr, {.seed = 6});
  EXPECT_NE(other.edges.size() == out.edges.size() && other.edges[0].points == out.edges[0].points,
            true);
}

}  // namespace
}  // namespace tw
