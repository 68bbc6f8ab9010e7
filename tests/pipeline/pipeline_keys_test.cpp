// Issue #24 item 2: every key of the one key table (pipeline/detail/pipeline_keys, what
// `terraweave schema` prints) changes what a run writes, or is documented not to (docs/pipeline.md,
// "Keys that change no bytes") and then changes no byte. One test per block of the table (ctest
// runs them in parallel): a tiny world (the 64 x 64 test DEM) as the base, each row the base with
// the key at a second valid value (derived from the table's choices, default and range where no
// value is written here), run by `terraweave run` in children forked from one process and
// compared by the run's layers (report.json's output hashes and the files themselves). A block's
// rows must name exactly its keys in the table, so a new key without a row fails here.
#include <fmt/format.h>
#include <gdal_priv.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <optional>

#include "option_table.hpp"
#include "pipeline/detail/pipeline_keys.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {
namespace {

namespace fs = std::filesystem;
using detail::KeyDefault;
using detail::KeySpec;
using detail::ValueType;

constexpr const char* kAuto = "<auto>";

// The blocks the tests below check (check_block refuses one not listed here, and
// EveryBlockHasATable compares the list with the key table).
const std::set<std::string> kBlocksTested = {
    "root",          "generate",       "output",         "tiles",      "avoidance",
    "repair",        "export_engines", "export_options", "line_class", "road_profile",
    "river_profile", "ridge_profile",  "conform",        "synthesis",  "binding",
    "grow",          "grow_region",    "network",        "area_class", "lead",
    "existing"};

// A second valid value of a key with a default: another choice, the other boolean, or a number
// in range away from the default.
std::optional<std::string> second_value(const KeySpec& key) {
  const detail::ValueForm& form = key.forms.front();
  const KeyDefault& d = key.fallback;
  if (form.type == ValueType::boolean && d.kind == KeyDefault::Kind::boolean)
    return d.boolean ? "false" : "true";
  if (form.type == ValueType::choice && d.kind == KeyDefault::Kind::text)
    for (std::string_view v : form.values)
      if (v != d.text) return std::string(v);
  if ((form.type == ValueType::number || form.type == ValueType::integer) &&
      d.kind == KeyDefault::Kind::number) {
    double v = d.number != 0.0 ? d.number * 2.0 : 1.0;
    const bool above = form.exclusive_maximum ? v >= form.maximum : v > form.maximum;
    if (above) v = form.type == ValueType::integer ? d.number - 1.0 : d.number / 2.0;
    return form.type == ValueType::integer ? fmt::format("{}", std::llround(v))
                                           : fmt::format("{}", v);
  }
  return std::nullopt;
}

// One key's row: the base pipeline with `context` overrides, then A adds `a`, B adds `b`
// (kAuto: the key at second_value). `b_folder`: where B writes (output.dir).
struct KeyRow {
  std::string key;
  std::vector<std::string> b = {kAuto};
  std::vector<std::string> a = {};
  Expect expect = Expect::changes;
  std::string doc = "";
  int a_exit = 0, b_exit = 0;
  std::string b_folder = "out";
};

class PipelineKeys : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(d);
    DemSpec spec;
    spec.nodata = -9999.0;
    write_dem(d / "dem.tif", spec);
    {  // a nodata corner, for export nodata_height
      GDALAllRegister();
      std::unique_ptr<GDALDataset> dem(
          GDALDataset::Open((d / "dem.tif").c_str(), GDAL_OF_RASTER | GDAL_OF_UPDATE));
      ASSERT_TRUE(dem);
      std::vector<float> hole(16, -9999.0f);
      ASSERT_EQ(dem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, 4, 4, hole.data(), 4, 4,
                                                GDT_Float32, 0, 0),
                CE_None);
    }
    spec.pixel_size = 8.0;
    write_dem(d / "dem8.tif", spec);
    const fs::path map = d / "map.gpkg";
    write_layer(map, "roads",
                {{"LINESTRING (500020 5000300, 500600 5000250)", 6.0, {{"highway", "primary"}}},
                 {"LINESTRING (500300 5000020, 500320 5000600)", 8.0, {{"highway", "track"}}}});
    write_layer(map, "roads2", {{"LINESTRING (500020 5000400, 500600 5000350)", 6.0}});
    write_layer(map, "rivers",
                {{"LINESTRING (500050 5000600, 500200 5000450, 500600 5000420)", 5.0}});
    write_layer(map, "ridges", {{"LINESTRING (500100 5000100, 500500 5000150)", 4.0}});
    write_layer(map, "paths",
                {{"LINESTRING (500100 5000500, 500118 5000500)", 4.0, {{"surface", "a"}}},
                 {"LINESTRING (500400 5000100, 500418 5000104)", 4.0, {{"surface", "b"}}}});
    // Near vertices (3 m), a spike (back by 175 degrees), a 90-degree turn back, a small loop.
    write_layer(map, "messy",
                {{"LINESTRING (500050 5000450, 500100 5000452, 500103 5000452, 500200 5000460, "
                  "500150 5000464, 500260 5000462, 500300 5000470, 500300 5000490, 500290 5000480, "
                  "500310 5000476, 500400 5000480, 500400 5000520, 500420 5000500)",
                  6.0}});
    write_layer(map, "houses",
                {{"POLYGON ((500200 5000200, 500260 5000200, 500260 5000260, 500200 5000260, "
                  "500200 5000200))",
                  1.0,
                  {{"use", "house"}}},
                 {"POLYGON ((500400 5000400, 500440 5000400, 500440 5000440, 500400 5000440, "
                  "500400 5000400))",
                  1.0,
                  {{"use", "barn"}}}});
    // Over the west end of the first path: its pieces there have no room.
    write_layer(map, "block",
                {{"POLYGON ((500095 5000490, 500107 5000490, 500107 5000510, 500095 5000510, "
                  "500095 5000490))",
                  1.0}});
    // Another source with the layers of the first.
    const fs::path map2 = d / "map2.gpkg";
    write_layer(map2, "roads", {{"LINESTRING (500020 5000200, 500600 5000350)", 6.0}});
    write_layer(map2, "fields",
                {{"POLYGON ((500100 5000100, 500300 5000100, 500300 5000300, 500100 5000300, "
                  "500100 5000100))",
                  1.0}});
    write_layer(map2, "houses",
                {{"POLYGON ((500300 5000300, 500340 5000300, 500340 5000340, 500300 5000340, "
                  "500300 5000300))",
                  1.0}});
    write_layer(map, "long", {{"LINESTRING (500050 5000540, 500330 5000590)", 4.0}});
    write_layer(map, "across", {{"LINESTRING (500109 5000488, 500109 5000512)", 4.0}});
    write_layer(map, "walls", {{"LINESTRING (500100 5000550, 500500 5000560)", 3.0}});
    write_layer(map, "fields",
                {{"POLYGON ((500060 5000060, 500260 5000060, 500260 5000220, 500060 5000220, "
                  "500060 5000060))",
                  1.0,
                  {{"name", "a"}}},
                 {"POLYGON ((500340 5000380, 500560 5000380, 500560 5000580, 500340 5000580, "
                  "500340 5000380))",
                  1.0,
                  {{"name", "b"}}}});
    write_layer(map, "fields2",
                {{"POLYGON ((500100 5000100, 500300 5000100, 500300 5000300, 500100 5000300, "
                  "500100 5000100))",
                  std::nullopt}});
    // A network exemplar: a grid of field edges, every other line kind a; a drawn line.
    std::vector<VectorFeature> grid, gappy;
    int k = 0;
    auto add = [&](std::vector<VectorFeature>& to, int x0, int y0, int x1, int y1) {
      to.push_back({fmt::format("LINESTRING ({} {}, {} {})", x0, y0, x1, y1),
                    1.0,
                    {{"kind", k++ % 2 ? "a" : "b"}}});
    };
    for (int i = 0; i <= 6; ++i) add(grid, 500000 + i * 100, 4000000, 500000 + i * 100, 4000480);
    for (int j = 0; j <= 6; ++j)
      for (int i = 0; i < 6; ++i) {
        if ((i + j) % 3 == 1 && j > 0 && j < 6) continue;
        const int y = 4000000 + j * 80 + ((i * 7 + j) % 3) * 6 * (j > 0 && j < 6);
        add(grid, 500000 + i * 100, y, 500000 + (i + 1) * 100, y);
      }
    for (int i = 0; i <= 6; ++i) add(gappy, 500000 + i * 100, 4000000, 500000 + i * 100, 4000480);
    for (int j = 1; j < 6; ++j)
      for (int i = 0; i < 6; ++i)
        add(gappy, 500000 + i * 100, 4000000 + j * 80, 500096 + i * 100, 4000000 + j * 80);
    write_layer(d / "net.gpkg", "grid", grid);
    write_layer(d / "net.gpkg", "gappy", gappy);
    write_layer(d / "net.gpkg", "south",
                {{"LINESTRING (500000 4000000, 500000 4000250)", 1.0},
                 {"LINESTRING (500100 4000000, 500110 4000250)", 1.0},
                 {"LINESTRING (500000 4000100, 500110 4000100)", 1.0},
                 {"LINESTRING (500000 4000200, 500110 4000210)", 1.0}});
    write_layer(d / "net.gpkg", "west",
                {{"POLYGON ((500000 4000000, 500350 4000000, 500350 4000480, 500000 4000480, "
                  "500000 4000000))",
                  std::nullopt}});
    write_layer(d / "net.gpkg", "drawn",
                {{"LINESTRING (500100 5000100.5, 500250 5000102.75)", 1.0},
                 {"LINESTRING (500250 5000102.75, 500249.5 5000220)", 1.0}});
    std::string svg = R"(<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 100 100">)";
    for (int i = 0; i <= 4; ++i)
      svg += fmt::format(
          R"(<line x1="{0}" y1="0" x2="{0}" y2="100"/><line x1="0" y1="{0}" x2="100" y2="{1}"/>)",
          i * 25, i * 25 + (i % 2) * 3);
    std::ofstream(d / "grid.svg") << svg + "</svg>";
  }

  std::string base_yaml() const {
    return fmt::format(R"(version: 1
seed: 3
heightfield: {}/dem.tif
output: {{ dir: out, preview: false }}
features:
  roads: {{ source: {}/map.gpkg, layer: roads, kind: road, width: 6 }}
)",
                       d.string(), d.string());
  }

  Invocation run(const std::vector<std::string>& sets, const std::string& folder = "out") const {
    Invocation i{{"-q", "run", "p.yaml"}, {}, {{"p.yaml", base_yaml()}}, folder, ".terraweave/"};
    for (const std::string& s : sets) {
      i.args.push_back("--set");
      i.args.push_back(s);
    }
    return i;
  }

  // Checks block `block`, its keys under `prefix` ("features.roads.profile."), over the base
  // with the `context` overrides.
  void check_block(const std::string& block, const std::string& prefix,
                   const std::vector<std::string>& context, const std::vector<KeyRow>& rows) {
    EXPECT_TRUE(kBlocksTested.count(block)) << block << ": add it to kBlocksTested";
    std::set<std::string> listed;
    for (const KeySpec& key : detail::pipeline_block(block).keys)
      listed.insert(std::string(key.name));
    std::vector<OptionRow> option_rows;
    for (const KeyRow& r : rows) {
      std::vector<std::string> a = context, b = context;
      for (const std::string& s : r.a) a.push_back(s);
      for (const std::string& s : r.b) {
        if (s != kAuto) {
          b.push_back(s);
          continue;
        }
        const KeySpec* spec = detail::pipeline_block(block).find(r.key);
        const std::optional<std::string> value = spec ? second_value(*spec) : std::nullopt;
        EXPECT_TRUE(value) << block << "." << r.key << ": no second value derived; write one";
        if (value) b.push_back(prefix + r.key + "=" + *value);
      }
      option_rows.push_back(
          {r.key, run(a), run(b, r.b_folder), r.expect, r.doc, r.a_exit, r.b_exit});
    }
    check_option_rows(block, listed, option_rows, batch);
  }

  TempDir dir;
  const fs::path d = dir / "d";
  Batch batch{d, dir / "w"};
  const std::string samples = (source_dir() / "samples").string();
  const std::string chain = samples + "/exemplars/chain_199x82.png";
  const std::string map = (dir / "d/map.gpkg").string();
  const std::string net = (dir / "d/net.gpkg").string();
  // Two 18 m paths with a pattern along them.
  std::string paths(const std::string& synthesis_more = "") const {
    return "features.paths={source: " + map +
           ", layer: paths, kind: road, width: 4, synthesis: {exemplar: " + chain +
           ", scale: 4, width: 4, delta: 3" + synthesis_more + "}}";
  }
};

