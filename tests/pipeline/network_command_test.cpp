// `terraweave network synthesize|complete|clone` through the CLI (issue #20, docs/networks.md):
// the GeoPackage holds suggestions that GEOS finds crossing nothing and inside the region, and
// names in its layers' metadata the command, its inputs and the method asked and chosen; the
// partial drawing comes back exactly, the same seed gives the same bytes, and every bad input is
// one line naming the file, key or FID with nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>

#include "commands/network_command.hpp"
#include "core/error.hpp"
#include "network/example_networks.hpp"
#include "pipeline/version.hpp"
#include "test_support.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const std::string kUtm31nCrsMember = R"("crs":{"type":"name","properties":{"name":"EPSG:32631"}})";

// `kinds`, when given: each line's "kind" property.
std::string lines_geojson(const std::vector<std::string>& coordinates,
                          const std::vector<std::string>& kinds = {}) {
  std::string features;
  for (std::size_t i = 0; i < coordinates.size(); ++i)
    features += std::string(i ? "," : "") + R"({"type":"Feature","id":)" + std::to_string(i + 1) +
                R"(,"properties":{)" +
                (kinds.empty() ? std::string() : R"("kind":")" + kinds[i] + "\"") +
                R"(},"geometry":{"type":"LineString","coordinates":)" + coordinates[i] + "}}";
  return R"({"type":"FeatureCollection",)" + kUtm31nCrsMember + R"(,"features":[)" + features +
         "]}";
}

// A small grid of fields in UTM 31N metres: its lines' coordinates.
std::vector<std::string> grid_lines() {
  std::vector<std::string> lines;
  for (int i = 0; i <= 6; ++i) {
    const int x = 500000 + i * 100;
    lines.push_back("[[" + std::to_string(x) + ",4000000],[" + std::to_string(x) + ",4000480]]");
  }
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i < 6; ++i) {
      if ((i + j) % 3 == 1 && j > 0 && j < 6) continue;
      const int y = 4000000 + j * 80 + ((i * 7 + j) % 3) * 6 * (j > 0 && j < 6);
      lines.push_back("[[" + std::to_string(500000 + i * 100) + "," + std::to_string(y) + "],[" +
                      std::to_string(500000 + (i + 1) * 100) + "," + std::to_string(y) + "]]");
    }
  return lines;
}
std::string grid_exemplar() {
  return lines_geojson(grid_lines());
}

struct Layer {
  std::vector<std::vector<std::pair<double, double>>> lines;
};
Layer read_layer(const fs::path& gpkg, const char* name) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                    nullptr, nullptr, nullptr));
  Layer out;
  if (!ds) return out;
  OGRLayer* layer = ds->GetLayerByName(name);
  if (!layer) return out;
  for (auto& f : *layer) {
    const OGRLineString* ls = f->GetGeometryRef()->toLineString();
    auto& line = out.lines.emplace_back();
    for (int i = 0; i < ls->getNumPoints(); ++i) line.push_back({ls->getX(i), ls->getY(i)});
  }
  return out;
}

// The metadata items of a layer of network.gpkg, read back through GDAL (empty: no such layer).
std::map<std::string, std::string> network_layer_metadata(const fs::path& gpkg, const char* name) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(gpkg.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                    nullptr, nullptr, nullptr));
  std::map<std::string, std::string> items;
  OGRLayer* layer = ds ? ds->GetLayerByName(name) : nullptr;
  if (!layer) return items;
  for (const char* const* item = layer->GetMetadata(); item && *item; ++item) {
    char* key = nullptr;
    const char* value = CPLParseNameValue(*item, &key);
    if (key && value) items[key] = value;
    CPLFree(key);
  }
  return items;
}

