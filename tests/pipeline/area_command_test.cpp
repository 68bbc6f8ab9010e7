// `terraweave area` on the demo map's landuse polygons (issue #13 A): shapes stay inside their
// polygon and off the roads, files come back as written, same seed same bytes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogr_api.h>
#include <ogrsf_frmts.h>

#include <fstream>
#include <memory>

#include "commands/area_command.hpp"
#include "test_support.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::unique_ptr<GDALDataset> open_vector(const fs::path& path) {
  GDALAllRegister();
  return std::unique_ptr<GDALDataset>(GDALDataset::Open(
      path.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
}

// The orchard next to the demo's forest reserve (an `existing` polygon) and its roads.
AreaCommand orchard_command(const fs::path& out) {
  AreaCommand c;
  c.sketch = source_dir() / "samples/sketches/orchard.geojson";
  c.polygons = (source_dir() / "samples/landuse.geojson").string();
  c.where = "landuse = 'orchard'";
  c.scale = 40.0;
  c.avoid = {(source_dir() / "samples/map.gpkg").string() + ":roads",
             (source_dir() / "samples/map.gpkg").string() + ":existing"};
  c.avoid_width = 12.0;
  c.out = out;
  return c;
}

TEST(AreaCommand, OrchardStaysInTheFieldAndOffTheReserveAndRoads) {
  TempDir dir;
  const AreaCommandResult r = run_area_command(orchard_command(dir / "out"));
  EXPECT_EQ(r.polygons, 1);
  EXPECT_GT(r.instances, 1000);
  auto shapes = open_vector(dir / "out/shapes.gpkg");
  ASSERT_TRUE(shapes);
  OGRLayer* strokes = shapes->GetLayerByName("strokes");
  OGRLayer* instances = shapes->GetLayerByName("instances");
  ASSERT_TRUE(strokes && instances);
  EXPECT_EQ(instances->GetFeatureCount(), r.instances);
  EXPECT_EQ(strokes->GetFeatureCount(), r.strokes);
  EXPECT_EQ(lines_of(read_file(dir / "out/instances.csv")).size(), std::size_t(r.instances) + 1);

  auto landuse = open_vector(source_dir() / "samples/landuse.geojson");
  OGRLayer* fields = landuse->GetLayer(0);
  fields->SetAttributeFilter("landuse = 'orchard'");
  std::unique_ptr<OGRFeature> field(fields->GetNextFeature());
  ASSERT_TRUE(field);
  std::unique_ptr<OGRGeometry> grown(field->GetGeometryRef()->Buffer(1e-6));
  auto map = open_vector(source_dir() / "samples/map.gpkg");
  std::vector<std::unique_ptr<OGRGeometry>> roads, existing;
  for (auto& road : *map->GetLayerByName("roads")) {
    roads.emplace_back(road->GetGeometryRef()->clone());
  }
  for (auto& area : *map->GetLayerByName("existing")) {
    existing.emplace_back(area->GetGeometryRef()->clone());
  }
  // The reserve covers part of the field: trees there are left out.
  EXPECT_GT(r.forbidden, 100);
  int checked = 0;
  for (auto& stroke : *strokes) {
    const OGRGeometry* g = stroke->GetGeometryRef();
    ASSERT_TRUE(g->Within(grown.get())) << "FID " << stroke->GetFID();
    const double half = 0.5 * stroke->GetFieldAsDouble("width_m");
    // The avoidance map forbids pixel centres within 6 m of a road; a stroke keeps clear of
    // them, so it stays beyond 6 m less a pixel diagonal of the centreline.
    for (const auto& road : roads) ASSERT_GT(g->Distance(road.get()), 6.0 + half - 1.5);
    // Nor does it reach into an existing area farther than a pixel diagonal (pixel-centre rule).
    for (const auto& area : existing) {
      if (g->Intersects(area.get())) {
        std::unique_ptr<OGRGeometry> inside(g->Intersection(area.get()));
        ASSERT_LT(OGR_G_Length(OGRGeometry::ToHandle(inside.get())), 1.5)
            << "FID " << stroke->GetFID();
      }
    }
    ++checked;
  }
  EXPECT_EQ(checked, r.strokes);
  EXPECT_TRUE(fs::file_size(dir / "out/preview.png") > 1000);
}

TEST(AreaCommand, SameSeedSameBytesOtherSeedOtherShapes) {
  TempDir dir;
  AreaCommand c = orchard_command(dir / "a");
  c.avoid.clear();
  run_area_command(c);
  c.out = dir / "b";
  run_area_command(c);
  EXPECT_EQ(read_file(dir / "a/instances.csv"), read_file(dir / "b/instances.csv"));
  c.out = dir / "c";
  c.seed = 2;
  run_area_command(c);
  EXPECT_NE(read_file(dir / "a/instances.csv"), read_file(dir / "c/instances.csv"));
}

// A self-crossing (bowtie) field on the demo's hillside, EPSG:31985: read, it is repaired with a
// `repaired` warning naming FID 0.
void write_bowtie(const fs::path& path) {
  std::ofstream(path) << R"({"type": "FeatureCollection",
    "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::31985"}},
    "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "Polygon",
     "coordinates": [[[291200, 9115250], [291400, 9115400], [291400, 9115250],
                      [291200, 9115400], [291200, 9115250]]]}}]})";
}