const char* const kWhere =
    "docs/pipeline.md: The keys that say where files go (`output.dir`, `cache`) do not change "
    "what they hold";

TEST(PipelineKeyTables, EveryBlockHasATable) {
  std::set<std::string> blocks;
  for (const detail::KeyBlock& block : detail::pipeline_blocks())
    blocks.insert(std::string(block.name));
  EXPECT_EQ(blocks, kBlocksTested);
}

TEST_F(PipelineKeys, Root) {
  const std::string block = "existing=[{source: " + map + ", layer: block}]";
  const std::string across =
      "features.more={source: " + map +
      ", layer: across, kind: road, width: 4, synthesis: {exemplar: " + chain +
      ", scale: 4, width: 4, delta: 3, empty_pieces: true}}";
  const std::string generate =
      "generate={width: 32, height: 32, pixel_size: 10, origin: [500000, 5000640]}";
  check_block(
      "root", "", {},
      {
          {"version", {"version=2"}, {}, Expect::changes, "", 0, 1},
          {"seed", {"heightfield=null", generate, "seed=4"}, {"heightfield=null", generate}},
          {"heightfield", {"heightfield=" + d.string() + "/dem8.tif"}},
          {"generate", {"heightfield=null", generate}},
          {"resolution", {"resolution=20"}},
          {"output", {"output={dir: out, preview: true}"}},
          {"backend",
           {paths(), "backend=opencl"},
           {paths(), "backend=cpu"},
           Expect::same_bytes,
           "docs/cli.md: outputs are the same bytes on either"},
          {"precedence",
           {"features.rivers={source: " + map + ", layer: rivers, kind: river, width: 5}",
            "precedence=[rivers, roads]"},
           {"features.rivers={source: " + map + ", layer: rivers, kind: river, width: 5}",
            "precedence=[roads, rivers]"}},
          {"features",
           {"features.ridges={source: " + map + ", layer: ridges, kind: ridge, width: 4}"}},
          {"existing", {"existing=[{source: " + map + ", layer: houses}]"}},
          // The canvas where the paths' patterns meet the house over one of them.
          {"synthesis_resolution",
           {paths(", empty_pieces: true"), block, "synthesis_resolution=3"},
           {paths(", empty_pieces: true"), block}},
          // A class across the first path: the later one avoids the earlier one's pattern.
          {"synthesis_order",
           {paths(", empty_pieces: true"), across, "synthesis_order=[more, paths]"},
           {paths(", empty_pieces: true"), across, "synthesis_order=[paths, more]"}},
          {"region", {"region=[500100, 5000100, 500500, 5000500]"}},
          {"resampling", {"resolution=7", "resampling=cubic"}, {"resolution=7"}},
          {"strict",
           {"features.roads.layer=messy", "strict=true"},
           {"features.roads.layer=messy"},
           Expect::changes,
           "",
           0,
           1},
          {"repair",
           {"features.roads.layer=messy", "repair={merge_distance: 5}"},
           {"features.roads.layer=messy"}},
          {"avoidance", {"avoidance={max_distance: 5}"}},
          {"cache", {paths(), "cache=c"}, {paths()}, Expect::same_bytes, kWhere},
          {"export", {"export=[unity]"}},
      });
}

