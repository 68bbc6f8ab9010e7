// The JSON Schema of pipeline files (issue #22 item 6): written from the reader's key table, the
// shipped docs/pipeline.schema.json equals it, every pipeline of pipelines/ validates against it
// (valijson, a real draft-07 validator), and what the reader refuses the schema refuses too: an
// unknown key in every block of the table, a value of the wrong type for every key, every range
// bound crossed, every required key removed.
#include "pipeline/schema.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

#include "core/error.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/pipeline_keys.hpp"
#include "pipeline/detail/resolved_config.hpp"
#include "pipeline/detail/yaml_reader.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

namespace fs = std::filesystem;
using detail::ValueType;
using namespace tw::test;

// A pipeline that reaches every block of the key table (parsing opens no input file).
const char* const kEveryBlock = R"(version: 1
seed: 3
generate: { width: 64, height: 64, pixel_size: 4, relief: 10, crs: "EPSG:32631", origin: [500000, 5000000] }
output: { dir: out, tiles: { size: 32, overlap: 2 }, compress: deflate }
avoidance: { max_distance: 100 }
repair: { merge_distance: 0.1 }
export: { unreal: { size: 127 }, godot: { height: r16 } }
features:
  roads:
    source: lines.geojson
    kind: road
    width: 6
    profile: { max_grade: 0.1 }
    repair: { min_loop: 1 }
    synthesis:
      exemplar: [a.png, b.png]
      choose: mix
      bind: [{ exemplar: 1, where: "lanes = 2", near_junction: 5 }]
  rivers: { source: lines.geojson, kind: river, width: 4, profile: { depth: 1 }, conform: { corridor: 20 } }
  ridges: { source: lines.geojson, kind: ridge, width: 4, profile: { height: 2 } }
  hedges: { kind: hedge, grow: { element: hedge.json, region: { source: fields.geojson } } }
  lanes: { kind: trail, width: 3, network: { exemplar: lanes.gpkg, region: [0, 0, 200, 200] } }
  vines: { kind: area, source: fields.geojson, sketch: rows.geojson, lead: { bearing: 30 } }
existing:
  - { source: lines.geojson, width: 3 }
)";

// Where each block of the table lies in kEveryBlock.
const std::map<std::string, std::string>& block_paths() {
  static const std::map<std::string, std::string> paths{
      {"root", ""},
      {"generate", "generate"},
      {"output", "output"},
      {"tiles", "output.tiles"},
      {"avoidance", "avoidance"},
      {"repair", "repair"},
      {"export_engines", "export"},
      {"export_options", "export.unreal"},
      {"line_class", "features.roads"},
      {"road_profile", "features.roads.profile"},
      {"river_profile", "features.rivers.profile"},
      {"ridge_profile", "features.ridges.profile"},
      {"conform", "features.rivers.conform"},
      {"synthesis", "features.roads.synthesis"},
      {"binding", "features.roads.synthesis.bind.0"},
      {"grow", "features.hedges.grow"},
      {"grow_region", "features.hedges.grow.region"},
      {"network", "features.lanes.network"},
      {"area_class", "features.vines"},
      {"lead", "features.vines.lead"},
      {"existing", "existing.0"},
  };
  return paths;
}

class PipelineSchema : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    schema_json_ = new nlohmann::json(nlohmann::json::parse(pipeline_schema_json()));
    schema_ = new valijson::Schema;
    valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
    parser.populateSchema(valijson::adapters::NlohmannJsonAdapter(*schema_json_), *schema_);
  }
  static void TearDownTestSuite() {
    delete schema_;
    delete schema_json_;
  }

  // "" when `doc` is valid, else the validator's first complaints.
  static std::string schema_errors(const nlohmann::json& doc) {
    valijson::Validator validator;
    valijson::ValidationResults results;
    if (validator.validate(*schema_, valijson::adapters::NlohmannJsonAdapter(doc), &results))
      return "";
    std::string out;
    valijson::ValidationResults::Error error;
    for (int i = 0; i < 3 && results.popError(error); ++i) {
      std::string where;
      for (const std::string& part : error.context) where += part;
      out += where + ": " + error.description + "; ";
    }
    return out.empty() ? "invalid" : out;
  }

  // The tree the reader reads (kEveryBlock with `overrides` applied), as JSON.
  static nlohmann::json tree_of(const std::string& text, const std::vector<Override>& overrides) {
    const detail::YamlSource src("p.yaml", "/base", overrides);
    return detail::yaml_to_json(src.load(text));
  }

  // The reader's error for `text` with `overrides` ("" when it reads it).
  static std::string reader_error(const std::string& text, const std::vector<Override>& overrides) {
    try {
      parse_pipeline(text, "p.yaml", "/base", overrides);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }

  // Both the reader and the schema refuse kEveryBlock with `o`; the reader names `key_path`.
  static void expect_both_refuse(const Override& o, const std::string& key_path) {
    SCOPED_TRACE("--set " + o.key_path + "=" + o.value);
    const std::string reader = reader_error(kEveryBlock, {o});
    EXPECT_NE(reader, "") << "the reader accepts it";
    EXPECT_NE(reader.find(key_path), std::string::npos) << reader;
    EXPECT_NE(schema_errors(tree_of(kEveryBlock, {o})), "") << "the schema accepts it";
  }

  static inline nlohmann::json* schema_json_ = nullptr;
  static inline valijson::Schema* schema_ = nullptr;
};

