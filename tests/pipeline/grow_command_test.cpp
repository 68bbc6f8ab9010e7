// `terraweave grow` on the demo DEM (issue #13 B): ornaments come back as GeoPackage lines
// that stay in the region and off the roads, the same seed gives the same lines, and a bad
// element file is one error naming the key with nothing written. Every option of the command
// changes what it writes (issue #24: six of them were shadowed and changed nothing).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "commands/grow_command.hpp"
#include "core/error.hpp"
#include "option_table.hpp"
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
  std::string kind, name;
  int ornament = 0;
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
    line.name = f->GetFieldAsString("name");
    line.ornament = f->GetFieldAsInteger("ornament");
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
  // Four words that are not numbers: a mistyped box, said as such rather than "cannot open".
  c.region = "a,b,c,d";
  try {
    run_grow_command(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("--region a,b,c,d: neither a polygon file nor a box of four "
                                    "numbers minx,miny,maxx,maxy"));
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
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

// Issue #24 item 8: --strict applies to grow as to run: a warning fails it, writing nothing.
TEST(GrowCommand, StrictFailsOnAWarningAndWritesNothing) {
  TempDir dir;
  write_bowtie(dir / "bowtie.geojson");
  const std::string args = " grow --dem " + (source_dir() / "samples/dem.tif").string() +
                           " --region " + (dir / "bowtie.geojson").string() + " --element " +
                           (source_dir() / "samples/ornaments/hedge.json").string() + " --out ";
  const auto strict = run_command(terraweave_binary().string() + " -q" + args +
                                  (dir / "strict").string() + " --strict 2>&1");
  EXPECT_EQ(strict.exit_code, 1);
  EXPECT_THAT(strict.output, HasSubstr("strict: 1 warning (first: grow.region: FID 0: "));
  EXPECT_THAT(strict.output, HasSubstr("nothing written"));
  EXPECT_FALSE(fs::exists(dir / "strict"));
  const auto plain =
      run_command(terraweave_binary().string() + " -q" + args + (dir / "plain").string() + " 2>&1");
  EXPECT_EQ(plain.exit_code, 0) << plain.output;
  EXPECT_TRUE(fs::exists(dir / "plain/ornaments.gpkg"));
}

// What a `terraweave grow` run printed and wrote: its summary line and every line of
// ornaments.gpkg with its attributes, as text (two runs compare equal when these are equal).
struct GrowOutput {
  int exit_code = 0;
  std::string summary, lines;
};

// Issue #24: each row changes one option of `terraweave grow` from value A to value B over the
// same base command on the demo DEM; the output must change (or, for the one option documented
// as not changing it, stay the same). The table must name every option `grow --help` lists,
// so an option added later without a row fails here, and one ignored again fails its row.
class GrowOptions : public ::testing::Test {
 protected:
  using Args = std::map<std::string, std::string>;  // option -> value ("" for a flag)
  static constexpr const char* kAbsent = "<absent>";

  void SetUp() override {
    // Two 200 m boxes on the hillside, for --region as polygons and --where; a track without a
    // width attribute across it, for --avoid-width.
    std::ofstream(dir / "fields.geojson") << R"({"type": "FeatureCollection",
      "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::31985"}},
      "features": [
      {"type": "Feature", "properties": {"name": "upper"}, "geometry": {"type": "Polygon",
       "coordinates": [[[291200, 9115250], [291400, 9115250], [291400, 9115400],
                        [291200, 9115400], [291200, 9115250]]]}},
      {"type": "Feature", "properties": {"name": "lower"}, "geometry": {"type": "Polygon",
       "coordinates": [[[291300, 9115100], [291500, 9115100], [291500, 9115250],
                        [291300, 9115250], [291300, 9115100]]]}}]})";
    std::ofstream(dir / "track.geojson") << R"({"type": "FeatureCollection",
      "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::31985"}},
      "features": [{"type": "Feature", "properties": {}, "geometry": {"type": "LineString",
       "coordinates": [[291350, 9115050], [291350, 9115450]]}}]})";
    // The demo DEM with every height doubled: the same ground, steeper.
    GDALAllRegister();
    std::unique_ptr<GDALDataset> dem(GDALDataset::Open((source_dir() / "samples/dem.tif").c_str(),
                                                       GDAL_OF_RASTER, nullptr, nullptr, nullptr));
    ASSERT_TRUE(dem);
    std::unique_ptr<GDALDataset> steep(GetGDALDriverManager()->GetDriverByName("GTiff")->CreateCopy(
        (dir / "steep.tif").c_str(), dem.get(), false, nullptr, nullptr, nullptr));
    ASSERT_TRUE(steep);
    GDALRasterBand* band = steep->GetRasterBand(1);
    const int w = band->GetXSize(), h = band->GetYSize();
    std::vector<float> heights(std::size_t(w) * h);
    ASSERT_EQ(band->RasterIO(GF_Read, 0, 0, w, h, heights.data(), w, h, GDT_Float32, 0, 0),
              CE_None);
    for (float& v : heights) v *= 2.0f;
    ASSERT_EQ(band->RasterIO(GF_Write, 0, 0, w, h, heights.data(), w, h, GDT_Float32, 0, 0),
              CE_None);
  }

  static Args base() {
    const std::string samples = (source_dir() / "samples").string();
    return {{"--dem", samples + "/dem.tif"},
            {"--region", "291200,9115100,291500,9115400"},  // the West spur road crosses it
            {"--where", kAbsent},
            {"--element", samples + "/ornaments/hedge.json"},
            {"--avoid", kAbsent},
            {"--avoid-width", kAbsent},
            {"--resolution", "10"},
            {"--seed", "7"},
            {"--contour", kAbsent},
            {"--first-fit", kAbsent},
            {"--trials", kAbsent},
            {"--max-ornaments", "4"},
            {"--clearance", kAbsent},
            {"--coverage-radius", kAbsent},
            {"--out", "out"}};
  }

  GrowOutput grow(Args args) {
    std::string line =
        "cd '" + dir.path().string() + "' && '" + terraweave_binary().string() + "' -q grow";
    for (const auto& [option, value] : args) {
      if (value == kAbsent) continue;
      std::string quoted = "'";  // a shell word: ' as '\''
      for (char ch : value) quoted += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
      line += " " + option + (value.empty() ? "" : " " + quoted + "'");
    }
    const auto cached = runs_.find(line);
    if (cached != runs_.end()) return cached->second;
    const fs::path out = dir / args.at("--out");
    fs::remove_all(out);
    const CommandResult r = run_command(line);
    GrowOutput output;
    output.exit_code = r.exit_code;
    output.summary = r.output;
    for (const ReadLine& l : read_lines(out / "ornaments.gpkg")) {
      output.lines += l.kind + " " + l.name + " " + std::to_string(l.ornament) + ":";
      for (const auto& p : l.points) output.lines += fmt::format(" {} {} {}", p[0], p[1], p[2]);
      output.lines += "\n";
    }
    return runs_[line] = output;
  }

  TempDir dir;
  std::map<std::string, GrowOutput> runs_;
};