TEST_F(PipelineKeys, Generate) {
  check_block("generate", "generate.",
              {"heightfield=null",
               "generate={width: 32, height: 32, pixel_size: 10, origin: [500000, 5000640]}"},
              {
                  {"width", {"generate.width=40"}},
                  {"height", {"generate.height=40"}},
                  {"pixel_size", {"generate.pixel_size=12"}},
                  {"relief"},
                  {"crs", {"generate.crs=EPSG:32632"}},
                  {"origin", {"generate.origin=[500100, 5000640]"}},
              });
}

TEST_F(PipelineKeys, Output) {
  check_block(
      "output", "output.", {},
      {
          {"dir", {"output.dir=elsewhere"}, {}, Expect::same_bytes, kWhere, 0, 0, "elsewhere"},
          {"formats", {"output.formats=[geotiff]"}},
          {"exr"},
          {"geotiff"},
          {"preview", {"output.preview=true"}},
          {"tiles", {"output.tiles={size: 32}"}},
          {"exr_half", {"output.exr_half=true"}},
          {"exr_compression", {"output.exr_compression=zip"}},
          {"compress"},
          {"predictor"},
          {"cog"},
          // Overviews need a raster larger than a block: 320 x 320 cells.
          {"overviews", {"resolution=2", "output.overviews=true"}, {"resolution=2"}},
          {"crs", {"output.crs=EPSG:32632"}},
      });
}

