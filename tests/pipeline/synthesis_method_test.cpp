// The synthesis-method seam (pipeline/synthesis_method.hpp, docs/methods.md): the built-in
// methods in their fixed order, and a fifth method, defined here only, that reaches the plan,
// the tile render, the tile cache key, the plan folder, the run's outputs (with its facts of
// every tile) and report.json without a line of pipeline code naming it.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/output_folder.hpp"
#include "layers/layer_set.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/input_check.hpp"
#include "pipeline/detail/job_outputs.hpp"
#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/report_json.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/method_report.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/footprint.hpp"
#include "synth/exemplar.hpp"
#include "synth/exemplar_stats.hpp"
#include "terrain/splat.hpp"
#include "test_support.hpp"
#include "test_world.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A stamp: one square of `side` pixels at the grid's centre, painted in its own splat material
// "stamp" and raised by `raise` metres.
struct StampPlan : MethodPayloadOf<StampPlan> {
  std::vector<Window> squares;
  std::size_t material = 0;  // in plan.splat_materials
  float raise = 0.0f;
};

// Its part of the run's report: how many squares it stamped.
struct StampReport : MethodPayloadOf<StampReport> {
  std::uint64_t squares = 0;
};

class StampMethod final : public SynthesisMethod {
 public:
  explicit StampMethod(int side, float raise) : side_(side), raise_(raise) {}
  std::string name() const override { return "stamp"; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig&, const PlanOptions& options) const override {
    return options.synthesize;
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<StampPlan>();
  }
  void plan(MethodContext& context, MethodPlan& entry) const override {
    const GridSpec& g = context.plan.grid;
    StampPlan& stamp = payload_as<StampPlan>(entry);
    stamp.squares = {{g.width / 2 - side_ / 2, g.height / 2 - side_ / 2, side_, side_}};
    stamp.raise = raise_;
    method_report<StampReport>(context.plan.report, name()).squares = stamp.squares.size();
  }
  void collect(MethodContext& context, MethodPlan& entry) const override {
    std::vector<std::string>& materials = context.plan.splat_materials;
    payload_as<StampPlan>(entry).material = materials.size();
    materials.push_back("stamp");
  }
  std::vector<Window> windows(const WorldPlan&, const MethodPlan& entry) const override {
    return payload_as<StampPlan>(entry).squares;
  }
  bool renders() const override { return true; }
  void render(const WorldPlan&, const MethodPlan& entry, const Window& window,
              Raster<float>& height, SplatLayers& splat) const override {
    const StampPlan& stamp = payload_as<StampPlan>(entry);
    for (const std::size_t i : items_meeting(entry.index, window)) {
      const Window part = intersect(stamp.squares[i], window);
      for (int r = part.row0; r < part.row_end(); ++r)
        for (int c = part.col0; c < part.col_end(); ++c) {
          const int x = c - window.col0, y = r - window.row0;
          height.at(x, y) += stamp.raise;
          for (std::size_t m = 0; m < splat.weights.size(); ++m)
            splat.weights[m].at(x, y) = m == stamp.material ? 1.0f : 0.0f;
        }
    }
  }
  std::vector<ContentHash> item_hashes(const WorldPlan&, const MethodPlan& entry) const override {
    std::vector<ContentHash> out;
    for (const Window& w : payload_as<StampPlan>(entry).squares) {
      Hasher h;
      detail::hash_window(h, w);
      out.push_back(h.real(payload_as<StampPlan>(entry).raise).digest());
    }
    return out;
  }
  // Per tile: the square's pixels in the tile's core and the height at the first of them.
  std::string tile_fact_key() const override { return "stamp_pixels"; }
  std::string tile_fact(const WorldPlan&, const MethodPlan& entry, const Raster<float>& height,
                        const Window& halo, const Window& core) const override {
    const Window part = intersect(payload_as<StampPlan>(entry).squares.at(0), core);
    if (part.width == 0) return "0";
    return fmt::format("{} {}", part.width * part.height,
                       height.at(part.col0 - halo.col0, part.row0 - halo.row0));
  }
  // stamp.txt: every tile's fact, one line each.
  std::string outputs_stage(const WorldPlan&, const MethodPlan&) const override {
    return "stamp.txt";
  }
  void write_outputs(const WorldPlan&, const MethodPlan&, MethodOutputs& outputs) const override {
    std::ofstream out(outputs.transaction.stage(outputs.dir / "stamp.txt"));
    for (const MethodTileFact& f : outputs.tile_facts) out << f.where << ": " << f.fact << "\n";
  }
  // Its part under `methods.stamp` of report.json, and its field in every class.
  void report_json(const RunReport& report, const PipelineConfig&, json& out) const override {
    if (const StampReport* part = method_report<StampReport>(report))
      out["methods"][name()] = {{"squares", part->squares}};
    for (std::size_t c = 0; c < report.classes.size(); ++c)
      out["classes"][c]["stamped"] = report.classes[c].name;
  }
  // Its part in plan.json itself: a number needs no object of its own.
  json encode_report(const MethodPayload& part, detail::PlanObjects&) const override {
    return {{"squares", dynamic_cast<const StampReport&>(part).squares}};
  }
  std::unique_ptr<MethodPayload> decode_report(const json& value,
                                               detail::PlanObjects&) const override {
    auto part = std::make_unique<StampReport>();
    part->squares = value.at("squares").get<std::uint64_t>();
    return part;
  }
  json encode(const MethodPlan& entry, detail::PlanObjects& objects) const override {
    const StampPlan& stamp = payload_as<StampPlan>(entry);
    return {{"squares", objects.put_cbor(detail::encode(stamp.squares))},
            {"material", stamp.material},
            {"raise", stamp.raise}};
  }
  void decode(const json& value, detail::PlanObjects& objects, MethodPlan& entry) const override {
    StampPlan& stamp = payload_as<StampPlan>(entry);
    detail::decode(objects.get_cbor(value.at("squares"), "stamp"), stamp.squares, "stamp");
    stamp.material = value.at("material").get<std::size_t>();
    stamp.raise = value.at("raise").get<float>();
  }