// Issue #24 item 8: --strict applies to area as to run: a warning fails it, writing nothing.
TEST(AreaCommand, StrictFailsOnAWarningAndWritesNothing) {
  TempDir dir;
  write_bowtie(dir / "bowtie.geojson");
  const std::string args = " area " + (source_dir() / "samples/sketches/orchard.geojson").string() +
                           " --polygons " + (dir / "bowtie.geojson").string() + " --out ";
  const auto strict = run_command(terraweave_binary().string() + " -q --strict" + args +
                                  (dir / "strict").string() + " 2>&1");
  EXPECT_EQ(strict.exit_code, 1);
  EXPECT_THAT(strict.output, HasSubstr("strict: 1 warning (first: area.polygons: FID 0: "));
  EXPECT_THAT(strict.output, HasSubstr("nothing written"));
  EXPECT_FALSE(fs::exists(dir / "strict"));
  const auto plain =
      run_command(terraweave_binary().string() + " -q" + args + (dir / "plain").string() + " 2>&1");
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_THAT(plain.output, HasSubstr("invalid polygon"));  // the warning, logged
  EXPECT_TRUE(fs::exists(dir / "plain/shapes.gpkg"));
}

TEST(AreaCommand, CliNamesTheBadInputAndWritesNothing) {
  TempDir dir;
  const std::string bin = terraweave_binary().string();
  const std::string polygons = (source_dir() / "samples/landuse.geojson").string();
  const auto missing =
      run_command(bin + " area " + (dir / "nope.geojson").string() + " --polygons " + polygons +
                  " --out " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_THAT(missing.output, HasSubstr("nope.geojson"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  // Geographic polygons: a projected CRS in metres is needed.
  const auto geographic =
      run_command(bin + " area " + (source_dir() / "samples/sketches/orchard.geojson").string() +
                  " --polygons " + (source_dir() / "samples/lines_wgs84.geojson").string() +
                  " --out " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(geographic.exit_code, 1);
  EXPECT_THAT(geographic.output, HasSubstr("projected CRS"));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// A Luxembourg canton (tests/data, 129 km²) at 5 cm per sketch unit: refused before anything is
// allocated, naming the polygon, its FID and the estimate; nothing written.
TEST(AreaCommand, AHugePolygonAtATinyScaleIsRefusedWithItsEstimate) {
  TempDir dir;
  const auto refused =
      run_command(terraweave_binary().string() + " area " +
                  (source_dir() / "samples/sketches/vineyard.geojson").string() + " --polygons " +
                  (source_dir() / "tests/data/lux_remich_2169.geojson").string() +
                  " --scale 0.05 --out " + (dir / "out").string() + " 2>&1");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.output, HasSubstr("lux_remich_2169.geojson: FID 0: the polygon (129 km²) at "
                                        "scale 0.05 m would need about "));
  EXPECT_THAT(refused.output, HasSubstr("allowed (3/4 of this machine's memory)"));
  EXPECT_THAT(refused.output, ::testing::Not(HasSubstr("bad_alloc")));
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// The canton with furrows on a 4 m lattice avoiding the Moselle: straight furrows are written
// as straight runs (two points each, cut where the river passes), and the GeoPackage stays in
// proportion to the canton (the ~0.1 MB per km² of docs/shape-patterns.md, at 40 m a unit).
TEST(AreaCommand, ACantonOfFurrowsIsWrittenInProportionToItsArea) {
  TempDir dir;
  AreaCommand c;
  c.sketch = source_dir() / "samples/sketches/furrows.geojson";
  c.polygons = (source_dir() / "tests/data/lux_remich_2169.geojson").string();
  c.scale = 40.0;
  c.resolution = 4.0;
  c.avoid = {(source_dir() / "samples/lines_wgs84.geojson").string()};
  c.avoid_width = 60.0;
  c.out = dir / "out";
  const AreaCommandResult r = run_area_command(c);
  EXPECT_EQ(r.polygons, 1);
  EXPECT_GT(r.strokes, 1000);
  EXPECT_GT(r.forbidden, 0);  // the Moselle cuts furrows
  auto shapes = open_vector(dir / "out/shapes.gpkg");
  ASSERT_TRUE(shapes);
  OGRLayer* strokes = shapes->GetLayerByName("strokes");
  ASSERT_TRUE(strokes);
  for (auto& stroke : *strokes)
    ASSERT_EQ(stroke->GetGeometryRef()->toLineString()->getNumPoints(), 2) << stroke->GetFID();
  const double mb = double(fs::file_size(dir / "out/shapes.gpkg")) / 1e6;
  EXPECT_LT(mb / 129.0, 0.5) << mb << " MB";
}

}  // namespace
}  // namespace tw::test