TEST_F(PipelineKeys, TilesAvoidanceRepair) {
  check_block("tiles", "output.tiles.", {"output.tiles={size: 32}"},
              {{"size", {"output.tiles.size=16"}}, {"overlap", {"output.tiles.overlap=4"}}});
  check_block("avoidance", "avoidance.", {}, {{"max_distance", {"avoidance.max_distance=20"}}});
  check_block("repair", "repair.", {"features.roads.layer=messy"},
              {{"merge_distance", {"repair.merge_distance=5"}},
               {"min_loop", {"repair.min_loop=100"}},
               {"spike_angle", {"repair.spike_angle=80"}}});
}

TEST_F(PipelineKeys, Exports) {
  check_block("export_engines", "export.", {},
              {{"unreal", {"export={unreal: null}"}},
               {"unity", {"export={unity: null}"}},
               {"godot", {"export={godot: null}"}},
               {"terrain3d", {"export={terrain3d: null}"}}});
  check_block("export_options", "export.unity.", {"export={unity: {tile_size: 0}}"},
              {{"size", {"export.unity.size=129"}, {"export.unity.size=65"}},
               {"nodata_height", {"export.unity.nodata_height=-50"}},
               {"height", {"export={godot: {height: r16}}"}, {"export={godot: {height: exr}}"}},
               {"layers", {"export.unity.layers=true"}},
               {"tile_size", {"export.unity.tile_size=33"}}});
}

