#pragma once
// Reading a class's `tags` key (docs/osm.md): line, existing and `kind: area` classes.
#include <vector>

#include "pipeline/detail/yaml_reader.hpp"
#include "pipeline/config.hpp"

namespace tw::detail {

// tags: { key: [value, ...] } (a single value may stand alone). Throws tw::Error naming the
// file, line and key of the first bad entry.
std::vector<TagSelection> read_tags(const MapReader& m);

}  // namespace tw::detail
