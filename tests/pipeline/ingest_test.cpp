// The ingest stage's clip halo: a feature just off the heightfield whose profile reaches onto
// it is kept; one beyond that reach is not.
#include <gtest/gtest.h>

#include "pipeline/config.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

TEST(Ingest, FeaturesJustOffTheHeightfieldAreKeptWithinTheirReach) {
  const test::TempDir dir;
  // The DEM spans x 500000..500640, y 5000000..5000640 in 10 m cells.
  test::write_dem(dir / "dem.tif");
  // 10 m south of the DEM (reach 3 + 3 + 15 + 10 m = 31 m) and 40 m south of it.
  test::write_layer(dir / "map.gpkg", "roads",
                    {{"LINESTRING (500100 4999990,500500 4999990)", 6.0},
                     {"LINESTRING (500100 4999960,500500 4999960)", 6.0}});
  const PipelineConfig config = parse_pipeline(
      "version: 1\nheightfield: dem.tif\nfeatures:\n  roads: { source: map.gpkg, "
      "kind: road, width: 6, profile: { shoulder_width: 3, falloff: 15 } }\n",
      "p.yaml", dir.path());
  Warnings warnings;
  const Heightfield heightfield =
      detail::load_heightfield(detail::heightfield_input(config), warnings);
  const std::vector<LineFeature> lines =
      detail::load_feature_class(config.features[0], heightfield, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].fid, 1);
  EXPECT_EQ(lines[0].points.front(), (Vec2{500100, 4999990}));
  EXPECT_TRUE(warnings.empty());
}

}  // namespace
}  // namespace tw