// GEOS: pairs of suggested lines meeting where neither ends.
int crossings(const Layer& layer) {
  int count = 0;
  for (std::size_t i = 0; i < layer.lines.size(); ++i)
    for (std::size_t j = i + 1; j < layer.lines.size(); ++j) {
      OGRLineString a, b;
      for (auto [x, y] : layer.lines[i]) a.addPoint(x, y);
      for (auto [x, y] : layer.lines[j]) b.addPoint(x, y);
      if (!a.Intersects(&b)) continue;
      std::unique_ptr<OGRGeometry> common(a.Intersection(&b));
      const auto end = [&](double x, double y) {
        for (const auto* l : {&layer.lines[i], &layer.lines[j]})
          for (auto p : {l->front(), l->back()})
            if (std::hypot(p.first - x, p.second - y) < 1e-6) return true;
        return false;
      };
      if (wkbFlatten(common->getGeometryType()) == wkbPoint) {
        if (!end(common->toPoint()->getX(), common->toPoint()->getY())) ++count;
      } else if (wkbFlatten(common->getGeometryType()) == wkbMultiPoint) {
        for (const OGRPoint* p : *common->toMultiPoint())
          if (!end(p->getX(), p->getY())) ++count;
      } else {
        ++count;
      }
    }
  return count;
}

class NetworkCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir / "fields.geojson") << grid_exemplar();
    exemplar = (dir / "fields.geojson").string();
  }
  CommandResult network(const std::string& args) {
    return run_command(terraweave_binary().string() + " network " + args + " 2>&1");
  }
  TempDir dir;
  std::string exemplar;
  const std::string region = "500000,4000000,500900,4000700";
};

