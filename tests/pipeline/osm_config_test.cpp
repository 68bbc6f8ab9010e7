// The `tags` key of feature classes and existing entries (docs/osm.md, "Selecting ways").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/error.hpp"
#include "pipeline/config.hpp"

namespace tw {
namespace {

using ::testing::HasSubstr;

PipelineConfig parse(const std::string& features, const std::string& existing = "") {
  return parse_pipeline("version: 1\nheightfield: dem.tif\nfeatures:\n" + features + existing,
                        "p.yaml", "/base", {});
}

std::string error_of(const std::string& features) {
  try {
    parse(features);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(OsmConfig, TagsBecomeAWhereClauseAndImplyTheKind) {
  const PipelineConfig c = parse(
      "  roads: { source: a.osm, layer: lines, tags: { highway: [primary, residential] } }\n"
      "  rivers: { source: a.osm, layer: lines, tags: { waterway: stream }, where: \"name = 'x'\" "
      "}\n"
      "  ridges: { source: a.osm, layer: lines, tags: { natural: [ridge] }, width: 30 }\n",
      "existing:\n  - { source: a.osm, layer: multipolygons, tags: { landuse: [forest] } }\n");
  ASSERT_EQ(c.features.size(), 3u);
  EXPECT_EQ(c.features[0].kind, FeatureKind::road);
  EXPECT_EQ(c.features[0].width, 0.0);  // widths from the OSM tag table
  EXPECT_EQ(selection_where(c.features[0].tags, c.features[0].where),
            "\"highway\" IN ('primary', 'residential')");
  EXPECT_EQ(c.features[1].kind, FeatureKind::river);
  EXPECT_EQ(selection_where(c.features[1].tags, c.features[1].where),
            "\"waterway\" IN ('stream') AND (name = 'x')");
  EXPECT_EQ(c.features[2].kind, FeatureKind::ridge);
  EXPECT_EQ(c.features[2].width, 30.0);  // the fallback where the table has no width
  ASSERT_EQ(c.existing.size(), 1u);
  EXPECT_EQ(selection_where(c.existing[0].tags, c.existing[0].where), "\"landuse\" IN ('forest')");
}

TEST(OsmConfig, QuotesInValuesAreEscaped) {
  EXPECT_EQ(selection_where({{"name", {"O'Brien"}}}, ""), "\"name\" IN ('O''Brien')");
  EXPECT_EQ(selection_where({}, "a = 1"), "a = 1");
  EXPECT_EQ(selection_where({}, ""), "");
}

TEST(OsmConfig, AnExplicitKindWinsAndAmbiguousOrUnknownKeysNeedOne) {
  EXPECT_EQ(
      parse("  r: { source: a.osm, tags: { highway: [track] }, kind: ridge }\n").features[0].kind,
      FeatureKind::ridge);
  EXPECT_THAT(error_of("  r: { source: a.osm, tags: { highway: [a], waterway: [b] } }\n"),
              HasSubstr("features.r.tags: the tag keys imply both road and river; give kind"));
  EXPECT_THAT(error_of("  r: { source: a.osm, tags: { railway: [rail] } }\n"),
              HasSubstr("no tag key implies a kind"));
  EXPECT_THAT(error_of("  r: { source: a.osm, tags: { highway: [] } }\n"),
              HasSubstr("features.r.tags.highway: empty list"));
  // Without tags, width stays required.
  EXPECT_THAT(error_of("  r: { source: a.osm, kind: road }\n"), HasSubstr("width"));
}

}  // namespace
}  // namespace tw