std::string key_path(const std::string& block, std::string_view key) {
  const std::string& prefix = block_paths().at(block);
  return prefix.empty() ? std::string(key) : prefix + "." + std::string(key);
}

TEST_F(PipelineSchema, ShippedFileIsTheGeneratorsOutput) {
  // Regenerate with: build/src/terraweave schema > docs/pipeline.schema.json
  EXPECT_EQ(read_file(source_dir() / "docs/pipeline.schema.json"), pipeline_schema_json());
  const CommandResult printed = run_command(terraweave_binary().string() + " schema");
  EXPECT_EQ(printed.exit_code, 0);
  EXPECT_EQ(printed.output, pipeline_schema_json());
}

TEST_F(PipelineSchema, EveryShippedPipelineValidatesAndNamesTheSchema) {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(source_dir() / "pipelines")) {
    if (entry.path().extension() != ".yaml") continue;
    ++files;
    SCOPED_TRACE(entry.path().string());
    const std::string text = read_file(entry.path());
    EXPECT_EQ(lines_of(text).at(0), "# yaml-language-server: $schema=../docs/pipeline.schema.json");
    EXPECT_EQ(schema_errors(tree_of(text, {})), "");
    EXPECT_NO_THROW(parse_pipeline(text, entry.path().string(), entry.path().parent_path()));
  }
  EXPECT_EQ(files, 9);  // pipelines/*.yaml: a new one is counted here
}

TEST_F(PipelineSchema, EveryBlockIsReachedAndValid) {
  EXPECT_EQ(reader_error(kEveryBlock, {}), "");
  EXPECT_EQ(schema_errors(tree_of(kEveryBlock, {})), "");
  // Each block of the table has a place in kEveryBlock, so the tests below walk all of them.
  for (const detail::KeyBlock& block : detail::pipeline_blocks())
    EXPECT_EQ(block_paths().count(std::string(block.name)), 1u) << block.name;
  EXPECT_EQ(block_paths().size(), detail::pipeline_blocks().size());
}

TEST_F(PipelineSchema, AnUnknownKeyIsRefusedInEveryBlock) {
  for (const auto& [block, path] : block_paths()) {
    const std::string key = key_path(block, "colour");
    expect_both_refuse({key, "1"}, key);
  }
}

TEST_F(PipelineSchema, AValueOfTheWrongTypeIsRefusedForEveryKey) {
  // A nested list is no form of any key: both must refuse it, naming the key.
  for (const detail::KeyBlock& block : detail::pipeline_blocks()) {
    for (const detail::KeySpec& spec : block.keys) {
      const std::string key = key_path(std::string(block.name), spec.name);
      // `kind: [[1]]` makes the area class a line class, refused at its first area key.
      const std::string named = key == "features.vines.kind" ? "features.vines" : key;
      expect_both_refuse({key, "[[1]]"}, named);
    }
  }
  // Words where numbers belong, numbers where words belong.
  expect_both_refuse({"features.roads.width", "wide"}, "features.roads.width");
  expect_both_refuse({"features.hedges.grow.trials", "2.5"}, "features.hedges.grow.trials");
  expect_both_refuse({"output.exr", "maybe"}, "output.exr");
  expect_both_refuse({"backend", "gpu"}, "backend");
  expect_both_refuse({"features.roads.synthesis.channels", "{A: colour}"},
                     "features.roads.synthesis.channels.A");
  expect_both_refuse({"features.9roads", "{source: a.gpkg, kind: road, width: 2}"},
                     "features.9roads");
}