TEST_F(NetworkCommandTest, SynthesizeWritesLinesThatNeverCrossInsideTheRegionSameBytes) {
  const CommandResult r = network("synthesize --exemplar " + exemplar + " --region " + region +
                                  " --seed 4 --out " + (dir / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("0 crossings"));
  const Layer s = read_layer(dir / "a/network.gpkg", "suggestions");
  ASSERT_GT(s.lines.size(), 20u);
  EXPECT_EQ(crossings(s), 0);
  for (const auto& line : s.lines)
    for (auto [x, y] : line) {
      EXPECT_GE(x, 500000 - 1e-6);
      EXPECT_LE(x, 500900 + 1e-6);
      EXPECT_GE(y, 4000000 - 1e-6);
      EXPECT_LE(y, 4000700 + 1e-6);
    }
  EXPECT_TRUE(fs::exists(dir / "a/preview.png"));
  ASSERT_EQ(network("synthesize --exemplar " + exemplar + " --region " + region +
                    " --seed 4 --out " + (dir / "b").string())
                .exit_code,
            0);
  EXPECT_EQ(read_file(dir / "a/network.gpkg"), read_file(dir / "b/network.gpkg"));
  EXPECT_EQ(read_file(dir / "a/preview.png"), read_file(dir / "b/preview.png"));
}

// `--lead long_axis` turns the exemplar to the region's long axis (a pipeline's `lead:
// long_axis`): over a box wider east-west, 90°, the same lines as `--lead-bearing 90`, other
// than the lines as drawn; over one taller north-south, 0°.
TEST_F(NetworkCommandTest, LeadLongAxisIsTheBearingOfTheRegionsLongAxis) {
  const auto lines = [&](const std::string& box, const std::string& lead, const std::string& name) {
    const CommandResult r = network("synthesize --exemplar " + exemplar + " --region " + box +
                                    " --seed 4 " + lead + " --out " + (dir / name).string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_layer(dir / name / "network.gpkg", "suggestions").lines;
  };
  const std::string wide = "500000,4000000,500900,4000500", tall = "500000,4000000,500500,4000900";
  const auto bearing = [&](const std::string& name) {
    return network_layer_metadata(dir / name / "network.gpkg", "suggestions")
        .at("TERRAWEAVE_LEAD_BEARING");
  };
  const auto axis_wide = lines(wide, "--lead long_axis", "a");
  ASSERT_GT(axis_wide.size(), 10u);
  EXPECT_NEAR(std::stod(bearing("a")), 90.0, 1e-6);
  EXPECT_EQ(axis_wide, lines(wide, "--lead-bearing " + bearing("a"), "b"));
  EXPECT_NE(axis_wide, lines(wide, "", "c"));
  const auto axis_tall = lines(tall, "--lead long_axis", "d");
  const double tall_bearing = std::stod(bearing("d"));
  EXPECT_LT(std::min(tall_bearing, 360.0 - tall_bearing), 1e-6) << tall_bearing;
  EXPECT_EQ(axis_tall, lines(tall, "--lead-bearing " + bearing("d"), "e"));
  EXPECT_EQ(network_layer_metadata(dir / "a/network.gpkg", "suggestions").at("TERRAWEAVE_LEAD"),
            "long_axis");
}

// The summary says which method made the network (issue #20): on the terraces `automatic` keeps
// the layout (tests/network/layout_test.cpp, same exemplar, region and seed); `--method growth`
// is growth.
TEST_F(NetworkCommandTest, TheSummaryNamesTheMethodAskedAndTheOneChosen) {
  const NetworkLines terraces = example_network("terraces", 400.0, 3);
  Warnings warnings;
  const Network noded = build_planar_network(terraces, 1e-3, "exemplar", warnings);
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : noded.nodes) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  std::vector<std::string> coordinates;
  for (const auto& line : terraces.lines) {
    std::string text;
    for (Vec2 p : line) text += fmt::format("{}[{},{}]", text.empty() ? "[" : ",", p.x, p.y);
    coordinates.push_back(text + "]");
  }
  std::ofstream(dir / "terraces.geojson") << lines_geojson(coordinates);
  const std::string args = "synthesize --exemplar " + (dir / "terraces.geojson").string() +
                           fmt::format(" --region={},{},{},{}", lo.x, lo.y, hi.x, hi.y) +
                           " --snap 0.001 --seed 1 --out ";
  const CommandResult automatic = network(args + (dir / "automatic").string());
  ASSERT_EQ(automatic.exit_code, 0) << automatic.output;
  EXPECT_THAT(automatic.output, HasSubstr("; method automatic, chose layout;"));
  const CommandResult grown = network(args + (dir / "growth").string() + " --method growth");
  ASSERT_EQ(grown.exit_code, 0) << grown.output;
  EXPECT_THAT(grown.output, HasSubstr("; method growth, chose growth;"));

  // network.gpkg says the same to whoever opens it later: on each of its layers, the command,
  // the method asked and chosen, the seed, the exemplar, the version and the summary's counts.
  std::map<std::string, std::string> chose_layout =
      network_layer_metadata(dir / "automatic/network.gpkg", "suggestions");
  EXPECT_EQ(chose_layout["TERRAWEAVE_COMMAND"], "network synthesize");
  EXPECT_EQ(chose_layout["TERRAWEAVE_NETWORK_METHOD"], "automatic");
  EXPECT_EQ(chose_layout["TERRAWEAVE_NETWORK_CHOSEN"], "layout");
  EXPECT_EQ(chose_layout["TERRAWEAVE_SEED"], "1");
  EXPECT_EQ(chose_layout["TERRAWEAVE_EXEMPLAR"], (dir / "terraces.geojson").string());
  EXPECT_EQ(chose_layout["TERRAWEAVE_REGION"], fmt::format("{},{},{},{}", lo.x, lo.y, hi.x, hi.y));
  EXPECT_EQ(chose_layout["TERRAWEAVE_VERSION"], kTerraweaveVersion);
  EXPECT_EQ(chose_layout.count("TERRAWEAVE_PARTIAL"), 0u);
  EXPECT_EQ(chose_layout["TERRAWEAVE_KEPT_EDGES"], "0");
  // The counts are the summary's: "N suggested edges, 0 kept, M nodes ... ; S seeds, ...".
  EXPECT_THAT(automatic.output,
              HasSubstr(chose_layout["TERRAWEAVE_SUGGESTED_EDGES"] + " suggested edges, 0 kept, " +
                        chose_layout["TERRAWEAVE_NODES"] + " nodes"));
  EXPECT_THAT(automatic.output,
              HasSubstr("; " + chose_layout["TERRAWEAVE_SEEDS"] + " seeds, " +
                        chose_layout["TERRAWEAVE_T_JUNCTIONS"] + " T-junctions, " +
                        chose_layout["TERRAWEAVE_SNAPPED"] + " snapped onto nodes"));
  EXPECT_EQ(network_layer_metadata(dir / "automatic/network.gpkg", "nodes"), chose_layout);
  const std::map<std::string, std::string> growth =
      network_layer_metadata(dir / "growth/network.gpkg", "suggestions");
  EXPECT_EQ(growth.at("TERRAWEAVE_NETWORK_METHOD"), "growth");
  EXPECT_EQ(growth.at("TERRAWEAVE_NETWORK_CHOSEN"), "growth");
}

TEST_F(NetworkCommandTest, CompleteKeepsTheDrawingExactlyAndCloneGrowsTheTarget) {
  std::ofstream(dir / "drawn.geojson")
      << lines_geojson({"[[500050.125,4000300.5],[500450.25,4000302.75]]",
                        "[[500450.25,4000302.75],[500449.5,4000650.0]]"});
  const CommandResult r =
      network("complete --exemplar " + exemplar + " --partial " + (dir / "drawn.geojson").string() +
              " --region " + region + " --out " + (dir / "c").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("; method automatic, chose growth;"));  // completing is growth
  const std::map<std::string, std::string> completed =
      network_layer_metadata(dir / "c/network.gpkg", "kept");
  EXPECT_EQ(completed.at("TERRAWEAVE_COMMAND"), "network complete");
  EXPECT_EQ(completed.at("TERRAWEAVE_NETWORK_METHOD"), "automatic");
  EXPECT_EQ(completed.at("TERRAWEAVE_NETWORK_CHOSEN"), "growth");
  EXPECT_EQ(completed.at("TERRAWEAVE_PARTIAL"), (dir / "drawn.geojson").string());
  EXPECT_THAT(r.output,
              HasSubstr(" suggested edges, " + completed.at("TERRAWEAVE_KEPT_EDGES") + " kept, "));
  const Layer kept = read_layer(dir / "c/network.gpkg", "kept");
  ASSERT_EQ(kept.lines.size(), 2u);
  EXPECT_EQ(kept.lines[0].front(), (std::pair{500050.125, 4000300.5}));
  EXPECT_EQ(kept.lines[1].back(), (std::pair{500449.5, 4000650.0}));
  Layer all = read_layer(dir / "c/network.gpkg", "suggestions");
  EXPECT_GT(all.lines.size(), 10u);
  all.lines.insert(all.lines.end(), kept.lines.begin(), kept.lines.end());
  EXPECT_EQ(crossings(all), 0);

  // Clone: the exemplar's western half into an empty box east of it.
  std::ofstream(dir / "source.geojson")
      << R"({"type":"FeatureCollection",)" + kUtm31nCrsMember +
             R"(,"features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[500000,4000000],[500350,4000000],[500350,4000480],[500000,4000480],[500000,4000000]]]}}]})";
  const CommandResult c =
      network("clone --map " + exemplar + " --source-region " + (dir / "source.geojson").string() +
              " --target-region 500700,4000000,501300,4000480 --out " + (dir / "d").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const Layer cloned = read_layer(dir / "d/network.gpkg", "suggestions");
  EXPECT_GT(cloned.lines.size(), 10u);
  EXPECT_EQ(crossings(cloned), 0);
}

