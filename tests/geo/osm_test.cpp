#include <gdal_priv.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <GeographicLib/UTMUPS.hpp>

#include <fmt/format.h>

#include <cpl_conv.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "geo/features.hpp"
#include "geo/osm_tags.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

TEST(OsmTags, WidthTagInMetresWinsOverLanesAndClass) {
  EXPECT_EQ(osm_width({"7.5", "4", "primary", "", ""}).metres, 7.5);
  EXPECT_EQ(osm_width({"6 m", "", "residential", "", ""}).metres, 6.0);
  EXPECT_EQ(osm_width({"3m", "", "", "stream", ""}).metres, 3.0);
  EXPECT_EQ(osm_width({"6 m", "", "residential", "", ""}).from, "width=6 m");
}

TEST(OsmTags, LanesTimesLaneWidthWhenNoUsableWidth) {
  const OsmWidth lanes = osm_width({"", "3", "primary", "", ""});
  EXPECT_EQ(lanes.metres, 3 * kOsmLaneWidth);
  EXPECT_EQ(lanes.from, "lanes=3");
  // Feet are not metres: skipped with a problem, the lanes decide.
  const OsmWidth feet = osm_width({"12'", "2", "primary", "", ""});
  EXPECT_EQ(feet.metres, 7.0);
  EXPECT_THAT(feet.problem, HasSubstr("width=12'"));
}

TEST(OsmTags, ClassDefaultsFromTheTable) {
  EXPECT_EQ(osm_width({"", "", "primary", "", ""}).metres, 7.0);
  EXPECT_EQ(osm_width({"", "", "residential", "", ""}).metres, 5.5);
  EXPECT_EQ(osm_width({"", "", "track", "", ""}).metres, 3.0);
  EXPECT_EQ(osm_width({"", "", "path", "", ""}).metres, 1.5);
  EXPECT_EQ(osm_width({"", "", "motorway", "", ""}).metres, 11.0);
  EXPECT_EQ(osm_width({"", "", "", "river", ""}).metres, 20.0);
  EXPECT_EQ(osm_width({"", "", "", "canal", ""}).metres, 10.0);
  EXPECT_EQ(osm_width({"", "", "", "", "arete"}).metres, 15.0);
  // A bad lane count falls through to the class, with a problem.
  const OsmWidth bad_lanes = osm_width({"", "two", "residential", "", ""});
  EXPECT_EQ(bad_lanes.metres, 5.5);
  EXPECT_EQ(bad_lanes.from, "highway=residential");
  EXPECT_THAT(bad_lanes.problem, HasSubstr("lanes=two"));
  EXPECT_FALSE(osm_width({"", "", "proposed", "", ""}).metres.has_value());
  EXPECT_FALSE(osm_width({"", "", "", "", ""}).metres.has_value());
}

TEST(OsmTags, KindsOfSelectingKeys) {
  EXPECT_EQ(osm_kind_of_key("highway"), "road");
  EXPECT_EQ(osm_kind_of_key("waterway"), "river");
  EXPECT_EQ(osm_kind_of_key("natural"), "ridge");
  EXPECT_EQ(osm_kind_of_key("landuse"), "");
}

TEST(OsmTags, BridgesTunnelsAndLayers) {
  EXPECT_EQ(osm_structure("yes", ""), Structure::bridge);
  EXPECT_EQ(osm_structure("viaduct", ""), Structure::bridge);
  EXPECT_EQ(osm_structure("no", "yes"), Structure::tunnel);
  EXPECT_EQ(osm_structure("", "culvert"), Structure::tunnel);
  EXPECT_EQ(osm_structure("", "building_passage"), Structure::ground);
  EXPECT_EQ(osm_structure("no", "no"), Structure::ground);
  EXPECT_EQ(osm_structure("0", ""), Structure::ground);  // a GeoPackage integer column
  EXPECT_EQ(osm_structure("1", ""), Structure::bridge);
  EXPECT_EQ(parse_osm_layer("-1"), -1);
  EXPECT_EQ(parse_osm_layer(" 2 "), 2);
  EXPECT_FALSE(parse_osm_layer("1;2").has_value());
  EXPECT_FALSE(parse_osm_layer("").has_value());
  EXPECT_TRUE(meet_at_grade(Structure::ground, 0, Structure::ground, 0));
  EXPECT_FALSE(meet_at_grade(Structure::ground, 0, Structure::ground, 1));
  EXPECT_FALSE(meet_at_grade(Structure::bridge, 0, Structure::ground, 0));
  EXPECT_FALSE(meet_at_grade(Structure::ground, -1, Structure::tunnel, -1));
}

