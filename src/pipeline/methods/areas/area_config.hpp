#pragma once
// Reading a `kind: area` class of a pipeline file (pipeline/area_config.hpp).
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/area_config.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw::detail {

// A reader of the class's mapping with the keys a `kind: area` class takes.
MapReader area_class_reader(const YamlSource& src, const YAML::Node& node, const std::string& path);

// True when the class node says `kind: area` (a string; anything else is left to the line
// classes' reader and its messages).
bool is_area_class(const YAML::Node& node);

// The areas method's name (SynthesisMethod::name()), under which the config keeps its options.
inline constexpr const char* kAreasMethodName = "areas";

// The areas' options in the config (PipelineConfig::methods): their `kind: area` classes, in
// file order, synthesized after the line classes' patterns, each avoiding the areas before it.
struct AreaOptions : MethodOptionsOf<AreaOptions> {
  std::vector<AreaClassConfig> classes;
};

// The config's area classes (none when it has none).
const std::vector<AreaClassConfig>& area_classes(const PipelineConfig& config);

// Throws tw::Error naming the file, line and key of the first bad value; files go to `inputs`.
AreaClassConfig read_area_class(const MapReader& m, const std::string& name,
                                std::uint64_t default_seed, std::vector<InputFile>& inputs);

}  // namespace tw::detail
