// Incremental rebuilds with --cache (docs/cache.md, issue #10 item 3), tiles: a 5 x 5 tiling of
// the cache world, rendered through the tile cache. One changed road rebuilds exactly the tiles
// that its old and new footprints, and its junction partner's, reach (worked out here from the
// geometry); every other tile's files come from the cache (hard links); the files equal a run
// without cache byte for byte; a corrupt tile entry is detected and rebuilt. A tile's key holds
// the profile samples it can read: a changed sample reaches exactly the tiles whose render it
// changes, and a partner's tiles far from a moved junction are reused. A reused tile's cache
// files are read through for their hash only when their stat facts differ from the entry's or
// were recorded within the racy window; a file edited behind the cache's back is caught.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "cache_world.hpp"
#include "core/output_folder.hpp"
#include "file_edit.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/plan.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using namespace tw::test;

constexpr double kPixel = 4.0, kWorld = 640.0;
constexpr const char* kTiling = R"(
output: { tiles: { size: 34, overlap: 2 } }
avoidance: { max_distance: 12 }
)";

struct TiledRun {
  std::map<std::pair<int, int>, CacheStatus> tiles;  // by (ix, iy)
  std::map<std::pair<int, int>, int> files_hashed;   // Outcome::files_hashed, by (ix, iy)
  std::vector<Warning> warnings;
  std::size_t count = 0;
};

// The tiles' halo windows as local boxes.
Box tile_box(const TileSpec& tile) {
  const Window& w = tile.halo_window;
  return {w.col0 * kPixel, kWorld - w.row_end() * kPixel, w.col_end() * kPixel,
          kWorld - w.row0 * kPixel};
}

// A road's render reaches half its width plus its shoulder and falloff (terrain), or half its
// width plus the avoidance distance cap and a pixel (avoidance): 4 + 12 + 4 = 20 m; the pattern
// less. A tile is rebuilt when it meets that reach of a changed feature's old or new line: a
// feature whose synthesis is rebuilt, or which crosses a changed road where the crossing moved
// (a junction partner: its profile is graded at the junction).
std::set<std::pair<int, int>> expected_tiles(const std::vector<TileSpec>& tiles,
                                             const std::vector<Line>& before,
                                             const std::vector<Line>& after, double reach) {
  std::set<int> changed = expected_rebuilds(before, after);
  for (const Vec2 p : changed_crossings(before, after))
    for (std::size_t f = 0; f < after.size(); ++f)
      if (line_box(after[f], 0.0).holds(p, 0.5) || line_box(before[f], 0.0).holds(p, 0.5))
        changed.insert(int(f) + 1);
  std::set<std::pair<int, int>> out;
  for (const TileSpec& tile : tiles)
    for (const int fid : changed)
      for (const Line* line : {&before[std::size_t(fid - 1)], &after[std::size_t(fid - 1)]})
        if (tile_box(tile).meets(line_box(*line, reach))) out.insert({tile.ix, tile.iy});
  return out;
}

class TileCacheRun : public ::testing::Test {
 protected:
  void SetUp() override {
    write_roads(dir_ / "roads.gpkg", roads());
    write_exemplar(dir_.path());
  }

  PipelineConfig config() const {
    std::string text = kCachePipeline;
    if (plain_) {  // the roads without synthesis
      const std::size_t at = text.find("    synthesis:");
      text.erase(at, text.find('\n', at) + 1 - at);
    }
    return parse_pipeline(text + kTiling, "tiles.yaml", dir_.path());
  }

  TiledRun run(const std::string& name, bool with_cache = true) {
    const fs::path out = dir_ / name;
    const std::optional<fs::path> cache =
        with_cache ? std::optional<fs::path>(dir_ / "cache") : std::nullopt;
    Warnings warnings;
    PlanOptions plan_options;
    plan_options.cache_dir = cache;
    const WorldPlan plan = plan_world(config(), plan_options, warnings);
    WriteOptions write_options;
    write_options.preview = false;
    detail::TileCache tile_cache(plan, write_options, cache, warnings);
    OutputFolder folder(out);
    TiledRun result;
    for (const TileSpec& tile : plan.tiles) {
      const detail::TileCache::Outcome outcome = tile_cache.render_or_reuse(
          tile, folder, out,
          [&](LayerSet& layers, OutputStager& stager, std::map<std::string, std::string>&) {
            write_layer_set(layers, out / "tiles" / tile_file_stem("tile", tile), stager,
                            write_options);
          });
      result.tiles[{tile.ix, tile.iy}] = outcome.status;
      result.files_hashed[{tile.ix, tile.iy}] = outcome.files_hashed;
    }
    folder.commit();
    tiles_ = plan.tiles;
    result.warnings = warnings.list();
    result.count = plan.tiles.size();
    return result;
  }