// OSM XML over test::small_utm_grid (UTM 31N x 500000..501000, y 4999000..5000000); nodes are
// placed at UTM coordinates through GeographicLib.
class OsmSource : public ::testing::Test {
 protected:
  Heightfield grid = test::small_utm_grid();
  test::TempDir dir;
  std::map<int, Vec2> utm_of_node;

  std::string node(int id, double x, double y) {
    utm_of_node[id] = {x, y};
    double lat = 0.0, lon = 0.0;
    GeographicLib::UTMUPS::Reverse(31, true, x, y, lat, lon);
    return fmt::format(R"(  <node id="{}" version="1" lat="{:.9f}" lon="{:.9f}"/>)", id, lat, lon) +
           "\n";
  }
  static std::string way(int id, std::vector<int> nodes,
                         std::vector<std::pair<std::string, std::string>> tags) {
    std::string text = fmt::format(R"(  <way id="{}" version="1">)", id) + "\n";
    for (const int n : nodes) text += fmt::format(R"(    <nd ref="{}"/>)", n) + "\n";
    for (const auto& [k, v] : tags) text += fmt::format(R"(    <tag k="{}" v="{}"/>)", k, v) + "\n";
    return text + "  </way>\n";
  }
  std::string write_osm() {
    std::string xml = R"(<?xml version="1.0" encoding="UTF-8"?>)"
                      "\n<osm version=\"0.6\" generator=\"terraweave test\">\n";
    xml += node(1, 500100, 4999500) + node(2, 500300, 4999500) + node(3, 500500, 4999500);
    xml += node(4, 500100, 4999200) + node(5, 500900, 4999200);
    xml += node(6, 500100, 4999800) + node(7, 500900, 4999800);
    xml += node(8, 500600, 4999100) + node(9, 500600, 4999900);
    xml += way(101, {1, 2}, {{"highway", "primary"}, {"name", "Approach"}});
    xml += way(102, {2, 3}, {{"highway", "primary"}, {"bridge", "yes"}, {"layer", "1"}});
    xml += way(103, {4, 5},
               {{"highway", "track"}, {"tunnel", "yes"}, {"layer", "-1"}, {"lanes", "x"}});
    xml += way(104, {6, 7}, {{"highway", "residential"}, {"width", "6 m"}, {"layer", "1;2"}});
    xml += way(105, {8, 9}, {{"waterway", "stream"}});
    xml += "</osm>\n";
    const std::string path = (dir / "map.osm").string();
    std::ofstream(path) << xml;
    return path;
  }
};

TEST_F(OsmSource, LinesWithTagWidthsStructuresAndLayers) {
  LineClassSpec spec;
  spec.name = "roads";
  spec.source = {write_osm(), "lines", "highway IS NOT NULL"};
  spec.osm_widths = true;
  Warnings warnings;
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 4u);
  // FIDs are the OSM way ids.
  EXPECT_EQ(lines[0].fid, 101);
  EXPECT_EQ(lines[0].width, 7.0);  // highway=primary
  EXPECT_EQ(lines[0].structure, Structure::ground);
  EXPECT_EQ(lines[1].fid, 102);
  EXPECT_EQ(lines[1].structure, Structure::bridge);
  EXPECT_EQ(lines[1].layer, 1);
  EXPECT_EQ(lines[2].fid, 103);
  EXPECT_EQ(lines[2].structure, Structure::tunnel);
  EXPECT_EQ(lines[2].layer, -1);
  EXPECT_EQ(lines[2].width, 3.0);  // lanes=x is skipped: highway=track
  EXPECT_EQ(lines[3].fid, 104);
  EXPECT_EQ(lines[3].width, 6.0);  // width=6 m
  EXPECT_EQ(lines[3].layer, 0);    // layer=1;2 is malformed
  // Reprojected from WGS 84 into the grid's UTM metres (OSM keeps 1e-7 degrees: ~1 cm).
  ASSERT_EQ(lines[1].points.size(), 2u);
  EXPECT_NEAR(lines[1].points[0].x, utm_of_node[2].x, 0.02);
  EXPECT_NEAR(lines[1].points[0].y, utm_of_node[2].y, 0.02);
  EXPECT_NEAR(lines[1].points[1].x, utm_of_node[3].x, 0.02);
  const std::vector<Warning> listed = warnings.list();
  ASSERT_EQ(listed.size(), 2u);
  EXPECT_EQ(listed[0].code, "osm_tag");
  EXPECT_EQ(listed[0].fid, 103);
  EXPECT_THAT(listed[0].message, HasSubstr("lanes=x"));
  EXPECT_EQ(listed[1].fid, 104);
  EXPECT_THAT(listed[1].message, HasSubstr("layer=1;2"));
}