TEST_F(PipelineSchema, EveryRangeBoundIsRefusedByBoth) {
  int bounds = 0;
  for (const detail::KeyBlock& block : detail::pipeline_blocks()) {
    for (const detail::KeySpec& spec : block.keys) {
      const std::string key = key_path(std::string(block.name), spec.name);
      for (const detail::ValueForm& form : spec.forms) {
        const bool number = form.type == ValueType::number || form.type == ValueType::integer;
        if (!number && form.type != ValueType::map_number) continue;
        const std::string at = form.type == ValueType::map_number ? key + ".stroke" : key;
        const double step = form.type == ValueType::integer ? 1.0 : 0.5;
        if (std::isfinite(form.minimum)) {
          ++bounds;
          const double below = form.exclusive_minimum ? form.minimum : form.minimum - step;
          expect_both_refuse({at, fmt::format("{}", below)}, at);
        }
        if (std::isfinite(form.maximum)) {
          ++bounds;
          const double above = form.exclusive_maximum ? form.maximum : form.maximum + step;
          expect_both_refuse({at, fmt::format("{}", above)}, at);
        }
      }
    }
  }
  EXPECT_GE(bounds, 60);
}

TEST_F(PipelineSchema, AWordIsRefusedWhereNoTextIsTaken) {
  int keys = 0;
  for (const detail::KeyBlock& block : detail::pipeline_blocks()) {
    for (const detail::KeySpec& spec : block.keys) {
      const bool takes_text = std::any_of(spec.forms.begin(), spec.forms.end(), [](const auto& f) {
        return f.type == ValueType::string || f.type == ValueType::path;
      });
      if (takes_text) continue;
      ++keys;
      const std::string key = key_path(std::string(block.name), spec.name);
      const std::string named = key == "features.vines.kind" ? "features.vines" : key;
      expect_both_refuse({key, "zz"}, named);
    }
  }
  EXPECT_GE(keys, 80);
}

// The other direction: a value on (or just inside) each bound is read by both, so neither is
// stricter than the table.
TEST_F(PipelineSchema, EveryRangeBoundIsAcceptedByBoth) {
  for (const detail::KeyBlock& block : detail::pipeline_blocks()) {
    for (const detail::KeySpec& spec : block.keys) {
      const std::string key = key_path(std::string(block.name), spec.name);
      if (key == "export.unreal.size") continue;  // also one of the engine's sizes
      for (const detail::ValueForm& form : spec.forms) {
        const bool number = form.type == ValueType::number || form.type == ValueType::integer;
        if (!number && form.type != ValueType::map_number) continue;
        const std::string at = form.type == ValueType::map_number ? key + ".stroke" : key;
        const double step = form.type == ValueType::integer ? 1.0 : 0.5;
        std::vector<double> values;
        if (std::isfinite(form.minimum))
          values.push_back(form.exclusive_minimum ? form.minimum + step : form.minimum);
        if (std::isfinite(form.maximum))
          values.push_back(form.exclusive_maximum ? form.maximum - step : form.maximum);
        for (const double v : values) {
          const Override o{at, fmt::format("{}", v)};
          SCOPED_TRACE("--set " + o.key_path + "=" + o.value);
          EXPECT_EQ(reader_error(kEveryBlock, {o}), "");
          EXPECT_EQ(schema_errors(tree_of(kEveryBlock, {o})), "");
        }
      }
    }
  }
}

TEST_F(PipelineSchema, EveryRequiredKeyIsRequiredByBoth) {
  int required = 0;
  for (const detail::KeyBlock& block : detail::pipeline_blocks()) {
    for (const detail::KeySpec& spec : block.keys) {
      if (!spec.required) continue;
      ++required;
      const std::string key = key_path(std::string(block.name), spec.name);
      // Without `kind: area` the class is read as a line class, refused at its `sketch`.
      const std::string named = key == "features.vines.kind" ? "features.vines" : key;
      expect_both_refuse({key, "null"}, named);
    }
  }
  EXPECT_GE(required, 10);
}

}  // namespace
}  // namespace tw