  static int total_hashed(const TiledRun& run) {
    int total = 0;
    for (const auto& [at, hashed] : run.files_hashed) total += hashed;
    return total;
  }

  fs::path entry_path(const TiledRun& run, std::pair<int, int> at) const {
    return dir_ / "cache/tiles" / (run.tiles.at(at).key + ".twc");
  }

  static std::set<std::pair<int, int>> rebuilt(const TiledRun& run) {
    std::set<std::pair<int, int>> out;
    for (const auto& [at, status] : run.tiles)
      if (!status.reused) out.insert(at);
    return out;
  }

  void expect_same_files(const std::string& a, const std::string& b) const {
    EXPECT_EQ(expect_same_output_files(dir_ / a, dir_ / b),
              25u * 6u);  // height, splat, avoidance as EXR and GeoTIFF per tile
  }

  TempDir dir_;
  std::vector<TileSpec> tiles_;
  bool plain_ = false;
};

TEST_F(TileCacheRun, UnchangedRerunCopiesEveryTile) {
  const TiledRun first = run("first");
  ASSERT_EQ(first.count, 25u);  // 34-pixel tiles of a 160-pixel world
  EXPECT_EQ(rebuilt(first).size(), 25u);
  for (const auto& [at, status] : first.tiles) EXPECT_EQ(status.why, "new");
  const TiledRun second = run("second");
  EXPECT_TRUE(rebuilt(second).empty());
  for (const auto& [at, status] : second.tiles) {
    EXPECT_EQ(status.why, "unchanged");
    EXPECT_EQ(status.key, first.tiles.at(at).key);
  }
  // The facts recorded on storing vouch for every file at once: none is read.
  EXPECT_EQ(total_hashed(second), 0);
  expect_same_files("first", "second");
}

// A cache file edited in place through its output link (the same size, a new modification
// time): its facts differ from the entry's, so it is read through, and the hash mismatch
// rebuilds the tile. The tile's other files pass the quick check unread.
TEST_F(TileCacheRun, ACacheFileEditedBehindTheCachesBackIsReadAndCaught) {
  const TiledRun first = run("first");
  const fs::path edited = dir_ / "first/tiles/tile_x1_y1/height.exr";
  ASSERT_TRUE(fs::exists(edited));
  const auto before = fs::last_write_time(edited);
  test::flip_byte_in_place(edited, 10);
  ASSERT_NE(fs::last_write_time(edited), before);
  const TiledRun second = run("second");
  EXPECT_EQ(rebuilt(second), (std::set<std::pair<int, int>>{{1, 1}}));
  EXPECT_EQ(second.tiles.at({1, 1}).why, "corrupt entry");
  ASSERT_EQ(second.warnings.size(), 1u);
  EXPECT_EQ(second.warnings[0].code, "cache_corrupt");
  EXPECT_THAT(second.warnings[0].message, HasSubstr("content hash mismatch"));
  EXPECT_EQ(second.files_hashed.at({1, 1}), 1);  // the edited file; the others unread
  EXPECT_EQ(total_hashed(second), 1);
  run("clean", false);
  expect_same_files("second", "clean");
}