TEST_F(PipelineKeys, LineClass) {
  const std::string c = "features.roads.";
  check_block(
      "line_class", c, {},
      {
          {"source", {c + "source=" + d.string() + "/map2.gpkg"}},
          {"layer", {c + "layer=roads2"}},
          {"where", {c + "where=highway = 'track'"}},
          {"tags", {c + "tags={highway: [track]}"}},
          {"kind", {c + "kind=river"}},
          {"width_attribute", {c + "width_attribute=width"}},
          {"width", {c + "width=9"}},
          {"profile", {c + "profile={max_grade: 0.01}"}},
          {"conform",
           {"features.roads.kind=river", c + "conform={corridor: 40}"},
           {"features.roads.kind=river"}},
          {"synthesis",
           {c + "synthesis={exemplar: " + chain + ", scale: 4, width: 4, delta: 3}",
            c + "layer=paths"},
           {c + "layer=paths"}},
          {"repair", {c + "layer=messy", c + "repair={merge_distance: 5}"}, {c + "layer=messy"}},
          {"grow",
           {"features.hedges={kind: hedge, grow: {element: " + samples +
            "/ornaments/hedge.json, region: [500060, 5000060, 500260, 5000220], max_ornaments: "
            "2}}"}},
          {"network",
           {"features.hedges={kind: hedge, width: 2, network: {exemplar: " + net +
            ":grid, region: [500060, 5000060, 500360, 5000260]}}"}},
      });
}

TEST_F(PipelineKeys, Profiles) {
  check_block("road_profile", "features.roads.profile.", {},
              {{"max_grade"},
               {"shoulder_width"},
               {"falloff"},
               {"smoothing"},
               {"max_cut", {"features.roads.profile.max_cut=0.2"}},
               {"max_fill", {"features.roads.profile.max_fill=0.2"}}});
  const std::string river =
      "features.rivers={source: " + map + ", layer: rivers, kind: river, width: 5}";
  check_block("river_profile", "features.rivers.profile.", {river},
              {{"depth"},
               {"bank_width"},
               {"falloff"},
               {"min_slope", {"features.rivers.profile.min_slope=0.05"}},
               {"max_carve", {"features.rivers.profile.max_carve=0.3"}}});
  const std::string ridge =
      "features.ridges={source: " + map + ", layer: ridges, kind: ridge, width: 4}";
  check_block("ridge_profile", "features.ridges.profile.", {ridge},
              {{"height"}, {"falloff"}, {"sharpness"}});
  check_block("conform", "features.rivers.conform.",
              {river, "features.rivers.conform={corridor: 20}"},
              {{"corridor", {"features.rivers.conform.corridor=60"}}});
}

