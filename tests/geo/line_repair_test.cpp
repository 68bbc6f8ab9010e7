// Messy lines are repaired, not refused (docs/pipeline.md, "repair"): what read_line_features
// does to duplicate vertices, spikes, tiny loops, zero-length parts, Z/M values and lines that
// cross themselves, and that nothing outside the grid is judged.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "core/error.hpp"
#include "geo/detail/line_repair.hpp"
#include "geo/features.hpp"
#include "geo/line_repair_memo.hpp"
#include "geo_test_data.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

using test::TempDir;
using test::TestFeature;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// The test grid spans x 500000..501000, y 4999000..5000000 (UTM 31N).
class LineRepairs : public ::testing::Test {
 protected:
  Heightfield grid = test::small_utm_grid();
  TempDir dir;
  Warnings warnings;

  LineClassSpec spec_for(const std::vector<TestFeature>& features) {
    const std::string path = (dir / "lines.gpkg").string();
    test::write_vector(path, "GPKG", "lines", "EPSG:32631", features);
    LineClassSpec spec;
    spec.name = "roads";
    spec.subject = "features.roads";
    spec.source.path = path;
    spec.default_width = 4.0;
    return spec;
  }
};

TEST_F(LineRepairs, DuplicatesSpikesAndTinyLoopsAreRemovedWithOneWarning) {
  // An exact and a 4 mm duplicate of (500200, 4999500); a spike 80 m north of (500300, 4999500)
  // that comes back within a turn of 179.6 degrees; a loop of 0.3 + 0.4 + 0.3 + 0.4 = 1.4 m
  // through (500500.3, 4999500).
  const LineClassSpec spec =
      spec_for({{3,
                 "LINESTRING (500100 4999500,500200 4999500,500200 4999500,500200.004 4999500,"
                 "500300 4999500,500300 4999580,500300.5 4999500.5,500400 4999500,500500 4999500,"
                 "500500.6 4999500,500500.6 4999500.4,500500.3 4999500.4,500500.3 4999499.8,"
                 "500700 4999499.8)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(
      lines[0].points,
      ElementsAre(Vec2{500100, 4999500}, Vec2{500200, 4999500}, Vec2{500300, 4999500},
                  Vec2{500300.5, 4999500.5}, Vec2{500400, 4999500}, Vec2{500500, 4999500},
                  Vec2{500500.3, 4999500}, Vec2{500500.3, 4999499.8}, Vec2{500700, 4999499.8}));
  ASSERT_EQ(warnings.size(), 1u);
  const Warning w = warnings.list()[0];
  EXPECT_EQ(w.code, "repaired");
  EXPECT_EQ(w.subject, "features.roads");
  EXPECT_EQ(w.fid, 3);
  EXPECT_THAT(w.message, AllOf(HasSubstr("lines.gpkg:lines"),
                               HasSubstr("removed 2 duplicate vertices, 1 spike and 1 loop of "
                                         "1.4 m")));
}

TEST_F(LineRepairs, LoopRampAndLollipopCrossThemselvesAndStayWhole) {
  // A loop ramp crossing itself at (500300, 4999500) after an 800 m loop, and a cul-de-sac whose
  // end meets its own interior at (500300, 4999200): genuine self-crossings, kept as drawn.
  const LineClassSpec spec =
      spec_for({{1,
                 "LINESTRING (500100 4999500,500500 4999500,500500 4999700,500300 4999700,"
                 "500300 4999300)"},
                {2,
                 "LINESTRING (500100 4999200,500400 4999200,500400 4999100,500300 4999100,"
                 "500300 4999200)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0].points,
              ElementsAre(Vec2{500100, 4999500}, Vec2{500500, 4999500}, Vec2{500500, 4999700},
                          Vec2{500300, 4999700}, Vec2{500300, 4999300}));
  EXPECT_THAT(lines[1].points,
              ElementsAre(Vec2{500100, 4999200}, Vec2{500400, 4999200}, Vec2{500400, 4999100},
                          Vec2{500300, 4999100}, Vec2{500300, 4999200}));
  EXPECT_TRUE(warnings.empty());
}

TEST_F(LineRepairs, MinLoopDecidesWhatIsATinyLoop) {
  // The same loop ramp under min_loop 1000 m: its 800 m loop is cut at the crossing, and the
  // lollipop's 400 m head is cut back to where it meets the stem.
  LineClassSpec spec =
      spec_for({{1,
                 "LINESTRING (500100 4999500,500500 4999500,500500 4999700,500300 4999700,"
                 "500300 4999300)"},
                {2,
                 "LINESTRING (500100 4999200,500400 4999200,500400 4999100,500300 4999100,"
                 "500300 4999200)"}});
  spec.repair.min_loop = 1000.0;
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_THAT(lines[0].points,
              ElementsAre(Vec2{500100, 4999500}, Vec2{500300, 4999500}, Vec2{500300, 4999300}));
  EXPECT_THAT(lines[1].points, ElementsAre(Vec2{500100, 4999200}, Vec2{500300, 4999200}));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_THAT(warnings.list()[0].message, HasSubstr("removed 1 loop of 800 m"));
  EXPECT_THAT(warnings.list()[1].message, HasSubstr("removed 1 loop of 400 m"));
}

TEST_F(LineRepairs, NothingOutsideTheGridIsJudged) {
  // Inside: a clean line to the east edge. Outside (beyond the 2 m halo of a 4 m road): a bow
  // tie, a spike and a repeated vertex, none of which may fail the run or raise a warning.
  const LineClassSpec spec = spec_for(
      {{5,
        "LINESTRING (500500 4999500,500900 4999500,502000 4999500,502100 4999600,502100 4999400,"
        "502000 4999600,502000 4999600,502300 4999600,502200 4999600.1)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_THAT(lines[0].points,
              ElementsAre(Vec2{500500, 4999500}, Vec2{500900, 4999500}, Vec2{501002, 4999500}));
  EXPECT_TRUE(warnings.empty());
}

TEST_F(LineRepairs, ZeroLengthPartsAreDropped) {
  const LineClassSpec spec = spec_for(
      {{7, "MULTILINESTRING ((500100 4999100,500100 4999100),(500200 4999200,500300 4999200))"},
       {8, "LINESTRING (500400 4999400,500400.001 4999400)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0].fid, 7);
  EXPECT_THAT(lines[0].points, ElementsAre(Vec2{500200, 4999200}, Vec2{500300, 4999200}));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_EQ(warnings.list()[0].fid, 7);
  EXPECT_THAT(warnings.list()[0].message,
              HasSubstr("removed 1 duplicate vertex and 1 zero-length part"));
  EXPECT_EQ(warnings.list()[1].fid, 8);
}

TEST_F(LineRepairs, ZAndMValuesAreDroppedWithOneWarningPerClass) {
  const LineClassSpec spec =
      spec_for({{1, "LINESTRING Z (500100 4999100 12,500200 4999100 15)"},
                {2, "LINESTRING M (500100 4999300 1,500200 4999300 2)"},
                {3, "LINESTRING ZM (500100 4999500 12 1,500200 4999500 15 2)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_THAT(lines[2].points, ElementsAre(Vec2{500100, 4999500}, Vec2{500200, 4999500}));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings.list()[0].code, "dropped_zm");
  EXPECT_EQ(warnings.list()[0].subject, "features.roads");
  EXPECT_FALSE(warnings.list()[0].fid.has_value());
}

// The spike's tip (500350) goes, and so does the 0.2 m stub it leaves, which doubles back too.
TEST_F(LineRepairs, ClosedRingKeepsItsFirstVertexAndLosesItsSpike) {
  const LineClassSpec spec =
      spec_for({{4,
                 "LINESTRING (500100 4999100,500300 4999100,500300 4999300,500350 4999300,"
                 "500300.2 4999300,500100 4999300,500100 4999100)"}});
  const std::vector<LineFeature> lines = read_line_features(spec, grid, warnings);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_TRUE(lines[0].closed);
  EXPECT_THAT(lines[0].points, ElementsAre(Vec2{500100, 4999100}, Vec2{500300, 4999100},
                                           Vec2{500300, 4999300}, Vec2{500100, 4999300}));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings.list()[0].message, HasSubstr("removed 2 spikes"));
}

// An in-memory memo that counts its lookups and stores.
struct CountingMemo {
  std::map<ContentHash, RepairedPiece> entries;
  int lookups = 0, stores = 0;

  LineRepairMemo memo() {
    return {[this](const ContentHash& key) -> std::optional<RepairedPiece> {
              ++lookups;
              const auto found = entries.find(key);
              if (found == entries.end()) return std::nullopt;
              return found->second;
            },
            [this](const ContentHash& key, const RepairedPiece& repaired) {
              ++stores;
              entries[key] = repaired;
            }};
  }
};

// A memo's hit gives the lines and warnings of a fresh repair (one line repaired with a warning,
// one clean, one crossing itself, one dropped as zero-length); a changed point or option misses.
TEST_F(LineRepairs, AMemoHitGivesTheLinesAndWarningsOfAFreshRepair) {
  const std::vector<TestFeature> features = {
      {3,
       "LINESTRING (500100 4999500,500200 4999500,500200.004 4999500,500300 4999500,"
       "500300 4999580,500300.5 4999500.5,500400 4999500,500500 4999500,500500.6 4999500,"
       "500500.6 4999500.4,500500.3 4999500.4,500500.3 4999499.8,500700 4999499.8)"},
      {4, "LINESTRING (500100 4999800,500900 4999800)"},
      {5,
       "LINESTRING (500100 4999200,500400 4999200,500400 4999100,500300 4999100,"
       "500300 4999300)"},
      {6, "MULTILINESTRING ((500100 4999900,500500 4999900),(500600 4999900,500600.001 4999900))"}};
  LineClassSpec spec = spec_for(features);
  Warnings fresh_warnings;
  const std::vector<LineFeature> fresh = read_line_features(spec, grid, fresh_warnings);
  ASSERT_EQ(fresh_warnings.size(), 2u);  // FID 3 repaired, FID 6's stub dropped

  CountingMemo memo;
  spec.repair_memo = memo.memo();
  auto expect_as_fresh = [&](const std::vector<LineFeature>& lines, const Warnings& raised) {
    ASSERT_EQ(lines.size(), fresh.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      EXPECT_EQ(lines[i].fid, fresh[i].fid);
      EXPECT_EQ(lines[i].points, fresh[i].points) << "FID " << lines[i].fid;
      EXPECT_EQ(lines[i].closed, fresh[i].closed);
    }
    ASSERT_EQ(raised.size(), fresh_warnings.size());
    for (std::size_t i = 0; i < raised.size(); ++i) {
      EXPECT_EQ(raised.list()[i].code, fresh_warnings.list()[i].code);
      EXPECT_EQ(raised.list()[i].fid, fresh_warnings.list()[i].fid);
      EXPECT_EQ(raised.list()[i].message, fresh_warnings.list()[i].message);
    }
  };
  Warnings stored_warnings;
  expect_as_fresh(read_line_features(spec, grid, stored_warnings), stored_warnings);
  EXPECT_EQ(memo.stores, 5);  // one per piece
  Warnings hit_warnings;
  expect_as_fresh(read_line_features(spec, grid, hit_warnings), hit_warnings);
  EXPECT_EQ(memo.lookups, 10);
  EXPECT_EQ(memo.stores, 5);  // every piece was found

  // The memo's entry is what the reader uses: a different stored repair comes back.
  RepairedPiece& clean_line =
      memo.entries.at(line_repair_key({{500100, 4999800}, {500900, 4999800}}, false, spec.repair));
  clean_line.points = {{500100, 4999800}, {500500, 4999810}, {500900, 4999800}};
  clean_line.counts.spikes = 1;
  Warnings edited;
  const std::vector<LineFeature> from_edited = read_line_features(spec, grid, edited);
  EXPECT_EQ(from_edited[1].points, clean_line.points);
  ASSERT_EQ(edited.size(), 3u);
  EXPECT_EQ(edited.list()[1].fid, 4);
  EXPECT_THAT(edited.list()[1].message, HasSubstr("removed 1 spike"));

  // A moved point misses for its piece alone; a changed option misses for every piece.
  spec = spec_for(
      {features[0], {4, "LINESTRING (500100 4999800,500900 4999801)"}, features[2], features[3]});
  spec.repair_memo = memo.memo();
  Warnings moved_warnings;
  read_line_features(spec, grid, moved_warnings);
  EXPECT_EQ(memo.stores, 6);
  spec.repair.min_loop = 1.0;
  EXPECT_NE(line_repair_key({{0, 0}, {1, 0}}, false, spec.repair),
            line_repair_key({{0, 0}, {1, 0}}, false, LineRepair{}));
  Warnings option_warnings;
  read_line_features(spec, grid, option_warnings);
  EXPECT_EQ(memo.stores, 11);
  ASSERT_FALSE(option_warnings.list().empty());  // the 1.4 m loop is longer than min_loop now
  EXPECT_THAT(option_warnings.list()[0].message,
              HasSubstr("removed 1 duplicate vertex and 1 spike"));
}

// The repair memo stores a dropped piece as no points: repair_line must leave none behind when
// it says "drop", for an open line and for a ring.
TEST(RepairLine, ADroppedPieceIsLeftWithNoPoints) {
  LineRepairCounts counts;
  std::vector<Vec2> open = {{10, 10}, {10.004, 10}, {10, 10.003}};
  EXPECT_FALSE(detail::repair_line(open, false, LineRepair{}, counts));
  EXPECT_TRUE(open.empty());
  std::vector<Vec2> ring = {{5, 5}, {5.002, 5}, {5.002, 5.002}};
  EXPECT_FALSE(detail::repair_line(ring, true, LineRepair{}, counts));
  EXPECT_TRUE(ring.empty());
  EXPECT_EQ(counts.zero_length_parts, 2);
  std::vector<Vec2> kept = {{0, 0}, {3, 0}};
  EXPECT_TRUE(detail::repair_line(kept, false, LineRepair{}, counts));
  EXPECT_EQ(kept.size(), 2u);
}

TEST(RepairMessage, SaysWhatChangedInOneLine) {
  LineRepairCounts counts;
  counts.spikes = 1;
  counts.loops = {0.8};
  EXPECT_EQ(detail::describe(counts), "removed 1 spike and 1 loop of 0.8 m");
  counts.duplicates = 3;
  counts.loops = {0.5, 1.8, 1.2, 250.0};
  counts.zero_length_parts = 2;
  EXPECT_EQ(detail::describe(counts),
            "removed 3 duplicate vertices, 1 spike, 4 loops of 0.5 to 250 m and 2 zero-length "
            "parts");
}

}  // namespace
}  // namespace tw
