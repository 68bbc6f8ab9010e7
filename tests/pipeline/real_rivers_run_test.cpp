// A run on real river lines as they come: WDB II rivers (tests/data) over the Luxembourg DEM of
// pipelines/luxembourg.yaml. One of them doubles back 30 km south of the DEM; judged before
// clipping, it refused the whole run ("FID 1: part 0 intersects itself").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>

#include "pipeline/config.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

TEST(RealRiversRun, WdbRiversOverTheLuxembourgDemRun) {
  const test::TempDir out;
  const std::string rivers =
      (test::source_dir() / "tests/data/wdb2_rivers_luxembourg.geojson").string();
  const PipelineConfig config = load_pipeline(test::source_dir() / "pipelines/luxembourg.yaml",
                                              {{"features.rivers.source", rivers},
                                               {"features.rivers.where", "''"},
                                               {"features.rivers.width_attribute", "''"},
                                               {"features.rivers.width", "30"},
                                               // this test is about ingest, not carve bounds
                                               {"features.rivers.profile.max_carve", "1000"}});
  RunOptions options;
  options.output_dir = out.path();
  const RunReport report = run_pipeline(config, options);
  std::set<std::int64_t> fids;
  for (const FeatureReport& f : report.classes[0].features) fids.insert(f.fid);
  // FID 1's last 2 km and FID 4 lie on the DEM; 3 and 5 lie off it. The DEM is geographic, so
  // the grid is UTM 32N (its centre's zone, issue #12): at 6 E, 3 degrees west of the zone's
  // central meridian, grid north turns about 2 degrees from true north, and the grid's
  // bounding box holds nodata corners beyond the DEM's edges, where FID 2 ends.
  EXPECT_THAT(report.crs_wkt, testing::HasSubstr("UTM zone 32N"));
  EXPECT_EQ(fids, (std::set<std::int64_t>{1, 2, 4}));
  // FIDs 1 and 2 on the grid lie over nodata (outside Luxembourg, in the corners): left out of
  // the terrain, and said so. Nothing about FID 1's spike, which lies off the grid.
  ASSERT_EQ(report.warnings.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(report.warnings[i].code, "over_nodata");
    EXPECT_EQ(report.warnings[i].subject, "features.rivers");
    EXPECT_EQ(report.warnings[i].fid, std::int64_t(i + 1));
  }
  EXPECT_FALSE(report.outputs.empty());
  // validate (nothing written) reports the same warning.
  options.write_outputs = false;
  const RunReport validated = run_pipeline(config, options);
  ASSERT_EQ(validated.warnings.size(), 2u);
  EXPECT_EQ(to_string(validated.warnings[0]), to_string(report.warnings[0]));
  EXPECT_EQ(to_string(validated.warnings[1]), to_string(report.warnings[1]));
}

// The 7 real segments that are not simple, over a generated terrain that holds them all
// (UTM 31N, 1 km cells): the run succeeds and warns once per segment, naming its FID.
TEST(RealRiversRun, EveryMessyWdbRiverIsRepairedAndTheRunSucceeds) {
  const test::TempDir out;
  const std::string rivers = (test::source_dir() / "tests/data/wdb2_rivers_messy.geojson").string();
  const PipelineConfig config = parse_pipeline(
      "version: 1\n"
      "generate: { width: 450, height: 320, pixel_size: 1000, origin: [400000, 5500000] }\n"
      "output: { preview: false }\n"
      "features:\n"
      "  rivers: { source: " +
          rivers + ", kind: river, width: 30, profile: { max_carve: 1000 } }\n",
      "messy.yaml", out.path());
  RunOptions options;
  options.output_dir = out.path();
  const RunReport report = run_pipeline(config, options);
  const std::set<std::int64_t> messy{4, 27, 33, 77, 104, 110, 123};
  std::set<std::int64_t> fids, repaired;
  for (const FeatureReport& f : report.classes[0].features) fids.insert(f.fid);
  for (const Warning& w : report.warnings) {
    EXPECT_EQ(w.code, "repaired");
    EXPECT_EQ(w.subject, "features.rivers");
    if (w.fid) repaired.insert(*w.fid);
  }
  EXPECT_EQ(fids, messy);
  EXPECT_EQ(repaired, messy);
  EXPECT_EQ(report.warnings.size(), messy.size());
  EXPECT_FALSE(report.outputs.empty());
}

}  // namespace
}  // namespace tw