TEST_F(GrowOptions, EveryOptionChangesTheOutput) {
  const std::string samples = (source_dir() / "samples").string();
  const std::string fields = (dir / "fields.geojson").string();
  const std::string roads = samples + "/map.gpkg:roads";       // with a width attribute
  const std::string track = (dir / "track.geojson").string();  // without
  struct Row {
    std::string option;
    Args a, b;  // overrides of base()
    bool changes = true;
  };
  const std::vector<Row> table = {
      {"--dem", {}, {{"--dem", (dir / "steep.tif").string()}}},
      {"--region", {}, {{"--region", "291250,9115150,291550,9115450"}}},
      {"--where",
       {{"--region", fields}, {"--where", "name = 'upper'"}},
       {{"--region", fields}, {"--where", "name = 'lower'"}}},
      {"--element", {}, {{"--element", samples + "/ornaments/ditch.json"}}},
      {"--avoid", {}, {{"--avoid", roads}}},
      {"--avoid-width",
       {{"--avoid", track}, {"--avoid-width", "6"}},
       {{"--avoid", track}, {"--avoid-width", "60"}}},
      {"--resolution", {}, {{"--resolution", "8"}}},
      {"--seed", {}, {{"--seed", "8"}}},
      {"--contour", {}, {{"--contour", ""}}},
      {"--first-fit", {}, {{"--first-fit", ""}}},
      {"--trials", {}, {{"--trials", "2"}}},
      {"--max-ornaments", {}, {{"--max-ornaments", "1"}}},
      {"--clearance", {}, {{"--clearance", "15"}}},
      {"--coverage-radius", {}, {{"--coverage-radius", "25"}}},  // the coverage printed
      // Where the files go, not what they hold: documented in docs/ornaments.md.
      {"--out", {}, {{"--out", "elsewhere"}}, false},
  };
  // Every option the command lists has a row (its own options: not the global ones).
  const std::set<std::string> listed = help_options("grow");
  std::set<std::string> tabled;
  for (const Row& row : table) tabled.insert(row.option);
  EXPECT_EQ(listed, tabled) << "grow --help lists options the table does not, or the reverse";
  for (const Row& row : table) {
    Args a = base(), b = base();
    for (const auto& [k, v] : row.a) a[k] = v;
    for (const auto& [k, v] : row.b) b[k] = v;
    const GrowOutput out_a = grow(a), out_b = grow(b);
    // Every row is tried (and reported) even when one fails.
    EXPECT_EQ(out_a.exit_code, 0) << row.option << ": " << out_a.summary;
    EXPECT_EQ(out_b.exit_code, 0) << row.option << ": " << out_b.summary;
    EXPECT_FALSE(out_a.lines.empty()) << row.option;
    EXPECT_FALSE(out_b.lines.empty()) << row.option;
    if (out_a.exit_code != 0 || out_b.exit_code != 0) continue;
    const bool changed = out_a.summary != out_b.summary || out_a.lines != out_b.lines;
    EXPECT_EQ(changed, row.changes)
        << row.option << ": A " << out_a.summary << "B " << out_b.summary;
    std::printf("%-18s %s", row.option.c_str(), out_b.summary.c_str());
  }
}

}  // namespace
}  // namespace tw::test