// Facts recorded within the racy window of their files' modification time (git's rule: a
// write just after they were taken could leave the same time) do not vouch for the files: the
// tile's files are read through, the tile reused, and the facts recorded again, now trusted.
TEST_F(TileCacheRun, FactsRecordedWithinTheRacyWindowAreNotTrusted) {
  const TiledRun first = run("first");
  const fs::path entry = entry_path(first, {2, 2});
  detail::CacheRead read = detail::read_cache_entry(entry);
  ASSERT_EQ(read.state, detail::CacheRead::State::ok);
  // The entry as if written when its files were last modified.
  std::int64_t earliest = std::numeric_limits<std::int64_t>::max();
  int files = 0;
  for (const auto& [section, text] : read.sections) {
    if (!section.starts_with("stat:")) continue;
    std::istringstream fields(text);
    std::uint64_t bytes = 0;
    std::int64_t mtime_ns = 0;
    ASSERT_TRUE(fields >> bytes >> mtime_ns) << text;
    earliest = std::min(earliest, mtime_ns);
    ++files;
  }
  ASSERT_EQ(files, 6);  // height, splat, avoidance as EXR and GeoTIFF
  ASSERT_TRUE(read.sections.contains("stat_time"));
  ASSERT_GT(std::stoll(read.sections.at("stat_time")), earliest);  // settled: not racy
  read.sections["stat_time"] = std::to_string(earliest);
  detail::write_cache_entry(entry, read.sections);

  const TiledRun second = run("second");
  EXPECT_TRUE(rebuilt(second).empty());
  EXPECT_TRUE(second.warnings.empty());
  EXPECT_EQ(second.files_hashed.at({2, 2}), 6);
  EXPECT_EQ(total_hashed(second), 6);
  const TiledRun third = run("third");
  EXPECT_TRUE(rebuilt(third).empty());
  EXPECT_EQ(total_hashed(third), 0);
  expect_same_files("first", "third");
}

// A cache file whose time changed with its bytes the same is read through once, reused, and
// its new facts recorded: the next run reads nothing.
TEST_F(TileCacheRun, AFileWhoseTimeChangedIsReadOnceAndItsFactsRecordedAgain) {
  run("first");
  const fs::path touched = dir_ / "first/tiles/tile_x3_y0/height.tif";
  ASSERT_TRUE(fs::exists(touched));
  fs::last_write_time(touched, fs::last_write_time(touched) - std::chrono::hours(1));
  const TiledRun second = run("second");
  EXPECT_TRUE(rebuilt(second).empty());
  EXPECT_TRUE(second.warnings.empty());
  EXPECT_EQ(second.files_hashed.at({3, 0}), 1);
  EXPECT_EQ(total_hashed(second), 1);
  const TiledRun third = run("third");
  EXPECT_EQ(total_hashed(third), 0);
  expect_same_files("first", "third");
}

TEST_F(TileCacheRun, OneChangedRoadRebuildsTheTilesItsFootprintReaches) {
  run("before");
  const std::vector<Line> after = roads_with_r1_west_moved();
  EXPECT_EQ(expected_rebuilds(roads(), after), (std::set<int>{1, 2}));
  write_roads(dir_ / "roads.gpkg", after);
  const TiledRun changed = run("after");
  // The geometry leaves no tile border near the reach: any reach from 8 to 36 m agrees.
  const auto expected = expected_tiles(tiles_, roads(), after, 20.0);
  ASSERT_EQ(expected, expected_tiles(tiles_, roads(), after, 8.0));
  ASSERT_EQ(expected, expected_tiles(tiles_, roads(), after, 36.0));
  ASSERT_GT(expected.size(), 2u);
  ASSERT_LT(expected.size(), 20u);
  EXPECT_EQ(rebuilt(changed), expected);
  for (const auto& [at, status] : changed.tiles)
    EXPECT_EQ(status.why, expected.count(at) ? "features changed" : "unchanged");
  run("clean", false);
  expect_same_files("after", "clean");
}

// Issue #23 item 2: plain roads (no synthesis). R1's west end moves, so its crossing with R2
// moves and R2's profile is graded anew near it. A tile's key holds only the profile samples the
// tile can read: R2's tiles far from the crossing keep their key, R1's own are rebuilt, and
// every file equals a clean run's (no tile that reads a changed sample is reused).
TEST_F(TileCacheRun, APartnersTilesFarFromAMovedJunctionKeepTheirKey) {
  plain_ = true;
  run("before");
  const std::vector<Line> after = roads_with_r1_west_moved();
  write_roads(dir_ / "roads.gpkg", after);
  const TiledRun changed = run("after");
  run("clean", false);
  expect_same_files("after", "clean");
  const Line r2 = roads()[1];
  ASSERT_EQ(r2, after[1]);  // R2 itself is unchanged
  const Box junction = line_box({{320, 300}}, 150.0);
  std::set<std::pair<int, int>> own, far;
  for (const TileSpec& tile : tiles_) {
    const Box box = tile_box(tile);
    const bool r1_reaches =
        box.meets(line_box(roads()[0], 20.0)) || box.meets(line_box(after[0], 20.0));
    if (r1_reaches) own.insert({tile.ix, tile.iy});
    if (!r1_reaches && box.meets(line_box(r2, 20.0)) && !box.meets(junction))
      far.insert({tile.ix, tile.iy});
  }
  ASSERT_GE(own.size(), 5u);
  ASSERT_GE(far.size(), 2u);
  for (const auto& at : own)
    EXPECT_FALSE(changed.tiles.at(at).reused) << at.first << "," << at.second;
  for (const auto& at : far) {
    EXPECT_TRUE(changed.tiles.at(at).reused) << at.first << "," << at.second;
    EXPECT_EQ(changed.tiles.at(at).why, "unchanged");
  }
}

