#pragma once
// Reading a line class's `network:` block (pipeline/network_config.hpp, docs/networks.md "In
// pipelines").
#include <cstdint>
#include <vector>

#include "pipeline/config.hpp"
#include "pipeline/detail/method_config.hpp"
#include "pipeline/detail/yaml_reader.hpp"

namespace tw::detail {

// The `network:` block `m`. Throws tw::Error naming the file, line and key of the first bad
// value; the exemplar, region and partial files go to `inputs`.
NetworkClassConfig read_network(const MapReader& m, std::uint64_t default_seed,
                                std::vector<InputFile>& inputs);

// A line class's `network:` block, if there (MethodReader::read_lines): the class's lines are
// grown, so it reads no features (no tags, widths or grow: block) and needs a kind.
void read_network_lines(ClassReading& r);

}  // namespace tw::detail
