// Engine splines carry real heights (docs/exports.md, "Splines"): on the real Moselle over
// Luxembourg's DEM (pipelines/luxembourg.yaml), whose lines run beyond the map as real
// features do, every exported point lies within the terrain's extent in the engine (the corner
// cell centres) and its height is the final height layer's there (bilinear), never 0 as a
// placeholder; untiled and tiled exports, Unreal and Unity, JSON and CSV.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "geo/resample.hpp"
#include "layers/export.hpp"
#include "pipeline/config.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/run.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;

struct SplineCheck {
  int points = 0, on_edge = 0, exact = 0;
  double lowest = 1e300, highest = -1e300;
};

// Checks `dir`/splines.json and splines.csv against the final heights.
SplineCheck check_splines(const fs::path& dir, const LayerSet& final_set) {
  SplineCheck out;
  const GridSpec& g = final_set.grid;
  const Raster<float>& h = final_set.layers.at(0).bands.at(0);
  const double west = g.origin_x + 0.5 * g.pixel_width;
  const double east = g.origin_x + (g.width - 0.5) * g.pixel_width;
  const double north = g.origin_y - 0.5 * g.pixel_height;
  const double south = g.origin_y - (g.height - 0.5) * g.pixel_height;
  float lo = INFINITY, hi = -INFINITY;
  for (const float v : h.pixels)
    if (!std::isnan(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  const nlohmann::json json = nlohmann::json::parse(std::ifstream(dir / "splines.json"));
  std::vector<double> heights;
  for (const auto& spline : json["splines"]) {
    for (const auto& p : spline["points"]) {
      const double x = p["world"][0], y = p["world"][1], z = p["world"][2];
      heights.push_back(z);
      ++out.points;
      EXPECT_GE(x, west);
      EXPECT_LE(x, east);
      EXPECT_GE(y, south);
      EXPECT_LE(y, north);
      out.on_edge += x == west || x == east || y == south || y == north;
      EXPECT_NE(z, 0.0) << spline["name"];
      EXPECT_GE(z, lo - 1e-3);
      EXPECT_LE(z, hi + 1e-3);
      out.lowest = std::min(out.lowest, z);
      out.highest = std::max(out.highest, z);
      // Where the four cells around the point hold heights, nodata filling changes nothing:
      // the point's height is the final height layer's, bilinear.
      const Vec2 px = g.world_to_pixel({x, y}) - Vec2{0.5, 0.5};
      const int c = int(std::floor(px.x)), r = int(std::floor(px.y));
      bool valid = true;
      for (int dr = 0; dr <= 1; ++dr)
        for (int dc = 0; dc <= 1; ++dc) {
          const int cc = std::clamp(c + dc, 0, g.width - 1),
                    rr = std::clamp(r + dr, 0, g.height - 1);
          valid = valid && !std::isnan(h.at(cc, rr));
        }
      if (valid) {
        ++out.exact;
        EXPECT_NEAR(z, sample_height_bilinear(h, g, {x, y}), 1e-6) << spline["name"];
      }
    }
  }
  // The CSV gives the same points and heights (its last column, 3 decimals).
  const std::vector<std::string> rows = test::lines_of(test::read_file(dir / "splines.csv"));
  EXPECT_EQ(rows.size(), heights.size() + 1);
  for (std::size_t i = 1; i < rows.size() && i <= heights.size(); ++i) {
    const double z = std::stod(rows[i].substr(rows[i].rfind(',') + 1));
    EXPECT_NEAR(z, heights[i - 1], 1e-3 + 1e-9) << rows[i];
  }
  return out;
}

TEST(Splines, PointsLieOnTheMapWithTheFinalTerrainsHeights) {
  test::TempDir dir;
  const auto run = [&](const std::string& out, std::vector<Override> overrides) {
    overrides.push_back({"output.dir", (dir / out).string()});
    overrides.push_back({"output.preview", "false"});
    overrides.push_back({"export", "[unreal, unity]"});
    return run_pipeline(load_pipeline(test::source_dir() / "pipelines/luxembourg.yaml", overrides));
  };
  // The southern half of the map (a region of the run's grid): the Moselle and the road run
  // on beyond it.
  Warnings warnings;
  PlanOptions plan_options;
  plan_options.synthesize = false;
  const GridSpec world = plan_world(load_pipeline(test::source_dir() / "pipelines/luxembourg.yaml"),
                                    plan_options, warnings)
                             .grid;
  const double west = world.origin_x, north = world.origin_y;
  const double east = west + world.width * world.pixel_width;
  const double south = north - world.height * world.pixel_height;
  const std::string region =
      fmt::format("[{}, {}, {}, {}]", west, south, east, 0.5 * (south + north));
  run("untiled", {{"region", region}});
  run("tiled", {{"region", region}, {"output.tiles", "{ size: 128, overlap: 0 }"}});
  for (const char* out : {"untiled", "tiled"}) {
    LayerSet set;
    set.layers.push_back(read_geotiff_layer(
        dir / out / (std::string(out) == "tiled" ? "height.vrt" : "height.tif"), "height", set));
    for (const char* engine : {"unreal", "unity"}) {
      SCOPED_TRACE(std::string(out) + " " + engine);
      const SplineCheck c = check_splines(dir / out / "export" / engine, set);
      std::printf(
          "%s %s: %d spline points, %d on the map's edge, %d checked exactly, "
          "heights %.1f .. %.1f m\n",
          out, engine, c.points, c.on_edge, c.exact, c.lowest, c.highest);
      EXPECT_GT(c.points, 20);
      EXPECT_GE(c.on_edge, 2);           // lines that run beyond the map end on its edge
      EXPECT_GT(c.exact, c.points / 4);  // the others lie by nodata (the border)
      EXPECT_GT(c.lowest, 100.0);        // the Moselle's valley is ~130 m above the sea at least
    }
  }
}

}  // namespace
}  // namespace tw