TEST_F(OsmSource, WaterwaysSelectedByWhereOnTheirColumn) {
  LineClassSpec spec;
  spec.name = "streams";
  spec.source = {write_osm(), "lines", "waterway IN ('stream', 'river')"};
  spec.osm_widths = true;
  const std::vector<LineFeature> lines = read_line_features(spec, grid);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].fid, 105);
  EXPECT_EQ(lines[0].width, 3.0);
}

TEST_F(OsmSource, NoWidthFromTagsAndNoDefaultIsAnError) {
  LineClassSpec spec;
  spec.name = "all";
  spec.source = {write_osm(), "lines", "highway = 'primary' AND bridge IS NULL"};
  const std::string error = test::error_of([&] { read_line_features(spec, grid); });
  EXPECT_THAT(error, HasSubstr("FID 101"));
  EXPECT_THAT(error, HasSubstr("width must be a positive number"));
}

TEST_F(OsmSource, StructureColumnsOfAGeoPackage) {
  // The same columns in any source: a bridge column of GeoPackage integers.
  const std::string path = (dir / "roads.gpkg").string();
  test::write_vector(path, "GPKG", "roads", "EPSG:32631",
                     {{1, "LINESTRING (500100 4999100,500200 4999200)", 5.0}});
  {
    GDALDataset* dataset = GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_UPDATE);
    ASSERT_NE(dataset, nullptr);
    dataset->ExecuteSQL("ALTER TABLE roads ADD COLUMN bridge INTEGER", nullptr, nullptr);
    dataset->ExecuteSQL("UPDATE roads SET bridge = 1", nullptr, nullptr);
    GDALClose(dataset);
  }
  LineClassSpec spec;
  spec.name = "roads";
  spec.source.path = path;
  spec.default_width = 5.0;
  const std::vector<LineFeature> lines = read_line_features(spec, grid);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].structure, Structure::bridge);
}

// The sample as XML and as PBF (the same ways, converted by osmconvert) reads the same.
TEST(OsmSample, XmlAndPbfGiveTheSameFeatures) {
  const Heightfield dem = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  auto read = [&](const char* file) {
    LineClassSpec spec;
    spec.name = "roads";
    spec.source = {(test::source_dir() / "samples" / file).string(), "lines",
                   "highway IS NOT NULL"};
    spec.osm_widths = true;
    return read_line_features(spec, dem);
  };
  const std::vector<LineFeature> xml = read("olinda.osm");
  const std::vector<LineFeature> pbf = read("olinda.osm.pbf");
  ASSERT_EQ(xml.size(), 8u);
  ASSERT_EQ(pbf.size(), xml.size());
  for (std::size_t i = 0; i < xml.size(); ++i) {
    EXPECT_EQ(pbf[i].fid, xml[i].fid);
    EXPECT_EQ(pbf[i].width, xml[i].width);
    EXPECT_EQ(pbf[i].structure, xml[i].structure);
    EXPECT_EQ(pbf[i].layer, xml[i].layer);
    EXPECT_EQ(pbf[i].closed, xml[i].closed);
    ASSERT_EQ(pbf[i].points.size(), xml[i].points.size());
    for (std::size_t k = 0; k < xml[i].points.size(); ++k)
      EXPECT_LT(distance(pbf[i].points[k], xml[i].points[k]), 1e-6) << xml[i].fid;
  }
  EXPECT_EQ(xml[1].fid, 2002);
  EXPECT_EQ(xml[1].structure, Structure::bridge);
  EXPECT_TRUE(xml[6].closed);  // the residential loop stays a line, closed
}

// samples/olinda.osm as JOSM saves new data before upload: every id negative (-1, -2...), no
// version, `action="modify"`, and the nodes in reverse order (so ids are not increasing).
std::string josm_copy(const test::TempDir& dir) {
  std::ifstream in(test::source_dir() / "samples/olinda.osm");
  std::vector<std::string> nodes;
  std::string rest;
  for (std::string line; std::getline(in, line);) {
    line = std::regex_replace(line, std::regex(R"re(( id| ref)="(\d+)")re"), "$1=\"-$2\"");
    line = std::regex_replace(line, std::regex(R"re( version="\d+")re"), R"re( action="modify")re");
    if (line.find("<node ") != std::string::npos) {
      nodes.push_back(line);
    } else {
      if (line.find("<way ") != std::string::npos && !nodes.empty()) {
        std::reverse(nodes.begin(), nodes.end());
        for (const std::string& n : nodes) rest += n + "\n";
        nodes.clear();
      }
      rest += line + "\n";
    }
  }
  const std::string path = (dir / "josm.osm").string();
  std::ofstream(path) << rest;
  return path;
}