// The key against the render itself: one sample of R2's planned profile raised by a metre (as a
// partner's grading would). Every tile whose render changes gets a new key (a stale reuse is
// impossible), and the tiles that cannot read that sample keep theirs.
TEST_F(TileCacheRun, AChangedProfileSampleChangesTheKeyOfEveryTileWhoseRenderItReaches) {
  plain_ = true;
  Warnings warnings;
  const WorldPlan plan = plan_world(config(), PlanOptions{}, warnings);
  WorldPlan changed = plan_world(config(), PlanOptions{}, warnings);
  std::size_t r2 = changed.terrain.features.size();
  for (std::size_t e = 0; e < changed.terrain.features.size(); ++e)
    if (changed.terrain.input_index[e] == 1) r2 = e;  // FID 2, from y 50 to 590 at x 320
  ASSERT_LT(r2, changed.terrain.features.size());
  const double step = changed.terrain.steps[r2];
  const std::size_t sample = std::size_t(std::lround(400.0 / step));  // y 450, beside R3's end
  ASSERT_LT(sample, changed.terrain.profiles[r2].size());
  changed.terrain.profiles[r2][sample] += 1.0f;
  WriteOptions write_options;
  const detail::TileCache before(plan, write_options, std::nullopt, warnings);
  const detail::TileCache after(changed, write_options, std::nullopt, warnings);
  const auto pixels = [](const LayerSet& layers) {
    std::string bytes;
    for (const Layer& layer : layers.layers)
      for (const Raster<float>& band : layer.bands)
        bytes.append(reinterpret_cast<const char*>(band.pixels.data()),
                     band.pixels.size() * sizeof(float));
    return bytes;
  };
  int rendered_differently = 0, kept = 0;
  for (const TileSpec& tile : plan.tiles) {
    const bool same_key = before.key(tile).combined() == after.key(tile).combined();
    const bool same_render = pixels(render_tile(plan, tile)) == pixels(render_tile(changed, tile));
    if (!same_render) {
      ++rendered_differently;
      EXPECT_FALSE(same_key) << "tile " << tile.ix << "," << tile.iy << " would be reused stale";
    }
    kept += same_key;
  }
  EXPECT_GE(rendered_differently, 1);
  EXPECT_LE(rendered_differently, 4);  // a sample reaches the tiles within 23 m of it
  EXPECT_GE(kept, 20);                 // of 25: R2's other tiles among them
}

TEST_F(TileCacheRun, CorruptTileEntryIsDetectedAndRebuilt) {
  const TiledRun first = run("first");
  const fs::path entry = dir_ / "cache/tiles" / (first.tiles.at({1, 1}).key + ".twc");
  std::string bytes = read_file(entry);
  ASSERT_GT(bytes.size(), 300u);  // the files' digests (the files themselves: tiles/files)
  bytes[bytes.size() - 100] ^= 0x01;
  std::ofstream(entry, std::ios::binary | std::ios::trunc) << bytes;
  const TiledRun second = run("second");
  EXPECT_EQ(rebuilt(second), (std::set<std::pair<int, int>>{{1, 1}}));
  EXPECT_EQ(second.tiles.at({1, 1}).why, "corrupt entry");
  ASSERT_EQ(second.warnings.size(), 1u);
  EXPECT_EQ(second.warnings[0].code, "cache_corrupt");
  EXPECT_THAT(second.warnings[0].message, HasSubstr(entry.filename().string()));
  expect_same_files("first", "second");
}

}  // namespace
}  // namespace tw