 private:
  int side_;
  float raise_;
};

constexpr const char* kWorld = R"(version: 1
seed: 3
heightfield: dem.tif
output: { dir: out, exr: false, geotiff: true, preview: false }
features:
  roads:
    source: map.gpkg
    layer: roads
    kind: road
    width: 6
)";

class SynthesisMethods : public ::testing::Test {
 protected:
  void SetUp() override {
    test::write_dem(dir_ / "dem.tif");  // 64 x 64 pixels of 10 m
    test::write_layer(dir_ / "map.gpkg", "roads",
                      {{"LINESTRING (500020 5000100, 500300 5000400, 500600 5000620)"}});
  }
  PipelineConfig config() const { return parse_pipeline(kWorld, "world.yaml", dir_.path(), {}); }
  PipelineConfig tiled_config() const {  // tiles of 24 pixels, 2 of overlap
    std::string yaml = kWorld;
    const std::string output = "preview: false }";
    yaml.replace(yaml.find(output), output.size(),
                 "preview: false, tiles: { size: 24, overlap: 2 } }");
    return parse_pipeline(yaml, "world.yaml", dir_.path(), {});
  }

  // The built-in methods and a stamp after them.
  std::vector<const SynthesisMethod*> with_stamp(const StampMethod& stamp) const {
    std::vector<const SynthesisMethod*> methods = builtin_synthesis_methods();
    methods.push_back(&stamp);
    return methods;
  }

  WorldPlan plan(const std::vector<const SynthesisMethod*>& methods) const {
    return plan(methods, config());
  }
  WorldPlan plan(const std::vector<const SynthesisMethod*>& methods,
                 const PipelineConfig& config) const {
    Warnings warnings;
    PlanOptions options;
    options.methods = methods;
    return plan_world(config, options, warnings);
  }

  test::TempDir dir_;
};

TEST(SynthesisMethodRegistry, TheBuiltInMethodsComeLinesFirstThenPatternsThenAreas) {
  std::vector<std::string> names;
  std::vector<MethodStage> stages;
  for (const SynthesisMethod* m : builtin_synthesis_methods()) {
    names.push_back(m->name());
    stages.push_back(m->stage());
  }
  EXPECT_EQ(names, (std::vector<std::string>{"grown", "network", "patterns", "areas"}));
  EXPECT_EQ(stages, (std::vector<MethodStage>{MethodStage::lines, MethodStage::lines,
                                              MethodStage::placements, MethodStage::placements}));
}

