// plan_world reads heights window by window (geo/heightfield_source.hpp): the demo's plan and
// tile heights equal those over the whole read, bit for bit.
#include <gtest/gtest.h>

#include <cstring>

#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/plan.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

TEST(PlanHeights, TheDemoPlansThroughWindowsAsOverTheWholeRead) {
  const PipelineConfig config = load_pipeline(test::source_dir() / "pipelines/demo.yaml");
  Warnings warnings;
  PlanOptions options;
  options.synthesize = false;
  const WorldPlan plan = plan_world(config, options, warnings);
  ASSERT_TRUE(plan.heights.reader);  // no region: the DEM is read window by window

  Warnings whole_warnings;
  const Heightfield whole =
      detail::load_heightfield(detail::heightfield_input(config), whole_warnings);  // resampled 6 m
  ASSERT_EQ(plan.grid, whole.grid);
  const TerrainPlan expected =
      plan_terrain(whole.height, whole.grid, plan.terrain_features, plan.terrain_params);
  ASSERT_EQ(plan.terrain.profiles.size(), expected.profiles.size());
  for (std::size_t i = 0; i < expected.profiles.size(); ++i) {
    const auto& a = plan.terrain.profiles[i];
    const auto& b = expected.profiles[i];
    ASSERT_EQ(a.size(), b.size());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << "feature " << i;
  }

  const Window window{301, 577, 250, 130};
  const Raster<float> tile = read_height_window(plan.heights, plan.grid, window);
  for (int r = 0; r < window.height; ++r)
    for (int c = 0; c < window.width; ++c) {
      const float got = tile.at(c, r), want = whole.height.at(window.col0 + c, window.row0 + r);
      ASSERT_EQ(std::memcmp(&got, &want, sizeof got), 0) << c << ", " << r;
    }
}

}  // namespace
}  // namespace tw
