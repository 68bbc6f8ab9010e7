#pragma once
// Reading the patterns' keys of a pipeline file (docs/patterns.md, docs/pipeline.md): a line
// class's `synthesis:` block, and `synthesis_resolution` and `synthesis_order` at the top level.
#include <filesystem>

#include "pipeline/detail/method_config.hpp"

namespace tw::detail {

// What the patterns' inputs are (InputFile::role, report.json's `inputs[].role`): an exemplar
// image, and its height twin, a companion read as channel "height" where it exists.
inline constexpr const char* kExemplarRole = "exemplar";
inline constexpr const char* kExemplarHeightRole = "exemplar_height";

// An exemplar's height twin: NAME_height.tif beside NAME.png.
std::filesystem::path exemplar_height_path(const std::filesystem::path& exemplar);

// A line class's `synthesis:` block, if there (MethodReader::read_class). Throws tw::Error
// naming the file, line and key of the first bad value; the exemplars go to `inputs` (role
// kExemplarRole, with their height twins as companions).
void read_pattern_class(ClassReading& r);

// `synthesis_resolution`, and `synthesis_order`: each class with synthesis exactly once
// (default: precedence order). MethodReader::read_root.
void read_pattern_root(RootReading& r);

}  // namespace tw::detail