TEST_F(SynthesisMethods, APlanHoldsOneEntryPerMethodInOrder) {
  const StampMethod stamp(8, 2.0f);
  const WorldPlan plan = this->plan(with_stamp(stamp));
  std::vector<std::string> names;
  for (const MethodPlan& entry : plan.methods) names.push_back(method_name(entry));
  EXPECT_EQ(names, (std::vector<std::string>{"grown", "network", "patterns", "areas", "stamp"}));
  // Copying a plan copies the payloads.
  const WorldPlan copy = plan;
  EXPECT_NE(copy.methods.back().payload.get(), plan.methods.back().payload.get());
  EXPECT_EQ(payload_as<StampPlan>(copy.methods.back()).squares.size(), 1u);
}

TEST_F(SynthesisMethods, AFifthMethodReachesTheTileRenderTheCacheKeyThePlanFolderAndTheReport) {
  const StampMethod stamp(8, 2.0f);
  const WorldPlan bare = plan(builtin_synthesis_methods());
  const WorldPlan stamped = plan(with_stamp(stamp));
  ASSERT_EQ(stamped.tiles.size(), 1u);
  const LayerSet without = render_tile(bare, bare.tiles[0]);
  const LayerSet with = render_tile(stamped, stamped.tiles[0]);

  // The render: the square is raised by 2 m and all "stamp"; every other pixel is unchanged.
  const Layer* splat = find_layer(with, "splat");
  ASSERT_NE(splat, nullptr);
  const auto channel = std::find(splat->channels.begin(), splat->channels.end(), "splat.stamp");
  ASSERT_NE(channel, splat->channels.end());
  const std::size_t s = std::size_t(channel - splat->channels.begin());
  EXPECT_EQ(s, splat_materials().size());  // after the terrain's materials
  const Raster<float>& h0 = find_layer(without, "height")->bands[0];
  const Raster<float>& h1 = find_layer(with, "height")->bands[0];
  const Window square = payload_as<StampPlan>(stamped.methods.back()).squares.at(0);
  int inside = 0, outside_changed = 0;
  for (int y = 0; y < h1.height; ++y)
    for (int x = 0; x < h1.width; ++x) {
      const bool in =
          x >= square.col0 && x < square.col_end() && y >= square.row0 && y < square.row_end();
      if (in) {
        ++inside;
        EXPECT_FLOAT_EQ(h1.at(x, y), h0.at(x, y) + 2.0f);
        EXPECT_EQ(splat->bands[s].at(x, y), 1.0f);
      } else {
        outside_changed += h1.at(x, y) != h0.at(x, y);
        EXPECT_EQ(splat->bands[s].at(x, y), 0.0f);
      }
    }
  EXPECT_EQ(inside, 64);
  EXPECT_EQ(outside_changed, 0);

  // The tile cache key: its section changes with the stamp's items.
  const StampMethod higher(8, 3.0f);
  Warnings warnings;
  const WorldPlan raised = plan(with_stamp(higher));
  const detail::TileCache a(stamped, WriteOptions{}, std::nullopt, warnings);
  const detail::TileCache b(raised, WriteOptions{}, std::nullopt, warnings);
  EXPECT_EQ(a.key(stamped.tiles[0]).heightfield, b.key(raised.tiles[0]).heightfield);
  EXPECT_NE(a.key(stamped.tiles[0]).features, b.key(raised.tiles[0]).features);

  // The plan folder: the entry travels and renders the same bytes; a program that does not
  // know the method refuses the plan, naming it.
  save_plan(stamped, dir_ / "plan");
  const WorldPlan loaded = load_plan(dir_ / "plan", with_stamp(stamp));
  const LayerSet again = render_tile(loaded, loaded.tiles[0]);
  EXPECT_EQ(find_layer(again, "height")->bands[0].pixels, h1.pixels);
  EXPECT_EQ(find_layer(again, "splat")->bands[s].pixels, splat->bands[s].pixels);
  try {
    load_plan(dir_ / "plan");
    FAIL() << "a plan with an unknown method loaded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("method 'stamp'"), std::string::npos) << e.what();
  }

  // report.json: the method's own part (its type, back from the plan folder) under its name;
  // none for the built-in methods.
  const StampReport* part = method_report<StampReport>(loaded.report);
  ASSERT_NE(part, nullptr);
  EXPECT_EQ(part->squares, 1u);
  const json report = detail::report_to_json(loaded.report, config(), methods_in(loaded));
  EXPECT_EQ(report.at("methods").at("stamp").at("squares"), 1);
  EXPECT_FALSE(detail::report_to_json(bare.report, config(), methods_in(bare)).contains("methods"));
}