// A box --target-region over part of the map keeps the map's lines there exactly (cut by the
// box) and grows around them without crossing them (it used to read the box as a file name and
// silently keep nothing).
TEST_F(NetworkCommandTest, CloneIntoABoxKeepsTheMapsLinesAlreadyThere) {
  std::ofstream(dir / "source.geojson")
      << R"({"type":"FeatureCollection",)" + kUtm31nCrsMember +
             R"(,"features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[500000,4000000],[500350,4000000],[500350,4000480],[500000,4000480],[500000,4000000]]]}}]})";
  const CommandResult c =
      network("clone --map " + exemplar + " --source-region " + (dir / "source.geojson").string() +
              " --target-region 500350,4000000,500950,4000480 --out " + (dir / "d").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const Layer kept = read_layer(dir / "d/network.gpkg", "kept");
  // The map's lines east of x = 350: 3 whole verticals (400, 500, 600), the one at 300 outside,
  // and the horizontal pieces there.
  ASSERT_GE(kept.lines.size(), 10u);
  int verticals = 0;
  for (const auto& line : kept.lines) {
    for (auto [x, y] : line) {
      EXPECT_GE(x, 500350 - 1e-6);
      EXPECT_LE(x, 500600 + 1e-6);
    }
    verticals += line.front().first == line.back().first &&
                 std::abs(line.front().second - line.back().second) == 480.0;
  }
  EXPECT_EQ(verticals, 3);
  Layer all = read_layer(dir / "d/network.gpkg", "suggestions");
  EXPECT_GT(all.lines.size(), 3u);  // the strip east of the map is grown
  all.lines.insert(all.lines.end(), kept.lines.begin(), kept.lines.end());
  EXPECT_EQ(crossings(all), 0);
}