TEST_F(PipelineKeys, Synthesis) {
  const std::string s = "features.paths.synthesis.";
  const std::string hedge = samples + "/exemplars/hedge_192x48.png";
  const std::string ridge = samples + "/exemplars/ridge_band_200x64.png";
  const std::string two = s + "exemplar=[" + chain + ", " + hedge + "]";
  const std::string block = "existing=[{source: " + map + ", layer: block}]";
  check_block(
      "synthesis", s, {paths()},
      {
          {"exemplar", {s + "exemplar=" + hedge}},
          {"choose", {two, s + "choose=mix"}, {two}},
          // 100 pieces, where mixing pays (6 never switch).
          {"switch_cost",
           {two, s + "choose=mix", "features.paths.layer=long", s + "switch_cost=1000000"},
           {two, s + "choose=mix", "features.paths.layer=long"}},
          {"bind",
           {two, s + "choose=mix", s + "bind=[{exemplar: 1, where: \"surface = 'a'\"}]"},
           {two, s + "choose=mix"}},
          {"width", {s + "width=5"}},
          {"delta", {s + "delta=4"}},
          {"scale", {s + "scale=5"}},
          {"stitch"},
          // No valid position at 0.75: an error, unless the piece may stay empty.
          // The house over a path leaves pieces without room: transparent, or an error.
          {"empty_pieces", {block, s + "empty_pieces=false"}, {block}, Expect::changes, "", 0, 1},
          {"min_coverage", {s + "min_coverage=0.7"}},
          {"objective"},
          {"coverage_weight", {s + "coverage_weight=0"}},
          {"alpha"},
          // Feathering blends channels, not the coverage: the ridge band's height channel.
          {"feather", {s + "exemplar=" + ridge, s + "feather=2"}, {s + "exemplar=" + ridge}},
          {"seed", {s + "seed=9"}},
          {"backend",
           {s + "backend=opencl"},
           {s + "backend=cpu"},
           Expect::same_bytes,
           "docs/cli.md: outputs are the same bytes on either"},
          {"height_detail",
           {s + "exemplar=" + ridge, s + "height_detail=3"},
           {s + "exemplar=" + ridge}},
          {"channels", {s + "channels={A: splat.stones}"}},
      });
}

TEST_F(PipelineKeys, Binding) {
  const std::string s = "features.paths.synthesis.";
  const std::string hedge = samples + "/exemplars/hedge_192x48.png";
  check_block("binding", s + "bind.0.",
              {paths(), s + "exemplar=[" + chain + ", " + hedge + "]", s + "choose=mix",
               s + "bind=[{exemplar: 0, where: \"surface = 'a'\"}]"},
              {{"exemplar", {s + "bind.0.exemplar=1"}},
               {"where", {s + "bind.0.where=surface = 'b'"}},
               {"tags", {s + "bind.0.where=null", s + "bind.0.tags={surface: [b]}"}},
               {"near_junction", {s + "bind.0.near_junction=30"}}});
}

TEST_F(PipelineKeys, Grow) {
  const std::string g = "features.hedges.grow.";
  check_block(
      "grow", g,
      {"features.hedges={kind: hedge, grow: {element: " + samples +
       "/ornaments/hedge.json, region: [500060, 5000060, 500360, 5000260], max_ornaments: 3, "
       "seed: 5}}"},
      {
          {"element", {g + "element=" + samples + "/ornaments/ditch.json"}},
          {"region", {g + "region=[500100, 5000100, 500400, 5000300]"}},
          {"resolution", {g + "resolution=8"}},
          {"seed", {g + "seed=6"}},
          {"alignment"},
          {"first_fit"},
          {"trials", {g + "trials=2"}},
          {"max_ornaments", {g + "max_ornaments=1"}},
          {"max_elements", {g + "max_elements=5"}},
          {"coverage_radius",
           {g + "coverage_radius=25"},
           {},
           Expect::same_bytes,
           "docs/pipeline.md: `coverage_radius` changes only the coverage report.json reports"},
          {"clearance", {g + "clearance=15"}},
      });
  check_block("grow_region", g + "region.",
              {"features.hedges={kind: hedge, grow: {element: " + samples +
               "/ornaments/hedge.json, region: {source: " + map +
               ", layer: fields}, max_ornaments: 3, seed: 5}}"},
              {{"source", {g + "region.source=" + d.string() + "/map2.gpkg"}},
               {"layer", {g + "region.layer=fields2"}},
               {"where", {g + "region.where=name = 'b'"}}});
}

