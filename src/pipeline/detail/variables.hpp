#pragma once
// `${name}` in the values of a pipeline file, replaced from a variables file (--vars).
#include <yaml-cpp/yaml.h>

#include <string>

#include "pipeline/config.hpp"

namespace tw::detail {

// Replaces every `${name}` in every scalar under `root` (keys are left alone). An unknown name
// fails at the value, "file:line:col: key.path: ${name}: ...", naming the variables file and
// the names it defines.
void substitute_variables(YAML::Node root, const Variables& variables,
                          const std::string& file_label);

}  // namespace tw::detail
