// geo features into avoidance inputs.
#include "raster/features.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"

namespace tw {
namespace {

TEST(Features, PolygonsAndLinesBecomeAvoidanceInputs) {
  PolygonFeature lake{
      7, {{{0, 0}, {10, 0}, {10, 10}}, {{2, 1}, {8, 1}, {8, 7}}}, "lakes.gpkg:lakes"};
  LineFeature ring_road{3, {{0, 0}, {5, 0}, {5, 5}}, true, 6.0, "roads.gpkg:roads"};
  LineFeature track{4, {{1, 1}, {2, 2}}, false, 2.5, "roads.gpkg:roads"};
  AvoidanceInputs in;
  add_features({lake}, {ring_road, track}, in);
  ASSERT_EQ(in.polygons.size(), 1u);
  EXPECT_EQ(in.polygons[0], lake.rings);
  ASSERT_EQ(in.lines.size(), 2u);
  ASSERT_EQ(in.lines[0].size(), 4u);  // closing segment added
  EXPECT_EQ(in.lines[0].back(), (Vec2{0, 0}));
  EXPECT_EQ(in.lines[1], track.points);
  EXPECT_EQ(in.line_widths, (std::vector<double>{6.0, 2.5}));

  // The grid stays in the caller's hands: the map builds from these inputs.
  const GridSpec grid{20, 20, -5.0, 15.0, 1.0, 1.0};
  const auto map = build_avoidance_map(in, grid, Window::whole(grid));
  EXPECT_EQ(map.forbidden.at(int(10 - -5.0 - 1), int(15.0 - 0.5)), 1);  // (9.5, 0.5): lake
}

TEST(Features, ErrorsNameSourceAndFid) {
  PolygonFeature bad{42, {{{0, 0}, {1, 0}}}, "lakes.gpkg:lakes"};
  try {
    to_polygons({bad});
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lakes.gpkg:lakes"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("FID 42"), std::string::npos);
  }
  AvoidanceInputs in;
  LineFeature nan_line{9, {{0, 0}, {std::nan(""), 1}}, false, 1.0, "roads.gpkg:roads"};
  EXPECT_THROW(add_features({}, {nan_line}, in), Error);
  LineFeature negative{10, {{0, 0}, {1, 1}}, false, -1.0, "roads.gpkg:roads"};
  EXPECT_THROW(add_features({}, {negative}, in), Error);
}

}  // namespace
}  // namespace tw