TEST_F(SynthesisMethods, AFifthMethodsTileFactsOutputsAndReportFieldsGoThroughTheSeam) {
  const StampMethod stamp(8, 2.0f);
  const std::vector<const SynthesisMethod*> methods = with_stamp(stamp);
  const WorldPlan plan = this->plan(methods, tiled_config());
  ASSERT_EQ(plan.tiles.size(), 9u);  // 64 pixels in tiles of 24: 3 x 3

  // Every tile's facts hold each method's under its key (the areas' instance heights too), and
  // the outputs get the stamp's facts of every tile, in tile order.
  detail::MethodTileFacts facts;
  int pixels = 0;
  for (const TileSpec& tile : plan.tiles) {
    const LayerSet layers = render_tile(plan, tile);
    const std::map<std::string, std::string> tile_facts = detail::tile_facts(plan, layers, tile);
    ASSERT_TRUE(tile_facts.contains("stamp_pixels"));
    EXPECT_TRUE(tile_facts.contains("instance_heights"));
    EXPECT_TRUE(tile_facts.contains("xxh64"));
    std::istringstream fact(tile_facts.at("stamp_pixels"));
    int n = 0;
    fact >> n;
    pixels += n;
    if (n > 0) {  // the raised height of the square's first pixel in this tile
      const Window part =
          intersect(payload_as<StampPlan>(plan.methods.back()).squares[0], tile.window);
      float z = 0.0f;
      fact >> z;
      EXPECT_EQ(z, find_layer(layers, "height")
                       ->bands[0]
                       .at(part.col0 - tile.halo_window.col0, part.row0 - tile.halo_window.row0));
    }
    detail::add_method_facts(plan, tile_facts, fmt::format("tile {}", tile.index), facts);
  }
  EXPECT_EQ(pixels, 64);  // the square, once over the tiles' cores
  ASSERT_EQ(facts.size(), plan.methods.size());
  ASSERT_EQ(facts.back().size(), plan.tiles.size());

  OutputFolder folder(dir_ / "out");
  RunReport report = plan.report;
  detail::write_method_outputs(plan, facts, dir_ / "out", folder, report, nullptr);
  detail::write_job_report(plan, report, config(), dir_ / "out", folder);
  folder.commit();
  // report.json is written by the plan's methods: the stamp's own part is there.
  const json written_report = json::parse(read_file_bytes(dir_ / "out" / "report.json"));
  EXPECT_EQ(written_report.at("methods").at("stamp").at("squares"), 1);
  EXPECT_EQ(written_report.at("classes").at(0).at("stamped"), "roads");
  const std::string written = read_file_bytes(dir_ / "out" / "stamp.txt");
  std::string expected;
  for (const MethodTileFact& f : facts.back()) expected += f.where + ": " + f.fact + "\n";
  EXPECT_EQ(written, expected);
  EXPECT_NE(written.find("tile 8: "), std::string::npos);
  // The built-in methods wrote nothing here: no patterns, areas or grown classes.
  EXPECT_FALSE(fs::exists(dir_ / "out" / "areas.gpkg"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "ornaments.gpkg"));

  // report.json: its field in every class; the built-in methods' fields come from them, so a
  // list without them has none of their keys.
  const json with_all = detail::report_to_json(report, config(), methods);
  EXPECT_EQ(with_all.at("classes").at(0).at("stamped"), "roads");
  EXPECT_EQ(with_all.at("methods").at("stamp").at("squares"), 1);
  for (const char* key : {"areas", "pattern_violations", "grown_crossings"})
    EXPECT_TRUE(with_all.contains(key)) << key;
  EXPECT_TRUE(with_all.at("timings").contains("synthesis"));
  const json stamp_only = detail::report_to_json(report, config(), {&stamp});
  EXPECT_EQ(stamp_only.at("classes").at(0).at("stamped"), "roads");
  for (const char* key : {"areas", "pattern_violations", "grown_crossings"})
    EXPECT_FALSE(stamp_only.contains(key)) << key;
  EXPECT_FALSE(stamp_only.at("timings").contains("synthesis"));
  EXPECT_FALSE(detail::report_to_json(report, config(), builtin_synthesis_methods())
                   .at("classes")
                   .at(0)
                   .contains("stamped"));
}

