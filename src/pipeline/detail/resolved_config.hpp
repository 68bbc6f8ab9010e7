#pragma once
// The pipeline tree as JSON for the manifest: scalars that read as integers, numbers or
// booleans become those, the rest strings, so two reports diff value by value.
#include <yaml-cpp/yaml.h>
#include <nlohmann/json.hpp>

namespace tw::detail {

nlohmann::json yaml_to_json(const YAML::Node& node);

}  // namespace tw::detail