TEST_F(PipelineKeys, Network) {
  const std::string n = "features.hedges.network.";
  check_block(
      "network", n,
      {"features.hedges={kind: hedge, width: 2, network: {exemplar: " + net +
       ":grid, region: [500060, 5000060, 500460, 5000460], seed: 4}}"},
      {
          {"exemplar", {n + "exemplar=" + net + ":south"}},
          {"exemplar_where", {n + "exemplar_where=kind = 'b'"}},
          {"exemplar_region", {n + "exemplar_region=" + net + ":west"}},
          {"scale",
           {n + "exemplar=" + d.string() + "/grid.svg", n + "scale=3"},
           {n + "exemplar=" + d.string() + "/grid.svg", n + "scale=2"}},
          {"region", {n + "region=[500060, 5000060, 500360, 5000360]"}},
          {"partial", {n + "partial=" + net + ":drawn"}},
          {"seed", {n + "seed=5"}},
          {"lead", {n + "lead=long_axis"}, {n + "lead={bearing: 10}"}},
          {"lead_bearing", {n + "lead_bearing=45"}},
          {"clearance", {n + "clearance=30"}},
          // How far a grown end is pulled onto the network (35 % of the median edge, 35 m).
          // Snapping shows on 600 m (here 400 m: every end reaches the boundary first).
          {"snap",
           {n + "region=[500020, 5000020, 500620, 5000620]", n + "avoid=false", n + "snap=80"},
           {n + "region=[500020, 5000020, 500620, 5000620]", n + "avoid=false"}},
          {"candidates", {n + "candidates=2"}},
          {"method", {n + "method=quilt"}, {n + "method=growth"}},
          // The grid's tracks laid out first, then growth between them.
          {"method", {n + "method=layout"}, {n + "method=growth"}},
          {"avoid"},
      });
}

TEST_F(PipelineKeys, Areas) {
  const std::string a = "features.orchard.";
  const std::string sketches = samples + "/sketches/";
  const std::string orchard = "features.orchard={kind: area, source: " + map +
                              ", layer: fields, sketch: " + sketches +
                              "orchard.geojson, scale: 40}";
  check_block("area_class", a, {orchard},
              {
                  {"kind",
                   {a + "kind=road", a + "sketch=null", a + "scale=null", a + "width=4"},
                   {},
                   Expect::changes,
                   "",
                   0,
                   1},
                  {"source", {a + "source=" + d.string() + "/map2.gpkg"}},
                  {"layer", {a + "layer=fields2"}},
                  {"where", {a + "where=name = 'b'"}},
                  {"tags", {a + "tags={name: [b]}"}},
                  {"sketch", {a + "sketch=" + sketches + "vineyard.geojson"}},
                  {"shapes_from", {a + "shapes_from=" + sketches + "boulders.geojson"}},
                  {"scale", {a + "scale=30"}},
                  {"lead", {a + "lead=nearest_road"}},
                  {"jitter", {a + "jitter=1"}, {a + "jitter=0"}},
                  {"materials", {a + "materials={crown: tree}"}},
                  {"height", {a + "height={crown: 2}"}},
                  {"seed", {a + "seed=8"}},
              });
  check_block("lead", a + "lead.", {orchard, a + "lead={bearing: 30}"},
              {{"bearing", {a + "lead.bearing=75"}}});
}

TEST_F(PipelineKeys, Existing) {
  const std::string e = "existing.0.";
  check_block("existing", e, {"existing=[{source: " + map + ", layer: houses}]"},
              {{"source", {e + "source=" + d.string() + "/map2.gpkg"}},
               {"layer", {e + "layer=fields"}},
               {"where", {e + "where=use = 'house'"}},
               {"tags", {e + "tags={use: [barn]}"}},
               {"width", {e + "layer=walls", e + "width=12"}, {e + "layer=walls", e + "width=3"}}});
}

}  // namespace
}  // namespace tw::test
