#pragma once
// A synthesis method's reading of its keys of a pipeline file (docs/methods.md, "Its keys"):
// config.cpp reads the file's own keys and hands each block a method owns to the method, so it
// names none of them. A line class's keys are read in the order below; the hooks stand where
// the methods' blocks were read before the seam, so a file with several problems fails on the
// same first one (tests/pipeline compare the messages).
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw::detail {

// A line class being read (config.cpp's read_feature_class), as the methods see it.
struct ClassReading {
  const MapReader& m;            // the class's mapping
  const std::string& kind_name;  // `kind` as written ("" when absent)
  std::uint64_t seed;            // the pipeline's, the default of every `seed`
  std::vector<InputFile>& inputs;
  FeatureClassConfig& f;
  // Set by the method that makes the class's lines (its block is there): the class reads no
  // features, unless reads_source (a grown class's region polygons); a synthesis `bind` rule
  // cannot select them by attributes (`lines_without_attributes` says why, in the message).
  bool lines_made = false;
  bool reads_source = false;
  std::string lines_without_attributes{};
};

// What the whole file's reading sees after its classes (config.cpp's read_pipeline).
struct RootReading {
  const MapReader& root;
  PipelineConfig& config;
};

// A method's hooks into the reading; null: none. Plain function pointers: the readers are free
// functions of the method's glue (methods/<name>/<name>_config.cpp).
struct MethodReader {
  // Line kinds it adds to `kind` (after road, river, ridge), the terrain kind each is built as,
  // and the width and profile each starts from when a method makes the class's lines.
  std::vector<std::string> kinds{};
  FeatureKind (*terrain_kind)(const std::string& kind) = nullptr;
  void (*kind_defaults)(const std::string& kind, FeatureClassConfig& f) = nullptr;
  // A line class, before its source: reads the block that makes the class's lines, if there,
  // and sets r.lines_made; checks what a class of its kinds needs.
  void (*read_lines)(ClassReading& r) = nullptr;
  // A line class, after the class's own keys (repair last): reads its block of the class.
  void (*read_class)(ClassReading& r) = nullptr;
  // A class of its own under `features` (the areas: `kind: area`): whether `node` is one, and
  // its reading into the config; precedence refuses naming one, saying what it is
  // (own_class_note: "an area class (kind: area): ...").
  bool (*takes_class)(const YAML::Node& node) = nullptr;
  void (*read_own_class)(const YamlSource& src, const YAML::Node& node, const std::string& path,
                         const std::string& name, PipelineConfig& config) = nullptr;
  std::string own_class_note{};
  // After the classes and `precedence`: its top-level keys (the patterns' synthesis_order).
  void (*read_root)(RootReading& r) = nullptr;
};

// The built-in methods' readers in reading order (synthesis_method.cpp, beside the methods'
// registration): network, grown, patterns, areas. A network block is read before a grown
// class's (a class with a network: block is a network class, whatever its kind).
const std::vector<MethodReader>& builtin_method_readers();

}  // namespace tw::detail