// A box --source-region is the source's polygon, as `--help` says (it was opened as a file name:
// "cannot open as vector data").
TEST_F(NetworkCommandTest, CloneFromABoxSourceRegion) {
  const CommandResult c =
      network("clone --map " + exemplar + " --source-region 500000,4000000,500350,4000480" +
              " --target-region 500700,4000000,501300,4000480 --out " + (dir / "d").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const Layer cloned = read_layer(dir / "d/network.gpkg", "suggestions");
  EXPECT_GT(cloned.lines.size(), 10u);
  EXPECT_EQ(crossings(cloned), 0);
}

// An SVG map is cut by both regions like any map: the lines already in the target are kept as cut
// by it (they were kept whole and refused as outside the region or crossing).
TEST_F(NetworkCommandTest, CloneOfAnSvgMapKeepsItsLinesInTheTarget) {
  // The grid exemplar's layout in SVG units (1 m each; y down, so the map lies at y in -480..0).
  std::string paths;
  for (int i = 0; i <= 6; ++i)
    paths +=
        "<path d=\"M " + std::to_string(i * 100) + " 0 L " + std::to_string(i * 100) + " 480\"/>";
  for (int j = 0; j <= 6; ++j)
    for (int i = 0; i < 6; ++i) {
      if ((i + j) % 3 == 1 && j > 0 && j < 6) continue;
      const std::string y = std::to_string(j * 80 + ((i * 7 + j) % 3) * 6 * (j > 0 && j < 6));
      paths += "<path d=\"M " + std::to_string(i * 100) + " " + y + " L " +
               std::to_string((i + 1) * 100) + " " + y + "\"/>";
    }
  std::ofstream(dir / "map.svg") << "<svg>" + paths + "</svg>";
  const CommandResult c = network("clone --map " + (dir / "map.svg").string() +
                                  " --source-region 0,-480,350,0 --target-region 350,-480,950,0" +
                                  " --out " + (dir / "d").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  const Layer kept = read_layer(dir / "d/network.gpkg", "kept");
  ASSERT_GE(kept.lines.size(), 10u);
  for (const auto& line : kept.lines)
    for (auto [x, y] : line) {
      EXPECT_GE(x, 350 - 1e-6);
      EXPECT_LE(x, 600 + 1e-6);
    }
  Layer all = read_layer(dir / "d/network.gpkg", "suggestions");
  EXPECT_GT(all.lines.size(), 3u);
  all.lines.insert(all.lines.end(), kept.lines.begin(), kept.lines.end());
  EXPECT_EQ(crossings(all), 0);
}

// A map's lines crossing where neither ends (an SVG grid of full-length lines) are map data in the
// target: noded like the exemplar, with a warning per crossing naming both FIDs (they were read
// like a drawing and refused: "FID 3 crosses FID 6 (a partial network may meet itself only where
// a line ends)"). The kept layer still holds them exactly as cut by the target.
TEST_F(NetworkCommandTest, CloneNodesTheMapsCrossingLinesInTheTarget) {
  // Verticals x = 0..600 and horizontals y = 40..440 (SVG units, 1 m), each the map's full length.
  std::string paths;
  for (int i = 0; i <= 6; ++i)
    paths += "<line x1=\"" + std::to_string(i * 100) + "\" y1=\"0\" x2=\"" +
             std::to_string(i * 100) + "\" y2=\"480\"/>";
  for (int j = 0; j < 6; ++j)
    paths += "<line x1=\"0\" y1=\"" + std::to_string(40 + j * 80) + "\" x2=\"600\" y2=\"" +
             std::to_string(40 + j * 80 + (j % 2) * 3) + "\"/>";
  std::ofstream(dir / "crossing_map.svg") << "<svg>" + paths + "</svg>";
  const CommandResult c = network("clone --map " + (dir / "crossing_map.svg").string() +
                                  " --source-region 0,-480,350,0 --target-region 350,-480,950,0" +
                                  " --seed 4 --out " + (dir / "d").string());
  ASSERT_EQ(c.exit_code, 0) << c.output;
  // In the target, the verticals at 400 and 500 cross the six horizontals (the one at 600 is
  // where they end): 12 crossings, each warned once, naming the vertical (elements 4, 5) first.
  std::size_t warned = 0;
  for (std::size_t at = c.output.find("noded into a junction"); at != std::string::npos;
       at = c.output.find("noded into a junction", at + 1))
    ++warned;
  EXPECT_EQ(warned, 12u) << c.output;
  EXPECT_THAT(c.output, HasSubstr("--map (in --target-region): FID 4: crosses FID 7 where neither "
                                  "ends: noded into a junction there"));
  const Layer kept = read_layer(dir / "d/network.gpkg", "kept");
  ASSERT_EQ(kept.lines.size(), 9u);  // 3 verticals, 6 horizontals from x = 350 to 600
  for (const auto& line : kept.lines)
    for (auto [x, y] : line) {
      EXPECT_GE(x, 350 - 1e-6);
      EXPECT_LE(x, 600 + 1e-6);
    }
  const Layer suggested = read_layer(dir / "d/network.gpkg", "suggestions");
  EXPECT_GT(suggested.lines.size(), 3u);  // the strip east of the map is grown
  EXPECT_EQ(crossings(suggested), 0);
  // The suggestions cross no kept line: every crossing of the whole is one of the map's own.
  Layer all = suggested;
  all.lines.insert(all.lines.end(), kept.lines.begin(), kept.lines.end());
  EXPECT_EQ(crossings(all), crossings(kept));
  EXPECT_EQ(crossings(kept), 12);

  // A user's drawing keeps its strict rule: the same lines as --partial are refused.
  const CommandResult drawn = network("complete --exemplar " + (dir / "crossing_map.svg").string() +
                                      " --partial " + (dir / "crossing_map.svg").string() +
                                      " --region 0,-480,600,0 --out " + (dir / "e").string());
  EXPECT_NE(drawn.exit_code, 0);
  EXPECT_THAT(drawn.output, HasSubstr("crosses FID"));
  EXPECT_FALSE(fs::exists(dir / "e"));
}

// `--where` keeps a subset of the grid: the sparser exemplar's pieces meet the target's lattice
// of seeds exactly, where growth used to leave lines meeting off a node ("4 crossings ... (a
// growth bug)").
class NetworkCloneWhere : public NetworkCommandTest {
 protected:
  // The lines (counted from 1) whose number is a multiple of `every` are of kind `multiples`,
  // the others of the other kind; the 'a' lines are cloned.
  void clone_kind_a(int every, const std::string& multiples, const std::string& seed) {
    const std::string others = multiples == "a" ? "b" : "a";
    std::vector<std::string> kinds;
    for (std::size_t i = 1; i <= grid_lines().size(); ++i)
      kinds.push_back(i % std::size_t(every) ? others : multiples);
    std::ofstream(dir / "kinds.geojson") << lines_geojson(grid_lines(), kinds);
    std::ofstream(dir / "source.geojson")
        << R"({"type":"FeatureCollection",)" + kUtm31nCrsMember +
               R"(,"features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[500000,4000000],[500350,4000000],[500350,4000480],[500000,4000480],[500000,4000000]]]}}]})";
    const CommandResult c =
        network("clone --map " + (dir / "kinds.geojson").string() +
                " --where \"kind = 'a'\" --source-region " + (dir / "source.geojson").string() +
                " --target-region 500700,4000000,501300,4000480 " + seed + " --out " +
                (dir / "d").string());
    ASSERT_EQ(c.exit_code, 0) << c.output;
    const Layer grown = read_layer(dir / "d/network.gpkg", "suggestions");
    EXPECT_GT(grown.lines.size(), 5u);
    EXPECT_EQ(crossings(grown), 0);
  }
};

