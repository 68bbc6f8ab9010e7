// The drawn exemplar grown over regions three and four times its size (docs/networks.md,
// "Guarantees"): the output keeps every rule, as the GEOS safety net checks it. Each case once
// failed it with one pair of edges: a T made at a line's vertex left a step of 1e-14 m along
// the line ending there (a split kept the vertex the hit point was rounded off); a link ran
// 40 m along a line, nearly collinear, that Boost's intersection met at one point; a quilt seam
// end's link started where the end was cut, not where stitching had moved its node.
#include <gtest/gtest.h>

#include "network/check.hpp"
#include "network/growth.hpp"
#include "network_fixtures.hpp"

namespace tw {
namespace {

// The exemplar's extent scaled by `factor` about its centre, as the quality bench makes its
// regions.
std::vector<Polygon> scaled_extent(const Network& ex, double factor) {
  const NodeExtent e = node_extent(ex);
  const Vec2 c = 0.5 * (e.lo + e.hi), h = 0.5 * factor * (e.hi - e.lo);
  return {{{{c.x - h.x, c.y - h.y},
            {c.x + h.x, c.y - h.y},
            {c.x + h.x, c.y + h.y},
            {c.x - h.x, c.y + h.y}}}};
}

struct LargeRegionCase {
  double factor;
  std::uint64_t seed;
  NetworkMethod method;
};

TEST(NetworkDrawnLargeRegion, KeepsTheSafetyNetsRulesAtThreeAndFourTimesItsSize) {
  const Network ex = test::drawn_exemplar();
  for (const LargeRegionCase& c : {LargeRegionCase{4.0, 2, NetworkMethod::layout},
                                   LargeRegionCase{3.0, 3, NetworkMethod::layout},
                                   LargeRegionCase{4.0, 3, NetworkMethod::quilt}}) {
    SCOPED_TRACE(testing::Message()
                 << "x" << c.factor << " seed " << c.seed << " " << network_method_name(c.method));
    const std::vector<Polygon> region = scaled_extent(ex, c.factor);
    NetworkGrowthReport report;
    const Network out =
        grow_network(ex, region, nullptr, nullptr, {.seed = c.seed, .method = c.method}, &report);
    EXPECT_EQ(chosen_network_method(report), network_method_name(c.method));
    EXPECT_GT(out.edges.size(), 250u);
    const NetworkCheck check = check_network(out, region, nullptr);
    EXPECT_EQ(check.total(), 0) << check.first;
  }
}

}  // namespace
}  // namespace tw
