// Incremental rebuilds with --cache (docs/cache.md, issue #10 item 3), tiles: a 5 x 5 tiling of
// the cache world, rendered through the tile cache. One changed road rebuilds exactly the tiles
// that its old and new footprints, and its junction partner's, reach (worked out here from the
// geometry); every other tile's files come from the cache (hard links); the files equal a run
// without cache byte for byte; a corrupt tile entry is detected and rebuilt. A tile's key holds
// the profile samples it can read: a changed sample reaches exactly the tiles whose render it
// changes, and a partner's tiles far from a moved junction are reused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include "cache_world.hpp"
#include "core/output_folder.hpp"
#include "layers/write.hpp"
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
      result.tiles[{tile.ix, tile.iy}] =
          tile_cache
              .render_or_reuse(
                  tile, folder, out,
                  [&](LayerSet& layers, OutputStager& stager, std::map<std::string, std::string>&) {
                    write_layer_set(layers, out / "tiles" / tile_file_stem("tile", tile), stager,
                                    write_options);
                  })
              .status;
    }
    folder.commit();
    tiles_ = plan.tiles;
    result.warnings = warnings.list();
    result.count = plan.tiles.size();
    return result;
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
  expect_same_files("first", "second");
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