// A method that only resolves a default of its own (the seed, here) and records the inputs it
// is asked to check, claiming none: what the pipeline asks of every method before any stage.
class InputsRecorderMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return "inputs_recorder"; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig&, const PlanOptions&) const override { return false; }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<StampPlan>();
  }
  void resolve_defaults(PipelineConfig& config) const override { config.seed += 100; }
  bool check_input(const InputFile& input, detail::InputCheck&) const override {
    checked.push_back(input.path.filename().string());
    return false;
  }
  void plan(MethodContext&, MethodPlan&) const override {}
  json encode(const MethodPlan&, detail::PlanObjects&) const override { return {}; }
  void decode(const json&, detail::PlanObjects&, MethodPlan&) const override {}

  mutable std::vector<std::string> checked;
};

TEST_F(SynthesisMethods, DefaultsAndInputChecksGoThroughTheMethods) {
  // Without a synthesis class, the built-in methods leave the config as it is.
  const PipelineConfig plain = with_method_defaults(config());
  EXPECT_EQ(plain.seed, 3u);
  ASSERT_EQ(plain.features.size(), 1u);
  EXPECT_FALSE(has_method_options(plain.features[0], kPatternsMethodName));

  // With one, the patterns method sets its width and delta from the exemplar, flagged so.
  test::crop_raster(test::source_dir() / "samples/exemplars/cobble_edging_200x56.png",
                    dir_ / "cobble.png", "PNG", 60, 56);
  const PipelineConfig given =
      parse_pipeline(std::string(kWorld) + "    synthesis: { exemplar: cobble.png, scale: 5 }\n",
                     "world.yaml", dir_.path(), {});
  ASSERT_TRUE(has_method_options(given.features[0], kPatternsMethodName));
  EXPECT_FALSE(
      method_options<SynthesisConfig>(given.features[0], kPatternsMethodName)->width.has_value());
  EXPECT_FALSE(
      method_options<SynthesisConfig>(given.features[0], kPatternsMethodName)->delta.has_value());
  const ExemplarStats stats = exemplar_stats(load_exemplar((dir_ / "cobble.png").string()));
  const PipelineConfig resolved = with_method_defaults(given);
  const SynthesisConfig& s =
      *method_options<SynthesisConfig>(resolved.features[0], kPatternsMethodName);
  ASSERT_TRUE(s.width && s.delta);
  EXPECT_DOUBLE_EQ(*s.width, suggested_width(stats, 5.0));
  EXPECT_DOUBLE_EQ(*s.delta, suggested_delta(stats, 5.0));
  EXPECT_TRUE(s.width_from_exemplar);
  EXPECT_TRUE(s.delta_from_exemplar);
  EXPECT_EQ(resolved.seed, 3u);

  // The pipeline names no method: a list without the patterns resolves only its own defaults,
  // and each of the config's inputs is offered to its methods before the pipeline opens it.
  const InputsRecorderMethod recorder;
  const PipelineConfig recorded = with_method_defaults(given, {&recorder});
  EXPECT_EQ(recorded.seed, 103u);
  EXPECT_FALSE(method_options<SynthesisConfig>(recorded.features[0], kPatternsMethodName)
                   ->delta.has_value());
  detail::check_inputs(given.inputs, std::nullopt, {&recorder});
  EXPECT_EQ(recorder.checked, (std::vector<std::string>{"dem.tif", "map.gpkg", "cobble.png"}));
  // The built-in patterns method checks the exemplar, at its key.
  write_file_atomic(dir_ / "cobble.png", "not a PNG");
  try {
    detail::check_inputs(given.inputs, std::nullopt);
    ADD_FAILURE() << "a broken exemplar passed the check";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("world.yaml:11:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(
                  "features.roads.synthesis.exemplar: cannot be used as an exemplar"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tw