// An editor's file reads as the positive-id sample does: the same ways, FIDs negated.
TEST(OsmSample, JosmFileWithNegativeIdsAndUnsortedNodesReadsWhole) {
  const test::TempDir dir;
  const std::string josm = josm_copy(dir);
  {
    std::ifstream check(josm);
    const std::string text((std::istreambuf_iterator<char>(check)), {});
    ASSERT_THAT(text, HasSubstr(R"(<nd ref="-1"/>)"));
    ASSERT_LT(text.find(R"(<node id="-95")"), text.find(R"(<node id="-1")"));
  }
  const Heightfield dem = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  auto read = [&](const std::string& path, const char* where) {
    LineClassSpec spec;
    spec.name = "roads";
    spec.source = {path, "lines", where};
    spec.osm_widths = true;
    return read_line_features(spec, dem);
  };
  const std::string sample = (test::source_dir() / "samples/olinda.osm").string();
  for (const char* where : {"", "highway IS NOT NULL"}) {
    const std::vector<LineFeature> positive = read(sample, where);
    const std::vector<LineFeature> negative = read(josm, where);
    ASSERT_EQ(positive.size(), where[0] ? 8u : 11u);
    ASSERT_EQ(negative.size(), positive.size()) << where;
    for (std::size_t i = 0; i < positive.size(); ++i) {
      EXPECT_EQ(negative[i].fid, -positive[i].fid);
      EXPECT_EQ(negative[i].width, positive[i].width);
      ASSERT_EQ(negative[i].points.size(), positive[i].points.size());
      for (std::size_t k = 0; k < positive[i].points.size(); ++k)
        EXPECT_EQ(negative[i].points[k], positive[i].points[k]);
    }
  }
  Warnings warnings;
  const std::vector<PolygonFeature> areas =
      read_polygon_features({josm, "multipolygons", ""}, dem, "existing.0", warnings);
  ASSERT_EQ(areas.size(), 1u);
  EXPECT_LT(areas[0].fid, 0);
  EXPECT_GE(areas[0].rings[0].size(), 4u);
}

// Where GDAL's own node index is forced on (the user's OSM_USE_CUSTOM_INDEXING=YES), the file
// cannot be read: an error that says so, never 0 features, never "bad where clause".
TEST(OsmSample, UnreadableFileIsAReadErrorNotAnEmptyLayerOrABadClause) {
  const test::TempDir dir;
  const std::string josm = josm_copy(dir);
  const Heightfield dem = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  CPLSetConfigOption("OSM_USE_CUSTOM_INDEXING", "YES");
  for (const char* where : {"", "highway IS NOT NULL"}) {
    LineClassSpec spec;
    spec.name = "roads";
    spec.source = {josm, "lines", where};
    spec.default_width = 5.0;
    const std::string error = test::error_of([&] { read_line_features(spec, dem); });
    EXPECT_THAT(error, HasSubstr("josm.osm:lines: reading its features failed")) << where;
    EXPECT_THAT(error, HasSubstr("OSM_USE_CUSTOM_INDEXING")) << where;
    EXPECT_THAT(error, ::testing::Not(HasSubstr("where clause"))) << where;
  }
  CPLSetConfigOption("OSM_USE_CUSTOM_INDEXING", nullptr);
  LineClassSpec bad;
  bad.name = "roads";
  bad.source = {josm, "lines", "highway IS"};
  bad.default_width = 5.0;
  EXPECT_THAT(test::error_of([&] { read_line_features(bad, dem); }),
              HasSubstr("bad where clause 'highway IS'"));
}

// Why a source gave nothing: no rows, a clause matching none, or features off the grid; nothing
// to say when the layer's extent does not meet the grid.
TEST(OsmSample, WhyNoFeaturesSaysWhichItIs) {
  const test::TempDir dir;
  const std::string josm = josm_copy(dir);
  const Heightfield dem = read_heightfield((test::source_dir() / "samples/dem.tif").string());
  const std::optional<std::string> clause =
      why_no_features({josm, "lines", "highway = 'motorway'"}, dem);
  ASSERT_TRUE(clause.has_value());
  EXPECT_THAT(*clause,
              HasSubstr("the where clause 'highway = 'motorway'' matches none of its 11 rows"));
  const std::optional<std::string> none = why_no_features({josm, "points", ""}, dem);
  ASSERT_TRUE(none.has_value());
  EXPECT_THAT(*none, HasSubstr("the layer has no rows"));
  // A layer far away (UTM 31N, France) has nothing to say over Olinda.
  const std::string far = (dir / "far.gpkg").string();
  test::write_vector(far, "GPKG", "roads", "EPSG:32631",
                     {{1, "LINESTRING (500100 4999100,500200 4999200)", 5.0}});
  EXPECT_FALSE(why_no_features({far, "roads", ""}, dem).has_value());
}

}  // namespace
}  // namespace tw
