// `terraweave grow` on the demo DEM (issue #13 B): ornaments come back as GeoPackage lines
// that stay in the region and off the roads, the same seed gives the same lines, and a bad
// element file is one error naming the key with nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <memory>

#include "core/error.hpp"
#include "pipeline/grow_command.hpp"
#include "test_support.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

GrowCommand hillside_command(const fs::path& out) {
  GrowCommand c;
  c.dem = (source_dir() / "samples/dem.tif").string();
  c.region = "291000,9114000,291600,9114600";
  c.resolution = 10.0;
  c.element = source_dir() / "samples/ornaments/wall.json";
  c.avoid = {(source_dir() / "samples/map.gpkg").string() + ":roads"};
  c.avoid_width = 12.0;
  c.contour = true;
  c.seed = 7;
  c.max_ornaments = 6;
  c.out = out;
  return c;
}

struct ReadLine {
  std::vector<std::array<double, 3>> points;
  std::string kind;
};
std::vector<ReadLine> read_lines(const fs::path& gpkg) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                    nullptr, nullptr, nullptr));
  EXPECT_TRUE(ds);
  std::vector<ReadLine> out;
  if (!ds) return out;
  OGRLayer* layer = ds->GetLayerByName("ornaments");
  EXPECT_TRUE(layer);
  for (auto& f : *layer) {
    ReadLine& line = out.emplace_back();
    line.kind = f->GetFieldAsString("kind");
    const OGRLineString* g = f->GetGeometryRef()->toLineString();
    for (int k = 0; k < g->getNumPoints(); ++k)
      line.points.push_back({g->getX(k), g->getY(k), g->getZ(k)});
  }
  return out;
}

TEST(GrowCommand, TerraceWallsStayInTheRegionAndOffTheRoads) {
  TempDir dir;
  const GrowCommandResult r = run_grow_command(hillside_command(dir / "out"));
  EXPECT_GT(r.elements, 10);
  EXPECT_GT(r.coverage, 0.2);
  const std::vector<ReadLine> lines = read_lines(dir / "out/ornaments.gpkg");
  ASSERT_EQ(int(lines.size()), r.lines);
  EXPECT_TRUE(fs::exists(dir / "out/preview.png"));
  // Roads as OGR geometry, buffered to half their width: no wall point comes onto one.
  GDALAllRegister();
  std::unique_ptr<GDALDataset> map(GDALDataset::Open((source_dir() / "samples/map.gpkg").c_str(),
                                                     GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  OGRLayer* roads = map->GetLayerByName("roads");
  std::vector<std::unique_ptr<OGRGeometry>> road_areas;
  for (auto& f : *roads) road_areas.emplace_back(f->GetGeometryRef()->Buffer(6.0));
  for (const ReadLine& line : lines) {
    EXPECT_EQ(line.kind, "wall");
    for (const auto& p : line.points) {
      // The region is rasterized by the pixel-centre rule: half a 10 m cell of slack.
      EXPECT_GE(p[0], 291000.0 - 5.0);
      EXPECT_LE(p[0], 291600.0 + 5.0);
      EXPECT_GE(p[1], 9114000.0 - 5.0);
      EXPECT_LE(p[1], 9114600.0 + 5.0);
      OGRPoint point(p[0], p[1]);
      for (const auto& road : road_areas) ASSERT_FALSE(road->Contains(&point));
    }
  }
  // Same seed, same lines (a GeoPackage's bytes carry a timestamp, so compare what it holds).
  run_grow_command(hillside_command(dir / "again"));
  const std::vector<ReadLine> again = read_lines(dir / "again/ornaments.gpkg");
  ASSERT_EQ(again.size(), lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) EXPECT_EQ(again[i].points, lines[i].points);
}

TEST(GrowCommand, ABadElementFileIsOneErrorAndWritesNothing) {
  TempDir dir;
  std::FILE* f = std::fopen((dir / "bad.json").c_str(), "w");
  std::fputs(R"({"name": "x", "kind": "fence", "seed_tag": "a", "elements": []})", f);
  std::fclose(f);
  GrowCommand c = hillside_command(dir / "out");
  c.element = dir / "bad.json";
  try {
    run_grow_command(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json: key 'kind'"));
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  c = hillside_command(dir / "out");
  c.region = "100,100,200,200";
  EXPECT_THROW(run_grow_command(c), Error);
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace tw::test
