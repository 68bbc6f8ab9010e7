#pragma once
// Reading a grown line class of a pipeline file (pipeline/grow_config.hpp): `kind: hedge | wall |
// trail | ditch`, or any line kind with a `grow:` block.
#include <cstdint>
#include <string>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw::detail {

// What a grown class's element set is (InputFile::role, report.json's `inputs[].role`).
inline constexpr const char* kElementSetRole = "element_set";

// The line kinds whose features are grown, and the terrain kind of each: hedge and wall are
// raised (ridge), a ditch is carved (river), a trail is graded (road).
bool is_grown_kind(const std::string& kind);
FeatureKind terrain_kind_of(const std::string& grown_kind);

// The width and profile a grown kind starts from (docs/pipeline.md, "Grown classes"); the
// class's `width` and `profile` keys override them.
void apply_grown_defaults(const std::string& grown_kind, FeatureClassConfig& f);

// The `grow:` block `m` of a class of kind `kind`. Throws tw::Error naming the file, line and
// key of the first bad value; the element set (role kElementSetRole) and a region source go to
// `inputs`.
GrowConfig read_grow(const MapReader& m, const std::string& kind, std::uint64_t default_seed,
                     std::vector<InputFile>& inputs);

// A line class's `grow:` block, if there (MethodReader::read_lines), after a network block: a
// class of a grown kind needs one unless another method makes its lines.
void read_grown_lines(ClassReading& r);

}  // namespace tw::detail