// A dangling end joined straight ahead exactly onto another edge's end node is joined to that
// node (it split the edge there, leaving a one-point piece).
TEST_F(NetworkCloneWhere, DanglingEndsMeetingANodeJoinIt) {
  clone_kind_a(2, "a", "--seed 4");
}

// A piece ended exactly on a seed whose stubs had found nothing yet (a node without edges).
TEST_F(NetworkCloneWhere, PiecesKeepOffSeedsWithoutEdges) {
  clone_kind_a(3, "b", "");
}

TEST_F(NetworkCommandTest, BadInputIsOneLineAndNothingIsWritten) {
  std::ofstream(dir / "one.geojson") << lines_geojson({"[[500000,4000000],[500100,4000000]]"});
  std::ofstream(dir / "bad.svg")
      << R"(<svg><path d="M 0 0 L 10 0"/><rect x="1" y="1" width="2" height="2"/></svg>)";
  std::ofstream(dir / "crossing.geojson") << lines_geojson(
      {"[[500100,4000100],[500300,4000300]]", "[[500100,4000300],[500300,4000100]]"});
  std::ofstream(dir / "outside.geojson") << lines_geojson(
      {"[[500100,4000100],[500300,4000100]]", "[[500300,4000100],[509000,4000100]]"});
  std::ofstream(dir / "loop.geojson")
      << lines_geojson({"[[500100,4000100],[500300,4000300],[500300,4000100],[500100,4000300]]"});
  std::ofstream(dir / "empty.geojson") << lines_geojson({});
  std::ofstream(dir / "flat.geojson")
      << R"({"type":"FeatureCollection",)" + kUtm31nCrsMember +
             R"(,"features":[{"type":"Feature","id":3,"properties":{},"geometry":{"type":"Polygon","coordinates":[[[500000,4000000],[500500,4000000],[500900,4000000],[500000,4000000]]]}}]})";
  const std::string out = (dir / "never").string();
  const struct {
    std::string args, message;
  } cases[] = {
      {"synthesize --exemplar " + (dir / "one.geojson").string() + " --region " + region,
       "one.geojson: FID 1: a single line"},
      {"synthesize --exemplar " + (dir / "bad.svg").string() + " --region 0,0,10,10",
       "bad.svg: element 1 <rect>: not supported"},
      {"synthesize --exemplar " + exemplar + " --region 500000,4000000,500000,4000700",
       "--region 500000,4000000,500000,4000700: a degenerate (zero-area) box"},
      {"synthesize --exemplar " + exemplar + " --region 0,0,1000000,1000000",
       "1000000 km² is too large"},
      {"complete --exemplar " + exemplar + " --partial " + (dir / "crossing.geojson").string() +
           " --region " + region,
       "crossing.geojson: FID 1 crosses FID 2"},
      {"complete --exemplar " + exemplar + " --partial " + (dir / "outside.geojson").string() +
           " --region " + region,
       "outside.geojson: FID 2: outside the region"},
      {"complete --exemplar " + exemplar + " --partial " + (dir / "loop.geojson").string() +
           " --region " + region,
       "--partial " + (dir / "loop.geojson").string() + ": FID 1 crosses itself"},
      {"synthesize --exemplar " + (dir / "empty.geojson").string() + " --region " + region,
       "--exemplar " + (dir / "empty.geojson").string() + ": no lines"},
      {"synthesize --exemplar " + exemplar + " --region " + (dir / "flat.geojson").string(),
       "--region " + (dir / "flat.geojson").string() + ": FID 3: a degenerate (zero-area) polygon"},
      {"clone --map " + exemplar + " --source-region " + (dir / "flat.geojson").string() +
           " --target-region " + region,
       "flat.geojson: FID 3: a degenerate (zero-area) polygon"},
      // Completing lines is growth (docs/networks.md, "Which method"): the quilt and the layout
      // are refused, for a drawing and for a clone's target that holds some of the map's lines.
      {"complete --method quilt --exemplar " + exemplar + " --partial " +
           (dir / "one.geojson").string() + " --region " + region,
       "network complete: --method quilt cannot complete a drawing"},
      {"clone --method quilt --map " + exemplar + " --source-region 500000,4000000,500350,4000480" +
           " --target-region 500350,4000000,500950,4000480",
       "--target-region 500350,4000000,500950,4000480 holds"},
      {"complete --method layout --exemplar " + exemplar + " --partial " +
           (dir / "one.geojson").string() + " --region " + region,
       "network complete: --method layout cannot complete a drawing"},
      {"clone --method layout --map " + exemplar +
           " --source-region 500000,4000000,500350,4000480" +
           " --target-region 500350,4000000,500950,4000480",
       "network clone: --method layout: --target-region 500350,4000000,500950,4000480 holds"},
      // The command follows the region's long axis; the other leads read a run's roads and DEM.
      {"synthesize --lead contours --exemplar " + exemplar + " --region " + region,
       "network synthesize: --lead contours: the command follows long_axis only"},
      {"synthesize --lead long_axis --lead-bearing 30 --exemplar " + exemplar + " --region " +
           region,
       "give --lead or --lead-bearing, not both"},
  };
  for (const auto& c : cases) {
    const CommandResult r = network(c.args + " --out " + out);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_THAT(r.output, HasSubstr(c.message)) << r.output;
    EXPECT_THAT(r.output, HasSubstr("terraweave: error:"));
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace tw::test

namespace tw::test {
namespace {

// The drawing page's completion (docs/networks.md, "Drawing"): the library call the server makes.
class NetworkDrawing : public NetworkCommandTest {
 protected:
  Network exemplar_network() {
    Warnings warnings;
    return read_network_exemplar({.source = exemplar}, 0.0, warnings);
  }
  const std::vector<Polygon> box{
      {{{500000, 4000000}, {500900, 4000000}, {500900, 4000700}, {500000, 4000700}}}};
};

TEST_F(NetworkDrawing, CrossingStrokesAreRefusedNamingThem) {
  NetworkLines drawn;
  drawn.lines = {{{500100, 4000100}, {500300, 4000300}}, {{500100, 4000300}, {500300, 4000100}}};
  drawn.fids = {1, 2};
  std::string message;
  try {
    complete_drawing(exemplar_network(), drawn, box, nullptr, {});
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_THAT(message, HasSubstr("drawing (lines numbered from 1): FID 1 crosses FID 2"));
}

// A stroke leaving the region is cut there and kept; suggestions cross neither it nor the
// forbidden band, and stay in the region.
TEST_F(NetworkDrawing, SuggestionsKeepOffTheStrokeAndTheForbiddenCells) {
  NetworkLines drawn;
  drawn.lines = {{{499800, 4000350}, {500400, 4000350}}};
  drawn.fids = {1};
  ForbiddenMask forbidden;
  forbidden.grid = {.width = 100,
                    .height = 80,
                    .origin_x = 500000,
                    .origin_y = 4000800,
                    .pixel_width = 10,
                    .pixel_height = 10};
  forbidden.cells = Raster<std::uint8_t>(100, 80);
  for (int r = 0; r < 80; ++r)
    for (int c = 65; c < 68; ++c) forbidden.cells.at(c, r) = 1;  // x 500650..500680
  const auto suggestions = complete_drawing(exemplar_network(), drawn, box, &forbidden, {});
  ASSERT_GT(suggestions.size(), 10u);
  OGRLinearRing ring;
  for (auto [x, y] : {std::pair{500650.5, 3999000.0},
                      {500679.5, 3999000.0},
                      {500679.5, 4001000.0},
                      {500650.5, 4001000.0},
                      {500650.5, 3999000.0}})
    ring.addPoint(x, y);
  OGRPolygon band;
  band.addRing(&ring);
  Layer all;
  for (const auto& s : suggestions) {
    auto& line = all.lines.emplace_back();
    OGRLineString ls;
    for (Vec2 p : s) {
      line.push_back({p.x, p.y});
      ls.addPoint(p.x, p.y);
      EXPECT_GE(p.x, 500000 - 1e-6);
      EXPECT_LE(p.x, 500900 + 1e-6);
    }
    EXPECT_FALSE(ls.Intersects(&band));
  }
  all.lines.push_back({{500000, 4000350}, {500400, 4000350}});  // the stroke as cut
  EXPECT_EQ(crossings(all), 0);
}

TEST_F(NetworkDrawing, ViewOptionsOfTheDrawingPageNeedServe) {
  const CommandResult r =
      run_command(terraweave_binary().string() + " view nowhere --exemplar x.svg 2>&1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("view: --exemplar needs --serve"));
  const CommandResult s =
      run_command(terraweave_binary().string() + " view nowhere --serve 0 --save a.gpkg 2>&1");
  EXPECT_EQ(s.exit_code, 1);
  EXPECT_THAT(s.output, HasSubstr("view: --save needs --exemplar"));
}

}  // namespace
}  // namespace tw::test
