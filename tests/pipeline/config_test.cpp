// The pipeline file: types, defaults, relative paths, precedence, overrides, and located errors.
#include "pipeline/config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "core/error.hpp"
#include "pipeline/detail/manifest.hpp"
#include "pipeline/detail/region.hpp"
#include "pipeline/methods/areas/area_config.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const char* const kMinimal = R"(version: 1
seed: 7
heightfield: ../samples/dem.tif
features:
  roads: { source: map.gpkg, layer: roads, kind: road, width: 8 }
)";

PipelineConfig parse(const std::string& text, const std::vector<Override>& overrides = {}) {
  return parse_pipeline(text, "p.yaml", "/base/dir", overrides);
}

// The message of the tw::Error that parsing `text` throws ("" when it does not throw).
std::string error_of(const std::string& text, const std::vector<Override>& overrides = {}) {
  try {
    parse(text, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(PipelineConfig, ReadsValuesAndFillsDefaults) {
  const PipelineConfig c = parse(kMinimal);
  EXPECT_EQ(c.version, 1);
  EXPECT_EQ(c.seed, 7u);
  ASSERT_TRUE(c.heightfield.has_value());
  EXPECT_EQ(*c.heightfield, fs::path("/base/samples/dem.tif"));
  EXPECT_FALSE(c.resolution.has_value());
  EXPECT_EQ(c.backend, "auto");
  EXPECT_EQ(c.output.dir, fs::path("/base/dir/out"));
  EXPECT_TRUE(c.output.exr && c.output.geotiff && c.output.preview);
  ASSERT_EQ(c.features.size(), 1u);
  const FeatureClassConfig& roads = c.features[0];
  EXPECT_EQ(roads.name, "roads");
  EXPECT_EQ(roads.source, fs::path("/base/dir/map.gpkg"));
  EXPECT_EQ(roads.layer, "roads");
  EXPECT_EQ(roads.kind, FeatureKind::road);
  EXPECT_DOUBLE_EQ(roads.width, 8.0);
  EXPECT_DOUBLE_EQ(roads.road.max_grade, RoadProfile{}.max_grade);
  EXPECT_FALSE(has_method_options(roads, kPatternsMethodName));
  EXPECT_TRUE(c.existing.empty());
}

TEST(PipelineConfig, ReadsEveryNestedSection) {
  const PipelineConfig c = parse(R"(version: 1
seed: 3
generate: { width: 300, height: 200, pixel_size: 2.5, relief: 50, origin: [1000, 9000] }
resolution: 4
output: { dir: /tmp/o, exr: false, geotiff: true, preview: false }
backend: cpu
precedence: [ridges, rivers, roads]
features:
  roads: { source: m.gpkg, kind: road, width_attribute: w, where: "type = 'a'",
           profile: { max_grade: 0.05, shoulder_width: 2, falloff: 10, smoothing: 30 },
           synthesis: { exemplar: [a.png, b.png], delta: 3, scale: 6, stitch: false, backend: opencl } }
  ridges: { source: m.gpkg, layer: ridges, kind: ridge, width: 40, profile: { height: 12, sharpness: 2 } }
  rivers: { source: m.gpkg, layer: rivers, kind: river, width: 12,
            synthesis: { exemplar: r.png, seed: 99 } }
existing:
  - { source: m.gpkg, layer: existing }
  - { source: /abs/lines.shp, width: 6 }
)");
  EXPECT_FALSE(c.heightfield.has_value());
  EXPECT_EQ(c.generate.width, 300);
  EXPECT_EQ(c.generate.height, 200);
  EXPECT_DOUBLE_EQ(c.generate.pixel_size, 2.5);
  EXPECT_DOUBLE_EQ(c.generate.origin_x, 1000.0);
  EXPECT_DOUBLE_EQ(c.generate.origin_y, 9000.0);
  EXPECT_DOUBLE_EQ(*c.resolution, 4.0);
  EXPECT_EQ(c.output.dir, fs::path("/tmp/o"));
  EXPECT_FALSE(c.output.exr);
  EXPECT_FALSE(c.output.preview);
  EXPECT_EQ(c.backend, "cpu");
  ASSERT_EQ(c.features.size(), 3u);
  EXPECT_EQ(c.features[0].name, "ridges");
  EXPECT_EQ(c.features[1].name, "rivers");
  EXPECT_EQ(c.features[2].name, "roads");
  const FeatureClassConfig& roads = c.features[2];
  EXPECT_EQ(roads.width_attribute, "w");
  EXPECT_EQ(roads.where, "type = 'a'");
  EXPECT_DOUBLE_EQ(roads.road.max_grade, 0.05);
  EXPECT_DOUBLE_EQ(roads.road.smoothing, 30.0);
  ASSERT_TRUE(has_method_options(roads, kPatternsMethodName));
  EXPECT_EQ(method_options<SynthesisConfig>(roads, kPatternsMethodName)->exemplars,
            (std::vector<fs::path>{"/base/dir/a.png", "/base/dir/b.png"}));
  EXPECT_DOUBLE_EQ(method_options<SynthesisConfig>(roads, kPatternsMethodName)->delta.value_or(0.0),
                   3.0);
  EXPECT_FALSE(method_options<SynthesisConfig>(roads, kPatternsMethodName)->stitch);
  EXPECT_EQ(method_options<SynthesisConfig>(roads, kPatternsMethodName)->seed,
            3u);  // the pipeline's seed by default
  EXPECT_EQ(method_options<SynthesisConfig>(roads, kPatternsMethodName)->backend, "opencl");
  EXPECT_EQ(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->seed, 99u);
  EXPECT_EQ(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->backend, "");
  EXPECT_DOUBLE_EQ(c.features[0].ridge.height, 12.0);
  EXPECT_DOUBLE_EQ(c.features[0].ridge.sharpness, 2.0);
  ASSERT_EQ(c.existing.size(), 2u);
  EXPECT_EQ(c.existing[0].layer, "existing");
  EXPECT_EQ(c.existing[1].source, fs::path("/abs/lines.shp"));
  EXPECT_DOUBLE_EQ(c.existing[1].width, 6.0);
}

TEST(PipelineConfig, UnknownKeyNamesFileLineColumnAndSuggests) {
  const std::string text =
      std::string(kMinimal) + "  rivers: { source: m.gpkg, kind: river, widht: 3 }\n";
  EXPECT_EQ(error_of(text),
            "p.yaml:6:42: features.rivers.widht: unknown key (did you mean 'width'?)");
  EXPECT_EQ(error_of(std::string(kMinimal) + "colour: red\n"), "p.yaml:6:1: colour: unknown key");
}

TEST(PipelineConfig, WrongTypesAndBadValuesAreLocated) {
  EXPECT_EQ(error_of("version: 1\nseed: seven\n"),
            "p.yaml:2:7: seed: expected a non-negative integer, got 'seven'");
  EXPECT_EQ(error_of(R"(version: 1
features:
  roads: { source: m.gpkg, kind: road, width: wide }
)"),
            "p.yaml:3:47: features.roads.width: expected a number, got 'wide'");
  EXPECT_EQ(error_of(R"(version: 1
features:
  roads: { source: m.gpkg, kind: road, width: 0 }
)"),
            "p.yaml:3:47: features.roads.width: must be > 0, got 0");
  EXPECT_THAT(error_of(R"(version: 1
features:
  roads: { source: m.gpkg, kind: road, width: 3, synthesis: { exemplar: e.png, delta: -1 } }
)"),
              HasSubstr("features.roads.synthesis.delta: must be > 0, got -1"));
  EXPECT_THAT(error_of("version: 1\nresolution: .nan\nfeatures: {}\n"),
              HasSubstr("p.yaml:2:13: resolution: must be a finite number"));
  EXPECT_THAT(error_of("version: 1\noutput: [a]\n"),
              HasSubstr("p.yaml:2:9: output: expected a mapping"));
  EXPECT_THAT(error_of(R"(version: 1
features:
  roads: { source: m.gpkg, kind: raod, width: 3 }
)"),
              HasSubstr("features.roads.kind: unknown kind 'raod', expected road, river, ridge, "
                        "hedge, wall, trail or ditch (did you mean 'road'?)"));
  EXPECT_THAT(error_of("version: 2\n"), HasSubstr("p.yaml:1:10: version: only version 1"));
  EXPECT_THAT(error_of("version: 1\nbackend: gpu\n"), HasSubstr("backend: unknown backend 'gpu'"));
  EXPECT_THAT(error_of("version: [1\n"), HasSubstr("p.yaml:"));
}

TEST(PipelineConfig, RegionIsARectangleWithLocatedErrors) {
  EXPECT_FALSE(parse(kMinimal).region.has_value());
  const PipelineConfig c = parse(std::string(kMinimal) + "region: [1000, 2000.5, 1600, 2400]\n");
  ASSERT_TRUE(c.region.has_value());
  EXPECT_DOUBLE_EQ(c.region->min_x, 1000.0);
  EXPECT_DOUBLE_EQ(c.region->min_y, 2000.5);
  EXPECT_DOUBLE_EQ(c.region->max_x, 1600.0);
  EXPECT_DOUBLE_EQ(c.region->max_y, 2400.0);
  EXPECT_THAT(error_of(std::string(kMinimal) + "region: [1, 2, 3]\n"),
              HasSubstr("p.yaml:6:9: region: expected [min_x, min_y, max_x, max_y] in metres"));
  EXPECT_THAT(error_of(std::string(kMinimal) + "region: [1, 2, x, 4]\n"),
              HasSubstr("region.2: expected a number, got 'x'"));
  EXPECT_THAT(error_of(std::string(kMinimal) + "region: [5, 2, 3, 4]\n"),
              HasSubstr("region: min_x 5 is not below max_x 3"));
  EXPECT_THAT(error_of(std::string(kMinimal) + "region: [1, 4, 3, 4]\n"),
              HasSubstr("region: min_y 4 is not below max_y 4"));
  // --set can give a region too.
  const PipelineConfig o = parse(kMinimal, {parse_override("region=[0, 0, 10, 10]")});
  ASSERT_TRUE(o.region.has_value());
  EXPECT_DOUBLE_EQ(o.region->max_x, 10.0);
}

// What a region does to the output grid: the world grid's cells that meet it (a window, so
// the region's pixels are the world's), an error naming the region when it misses the grid.
TEST(PipelineConfig, RegionIsTheWindowOfTheWorldGridItMeets) {
  const GridSpec grid{10, 10, 1000.0, 2100.0, 10.0, 10.0};  // x 1000..1100, y 2000..2100
  EXPECT_EQ(detail::region_window(grid, {1021.3, 2040.0, 1059.9, 2070.2}, "dem.tif"),
            (Window{2, 2, 4, 4}));  // columns 1020..1060, rows 2080..2040 (the edge at 2040)
  EXPECT_EQ(detail::region_window(grid, {1020.0, 2030.0, 1030.0, 2040.0}, "dem.tif"),
            (Window{2, 6, 1, 1}));  // edges on cell edges: one cell
  EXPECT_EQ(detail::region_window(grid, {900.0, 1900.0, 1010.0, 2010.0}, "dem.tif"),
            (Window{0, 9, 1, 1}));  // clipped to the grid
  EXPECT_EQ(detail::region_window(grid, {0.0, 0.0, 5000.0, 5000.0}, "dem.tif"),
            Window::whole(grid));
  try {
    detail::region_window(grid, {0.0, 0.0, 10.0, 10.0}, "dem.tif");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(),
                HasSubstr("region [0, 0, 10, 10]: does not overlap the heightfield dem.tif"));
  }
  EXPECT_THAT(error_of(std::string(kMinimal) + "resampling: lanczos\n"),
              HasSubstr("resampling: unknown resampling 'lanczos', expected bilinear or cubic"));
  EXPECT_EQ(parse(std::string(kMinimal) + "resampling: cubic\n").resampling, Resampling::cubic);
  EXPECT_EQ(parse(kMinimal).resampling, Resampling::bilinear);
}

TEST(PipelineConfig, MissingRequiredKeysAreNamed) {
  EXPECT_THAT(error_of("seed: 1\n"), HasSubstr("version: missing required key"));
  EXPECT_THAT(error_of("version: 1\n"), HasSubstr("features: missing required key"));
  EXPECT_EQ(error_of("version: 1\nfeatures:\n  roads: { kind: road, width: 3 }\n"),
            "p.yaml:3:10: features.roads.source: missing required key");
  EXPECT_THAT(error_of("version: 1\nfeatures:\n  roads: { source: a, kind: road }\n"),
              HasSubstr("features.roads.width: missing required key"));
}

TEST(PipelineConfig, PrecedenceMustNameEachClassOnce) {
  const std::string two =
      std::string(kMinimal) + "  rivers: { source: m.gpkg, kind: river, width: 3 }\n";
  EXPECT_THAT(error_of(two + "precedence: [rivers, roadz]\n"),
              HasSubstr("precedence.1: 'roadz' is not a feature class (did you mean 'roads'?)"));
  EXPECT_THAT(error_of(two + "precedence: [rivers]\n"),
              HasSubstr("precedence: feature class 'roads' is missing from the list"));
  EXPECT_THAT(error_of(two + "precedence: [rivers, rivers]\n"),
              HasSubstr("'rivers' is listed twice"));
}

TEST(PipelineConfig, SynthesisKeys) {
  const std::string classes = R"(version: 1
features:
  roads: { source: m.gpkg, kind: road, width: 6,
           synthesis: { exemplar: [a.png, b.png], choose: best, width: 12, empty_pieces: false,
                        channels: { alpha: splat.marking, height: height }, height_detail: 0.5,
                        min_coverage: 0.25, alpha: continuous, feather: 3 } }
  rivers: { source: m.gpkg, kind: river, width: 9, synthesis: { exemplar: r.png } }
  ridges: { source: m.gpkg, kind: ridge, width: 40 }
)";
  const PipelineConfig c = parse(classes + "synthesis_resolution: 0.5\n");
  EXPECT_DOUBLE_EQ(c.synthesis_resolution, 0.5);
  EXPECT_EQ(synthesis_order(c), (std::vector<std::string>{"roads", "rivers"}));
  const SynthesisConfig& s = *method_options<SynthesisConfig>(c.features[0], kPatternsMethodName);
  EXPECT_EQ(s.choice, ExemplarChoice::best);
  EXPECT_DOUBLE_EQ(*s.width, 12.0);
  EXPECT_FALSE(s.empty_pieces);
  EXPECT_DOUBLE_EQ(s.height_detail, 0.5);
  EXPECT_DOUBLE_EQ(s.min_coverage.value_or(-1.0), 0.25);
  EXPECT_FALSE(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)
                   ->min_coverage);  // from the exemplar
  EXPECT_EQ(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->objective,
            Objective::pattern);
  EXPECT_TRUE(s.continuous_alpha);
  EXPECT_DOUBLE_EQ(s.feather, 3.0);
  EXPECT_DOUBLE_EQ(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->feather,
                   0.0);
  EXPECT_FALSE(
      method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->continuous_alpha);
  ASSERT_EQ(s.channels.size(), 2u);
  EXPECT_EQ(s.channels[0].channel, "A");
  EXPECT_EQ(s.channels[0].target, "splat.marking");
  EXPECT_EQ(s.channels[1].channel, "height");
  EXPECT_TRUE(
      method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->channels.empty());
  EXPECT_DOUBLE_EQ(
      method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->height_detail, 1.0);
  EXPECT_FALSE(method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)
                   ->width.has_value());  // from the exemplar (plan_world)
  EXPECT_FALSE(
      method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->delta.has_value());
  EXPECT_FALSE(
      method_options<SynthesisConfig>(c.features[1], kPatternsMethodName)->width_of_feature);
  PipelineConfig feature_width = parse(classes, {{"features.rivers.synthesis.width", "feature"}});
  EXPECT_TRUE(method_options<SynthesisConfig>(feature_width.features[1], kPatternsMethodName)
                  .width_of_feature);
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.width", "wide"}}),
              HasSubstr("features.rivers.synthesis.width: expected a number, got 'wide'"));

  EXPECT_EQ(synthesis_order(parse(classes + "synthesis_order: [rivers, roads]\n")),
            (std::vector<std::string>{"rivers", "roads"}));
  EXPECT_THAT(error_of(classes + "synthesis_order: [rivers]\n"),
              HasSubstr("synthesis_order: feature class 'roads' (with synthesis) is missing"));
  EXPECT_THAT(error_of(classes + "synthesis_order: [rivers, roads, ridges]\n"),
              HasSubstr("synthesis_order.2: 'ridges' is not a feature class with synthesis"));
  EXPECT_THAT(error_of(classes + "synthesis_order: [roads, roads]\n"),
              HasSubstr("'roads' is listed twice"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.channels", "{A: colour}"}}),
              HasSubstr("features.rivers.synthesis.channels.A: unknown output 'colour'"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.choose", "worst"}}),
              HasSubstr("unknown choice 'worst'"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.feather", "-1"}}),
              HasSubstr("features.rivers.synthesis.feather"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.alpha", "soft"}}),
              HasSubstr("features.rivers.synthesis.alpha: unknown alpha 'soft', expected binary "
                        "or continuous"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.min_coverage", "1"}}),
              HasSubstr("features.rivers.synthesis.min_coverage: must be below 1"));
  EXPECT_THAT(error_of(classes, {{"features.rivers.synthesis.min_coverage", "-0.1"}}),
              HasSubstr("features.rivers.synthesis.min_coverage"));
}

TEST(PipelineConfig, OverridesReplaceAddAndResolveAgainstTheCurrentFolder) {
  const PipelineConfig c = parse(
      kMinimal,
      {parse_override("heightfield=other.tif"), parse_override("features.roads.width=12.5"),
       parse_override("output={dir: /o, preview: false}"), parse_override("seed=11"),
       parse_override("features.rivers.source=r.gpkg"),
       parse_override("features.rivers.kind=river"), parse_override("features.rivers.width=4")});
  EXPECT_EQ(*c.heightfield, fs::current_path() / "other.tif");
  EXPECT_DOUBLE_EQ(c.features[0].width, 12.5);
  EXPECT_EQ(c.output.dir, fs::path("/o"));
  EXPECT_FALSE(c.output.preview);
  EXPECT_EQ(c.seed, 11u);
  ASSERT_EQ(c.features.size(), 2u);
  EXPECT_EQ(c.features[1].source, fs::current_path() / "r.gpkg");
  const PipelineConfig listed = parse(std::string(kMinimal) + "existing: [{source: a.gpkg}]\n",
                                      {parse_override("existing.0.layer=houses")});
  EXPECT_EQ(listed.existing[0].layer, "houses");
}

TEST(PipelineConfig, BadOverridesNameTheOverride) {
  EXPECT_EQ(
      error_of(kMinimal, {parse_override("features.roads.widht=3")}),
      "--set features.roads.widht=3: features.roads.widht: unknown key (did you mean 'width'?)");
  EXPECT_EQ(error_of(kMinimal, {parse_override("colour.shade=3")}),
            "--set colour.shade=3: colour: unknown key");
  EXPECT_EQ(error_of(kMinimal, {parse_override("features.roads.width=-2")}),
            "--set features.roads.width=-2: features.roads.width: must be > 0, got -2");
  EXPECT_THAT(error_of(kMinimal, {parse_override("existing.3.layer=x")}),
              HasSubstr("--set existing.3.layer=x"));
  EXPECT_THROW(parse_override("novalue"), Error);
  EXPECT_THROW(parse_override("=3"), Error);
}

TEST(PipelineConfig, LoadsAFileAndResolvesAgainstItsFolder) {
  test::TempDir dir;
  fs::create_directories(dir / "pipelines");
  std::ofstream(dir / "pipelines/p.yaml") << kMinimal;
  const PipelineConfig c = load_pipeline(dir / "pipelines/p.yaml");
  EXPECT_EQ(*c.heightfield, dir.path() / "samples/dem.tif");
  EXPECT_EQ(c.features[0].source, dir.path() / "pipelines/map.gpkg");
  try {
    load_pipeline(dir / "missing.yaml");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("missing.yaml: cannot read the pipeline file"));
  }
}

// Class names become file names (placements/<class>_<fid>.json): `../../x` would write
// outside --out (issue #9 item 8).
TEST(PipelineConfig, ClassNamesAreSafeIdentifiers) {
  const std::string good =
      std::string(kMinimal) + "  Big_roads-2: { source: m.gpkg, kind: road, width: 8 }\n";
  EXPECT_EQ(parse(good).features.back().name, "Big_roads-2");
  for (const char* name : {"../../x", "a/b", "2roads", "-x", "\"r d\"", "\"\""}) {
    SCOPED_TRACE(name);
    EXPECT_THAT(error_of(std::string(kMinimal) + "  " + name +
                         ": { source: m.gpkg, kind: road, width: 8 }\n"),
                HasSubstr("a class name must start with a letter or '_' and hold only letters, "
                          "digits, '_' and '-'"));
  }
  EXPECT_THAT(
      error_of(kMinimal, {{"features", "{\"../x\": {source: m.gpkg, kind: road, width: 3}}"}}),
      HasSubstr("features.../x: a class name must"));
}

// Network paths are refused naming the key, before any input is opened (issue #9 item 8).
TEST(PipelineConfig, NetworkInputsAreRefusedNamingTheKey) {
  const auto refusal = [](const std::vector<Override>& overrides, bool allow = false) {
    try {
      check_input_paths(parse(kMinimal, overrides), allow);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(refusal({}), "");
  EXPECT_EQ(refusal({{"heightfield", "/vsicurl?url=http%3A%2F%2Fexample.com%2Fdem.tif"}}),
            "--set heightfield=/vsicurl?url=http%3A%2F%2Fexample.com%2Fdem.tif: heightfield: "
            "'/vsicurl?url=http%3A%2F%2Fexample.com%2Fdem.tif' reaches the network "
            "(/vsicurl); terraweave reads local files unless run with --allow-network");
  // Kept as written (the nested "//" intact) for GDAL when allowed.
  EXPECT_EQ(parse(kMinimal, {{"heightfield", "/vsizip//vsicurl/https://example.com/d.zip/d.tif"}})
                .heightfield->string(),
            "/vsizip//vsicurl/https://example.com/d.zip/d.tif");
  EXPECT_THAT(refusal({{"features.roads.source", "https://example.com/roads.gpkg"}}),
              HasSubstr("features.roads.source: 'https://example.com/roads.gpkg' reaches the "
                        "network (https:)"));
  EXPECT_THAT(refusal({{"existing", "[{source: /vsis3/bucket/houses.gpkg}]"}}),
              HasSubstr("existing.0.source: '/vsis3/bucket/houses.gpkg' reaches the network"));
  EXPECT_THAT(refusal({{"features.roads.synthesis", "{exemplar: /vsigs/b/cobble.png}"}}),
              HasSubstr("features.roads.synthesis.exemplar: '/vsigs/b/cobble.png'"));
  const std::string generated =
      "version: 1\ngenerate: { crs: \"http://example.com/crs\" }\n"
      "features:\n  roads: { source: m.gpkg, kind: road, width: 8 }\n";
  try {
    check_input_paths(parse(generated), false);
    ADD_FAILURE() << "a URL CRS passed";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("generate.crs: 'http://example.com/crs' reaches the network"));
  }
  EXPECT_EQ(refusal({{"heightfield", "/vsicurl/https://example.com/dem.tif"}}, true), "");
}

TEST(PipelineConfig, ShippedPipelinesParse) {
  int parsed = 0;
  for (const auto& entry : fs::directory_iterator(test::source_dir() / "pipelines")) {
    if (entry.path().extension() != ".yaml") continue;
    const fs::path& file = entry.path();
    SCOPED_TRACE(file.string());
    ++parsed;
    const PipelineConfig c = load_pipeline(file);
    EXPECT_FALSE(c.features.empty());
  }
  EXPECT_GE(parsed, 4);  // demo, demo_closeup, generated, luxembourg
}

TEST(PipelineConfig, RepairDefaultsTopLevelAndPerClassKeys) {
  const PipelineConfig defaults = parse(kMinimal);
  EXPECT_DOUBLE_EQ(defaults.features[0].repair.min_loop, LineRepair{}.min_loop);
  EXPECT_DOUBLE_EQ(defaults.features[0].repair.merge_distance, LineRepair{}.merge_distance);
  EXPECT_DOUBLE_EQ(defaults.features[0].repair.spike_angle, LineRepair{}.spike_angle);
  // The class's own keys override the pipeline's one by one.
  const PipelineConfig c = parse(R"(version: 1
heightfield: dem.tif
repair: { min_loop: 5, spike_angle: 160 }
features:
  roads: { source: map.gpkg, kind: road, width: 8 }
  rivers: { source: map.gpkg, kind: river, width: 8, repair: { min_loop: 40 } }
)");
  EXPECT_DOUBLE_EQ(c.repair.min_loop, 5.0);
  EXPECT_DOUBLE_EQ(c.features[0].repair.min_loop, 5.0);
  EXPECT_DOUBLE_EQ(c.features[0].repair.spike_angle, 160.0);
  EXPECT_DOUBLE_EQ(c.features[1].repair.min_loop, 40.0);
  EXPECT_DOUBLE_EQ(c.features[1].repair.spike_angle, 160.0);
  EXPECT_DOUBLE_EQ(c.features[1].repair.merge_distance, LineRepair{}.merge_distance);
  EXPECT_DOUBLE_EQ(
      parse(kMinimal, {{"features.roads.repair.min_loop", "0.5"}}).features[0].repair.min_loop,
      0.5);
  EXPECT_THAT(error_of(std::string(kMinimal) + "repair: { spike_angle: 180 }\n"),
              HasSubstr("p.yaml:6:24: repair.spike_angle: must be below 180 degrees"));
  EXPECT_THAT(error_of(std::string(kMinimal) + "repair: { min_loop: -1 }\n"),
              HasSubstr("repair.min_loop"));
  EXPECT_THAT(error_of(std::string(kMinimal) + "repair: { min_lop: 1 }\n"),
              HasSubstr("did you mean 'min_loop'"));
}

// Every file a run opens is listed with the key (and line) that names it.
TEST(PipelineConfig, InputsNameTheirKeys) {
  const PipelineConfig c = parse(R"(version: 1
heightfield: dem.tif
features:
  roads:
    source: map.gpkg
    kind: road
    width: 8
    synthesis: { exemplar: [a.png, b.png] }
existing:
  - { source: areas.gpkg }
)");
  ASSERT_EQ(c.inputs.size(), 5u);
  EXPECT_EQ(c.inputs[0].path, fs::path("/base/dir/dem.tif"));
  EXPECT_EQ(c.inputs[0].kind, InputFile::Kind::raster);
  EXPECT_EQ(c.inputs[0].named_at, "p.yaml:2:14: heightfield");
  EXPECT_EQ(c.inputs[1].named_at, "p.yaml:5:13: features.roads.source");
  EXPECT_EQ(c.inputs[1].kind, InputFile::Kind::vector);
  EXPECT_EQ(c.inputs[3].path, fs::path("/base/dir/b.png"));
  EXPECT_EQ(c.inputs[3].kind, InputFile::Kind::method);
  EXPECT_EQ(c.inputs[3].role, "exemplar");
  ASSERT_EQ(c.inputs[3].companions.size(), 1u);
  EXPECT_EQ(c.inputs[3].companions[0].path, fs::path("/base/dir/b_height.tif"));
  EXPECT_EQ(c.inputs[3].named_at, "p.yaml:8:36: features.roads.synthesis.exemplar.1");
  EXPECT_EQ(c.inputs[4].named_at, "p.yaml:10:15: existing.0.source");
}

}  // namespace
}  // namespace tw

namespace tw {
namespace {

using ::testing::Not;

constexpr const char* kLinesAndArea = R"(version: 1
heightfield: ../samples/dem.tif
features:
  rivers: { source: map.gpkg, layer: rivers, kind: river, width: 8, conform: { corridor: 300 } }
  roads: { source: map.gpkg, layer: roads, kind: road, width: 8 }
  vines: { kind: area, source: map.gpkg, layer: fields, sketch: vineyard.geojson }
precedence: [rivers, roads]
)";

TEST(PipelineConfig, AnAreaClassInPrecedenceSaysWhyAndWhatToDo) {
  const std::string error = error_of(kLinesAndArea, {{"precedence", "[rivers, vines, roads]"}});
  EXPECT_THAT(error, HasSubstr("--set precedence=[rivers, vines, roads]: precedence.1"));
  EXPECT_THAT(error, HasSubstr("'vines' is an area class (kind: area)"));
  EXPECT_THAT(error, HasSubstr("remove it from precedence"));
  EXPECT_THAT(error, Not(HasSubstr("is not a feature class")));
}

// The methods read their blocks through the seam (detail/method_config.hpp), a network block
// before a grown class's: a hedge class with `network:` is a network class and needs no grow:
// block, and it starts from the hedge's width and profile (the grown kinds' defaults).
TEST(PipelineConfig, TheMethodsReadTheirBlocksANetworkBeforeAGrownKind) {
  const PipelineConfig c = parse(std::string(kMinimal) + R"(  hedges:
    kind: hedge
    network: { exemplar: drawn.svg, region: [0, 0, 100, 100] }
    synthesis: { exemplar: hedge.png, choose: mix, bind: [{exemplar: 0, near_junction: 2}] }
synthesis_order: [hedges]
synthesis_resolution: 0.5
)");
  ASSERT_EQ(c.features.size(), 2u);
  const FeatureClassConfig& hedges = c.features[1];
  ASSERT_TRUE(has_method_options(hedges, kNetworkMethodName));
  EXPECT_FALSE(has_method_options(hedges, kGrownMethodName));
  EXPECT_TRUE(hedges.source.empty());
  EXPECT_EQ(hedges.kind, FeatureKind::ridge);
  EXPECT_EQ(hedges.width, 2.0);
  EXPECT_EQ(hedges.ridge.height, 1.5);
  ASSERT_TRUE(has_method_options(hedges, kPatternsMethodName));
  EXPECT_EQ(method_options<SynthesisConfig>(hedges, kPatternsMethodName)->bind.size(), 1u);
  EXPECT_EQ(synthesis_order(c), std::vector<std::string>{"hedges"});
  EXPECT_EQ(c.synthesis_resolution, 0.5);
  // Without the block, the hedge kind is the grown method's, which asks for its grow: block.
  EXPECT_THAT(error_of(std::string(kMinimal) + "  hedges: { kind: hedge }\n"),
              HasSubstr("features.hedges.kind: a hedge class grows its lines: give a grow: block"));
  // A bind rule by attributes on the network's lines is refused with the network's reason.
  EXPECT_THAT(error_of(std::string(kMinimal) + R"(  hedges:
    kind: hedge
    network: { exemplar: drawn.svg, region: [0, 0, 100, 100] }
    synthesis: { exemplar: hedge.png, choose: mix, bind: [{exemplar: 0, where: "a = 1"}] }
)"),
              HasSubstr("features.hedges.synthesis.bind.0: a network class's lines are grown and "
                        "have no attributes for where or tags to select; bind them by "
                        "near_junction"));
}

TEST(PipelineConfig, NullOverrideRemovesAKeyOrDropsAClass) {
  const PipelineConfig all = parse(kLinesAndArea);
  ASSERT_EQ(all.features.size(), 2u);
  EXPECT_EQ(all.features[0].conform_corridor, 300.0);

  // A dropped class leaves precedence with it, so one flag is enough.
  const PipelineConfig no_roads = parse(kLinesAndArea, {{"features.roads", "null"}});
  ASSERT_EQ(no_roads.features.size(), 1u);
  EXPECT_EQ(no_roads.features[0].name, "rivers");
  EXPECT_EQ(detail::area_classes(no_roads).size(), 1u);
  const PipelineConfig no_vines = parse(kLinesAndArea, {{"features.vines", "~"}});
  EXPECT_EQ(no_vines.features.size(), 2u);
  EXPECT_TRUE(detail::area_classes(no_vines).empty());

  // A nested key goes back to its default.
  const PipelineConfig drawn = parse(kLinesAndArea, {{"features.rivers.conform", "null"}});
  EXPECT_EQ(drawn.features[0].conform_corridor, 0.0);

  EXPECT_THAT(error_of(kLinesAndArea, {{"features.lakes", "null"}}),
              HasSubstr("--set features.lakes=null: there is no 'features.lakes' to remove"));
}

// The manifest names no method: an input is listed under the role its method's reader gave it
// (the patterns' exemplar, grown's element set, or any method's own), then those of its
// companions that exist (an exemplar's NAME_height.tif twin, here a's but not b's).
TEST(PipelineConfig, AMethodsInputRolesAndCompanionsReachTheManifest) {
  const test::TempDir dir;
  for (const char* name : {"a.png", "a_height.tif", "b.png", "hedge.json", "c.dat", "c.idx"})
    std::ofstream(dir / name) << name;
  PipelineConfig c = parse_pipeline(R"(version: 1
heightfield: dem.tif
features:
  roads:
    source: map.gpkg
    kind: road
    width: 8
    synthesis: { exemplar: [a.png, b.png] }
  hedges: { kind: hedge, grow: { element: hedge.json, region: [0, 0, 100, 100] } }
)",
                                    "p.yaml", dir.path(), {});
  c.inputs.push_back({dir / "c.dat",
                      InputFile::Kind::method,
                      "p.yaml:9:1: stamps",
                      "stamp_set",
                      {{dir / "c.idx", "stamp_index"}, {dir / "c_missing.idx", "stamp_index"}}});
  std::vector<std::string> roles, names;
  std::vector<std::uintmax_t> bytes;
  for (const FileRecord& r : detail::record_inputs(c.inputs)) {
    roles.push_back(r.role);
    names.push_back(fs::path(r.path).filename().string());
    bytes.push_back(r.bytes);
  }
  EXPECT_EQ(roles,
            (std::vector<std::string>{"heightfield", "vector", "exemplar", "exemplar_height",
                                      "exemplar", "element_set", "stamp_set", "stamp_index"}));
  EXPECT_EQ(names, (std::vector<std::string>{"dem.tif", "map.gpkg", "a.png", "a_height.tif",
                                             "b.png", "hedge.json", "c.dat", "c.idx"}));
  // Files that exist are hashed (a missing heightfield and source are listed without).
  EXPECT_EQ(bytes, (std::vector<std::uintmax_t>{0, 0, 5, 12, 5, 10, 5, 5}));
}

}  // namespace
}  // namespace tw
