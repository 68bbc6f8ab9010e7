#pragma once
// Values of a pipeline file that the config's reader (config.cpp) and the synthesis methods'
// readers (detail/method_config.hpp) read alike.
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/yaml_reader.hpp"
#include "pipeline/lead.hpp"

namespace tw::detail {

// m.file(key), recorded as an input of `kind` (named where the key stands).
std::filesystem::path input_file(const MapReader& m, const std::string& key, InputFile::Kind kind,
                                 std::vector<InputFile>& inputs);

// A width in metres: positive and at most the key table's maximum (kMaxFeatureWidth,
// geo/features.hpp).
double read_width(const MapReader& m, const std::string& key);

// cpu | opencl | auto; `fallback` is "auto" or an already validated backend.
std::string read_backend(const MapReader& m, const std::string& key, const std::string& fallback);

// `lead: long_axis | nearest_road | contours | { bearing: DEG }` (pipeline/lead.hpp), when given:
// `lead` and, for a bearing, `bearing_deg` (finite compass degrees). Unknown names are refused
// naming the key, with the closest name.
void read_lead(const MapReader& m, Lead& lead, double& bearing_deg);

}  // namespace tw::detail
