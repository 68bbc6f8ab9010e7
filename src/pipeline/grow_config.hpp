#pragma once
// FloralSurf growth (docs/ornaments.md) as `terraweave grow` and a pipeline class's `grow:`
// block take it (docs/pipeline.md): the same knobs under the same names, read into one struct.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "pipeline/method_options.hpp"

namespace tw {

// What `terraweave grow`'s options and a `grow:` block share.
struct GrowSettings {
  double resolution = 0.0;  // metres between mesh vertices; 0 = the heightfield's
  std::uint64_t seed = 1;
  bool contour = false;    // `alignment: contour`: elements follow the contour direction
  bool first_fit = false;  // the greedy variant (the paper's Figure 6), for comparison
  int trials = 10;         // candidates per growth point
  int max_ornaments = 32;
  int max_elements = 20000;
  double coverage_radius = 0.0;     // metres, for the report; 0 = half the element set's scale
  std::optional<double> clearance;  // metres between unrelated lines; absent: the set's own
};

// The grown ornaments method's name (SynthesisMethod::name()): a line class's `grow:` block is
// its options, method_options<GrowConfig>(feature_class, kGrownMethodName).
inline constexpr const char* kGrownMethodName = "grown";

// A class's `grow:` block.
struct GrowConfig : MethodOptionsOf<GrowConfig> {
  // The class's `kind` as written: hedge, wall, trail, ditch (grown kinds: a ridge, ridge,
  // road and river profile) or road, river, ridge with a grow: block.
  std::string kind = "hedge";
  std::filesystem::path element;  // element set JSON (samples/ornaments/*.json)
  // `region`: [minx, miny, maxx, maxy] in the heightfield's CRS, or polygons {source, layer,
  // where}; absent: the class's own source, layer and where, read as polygons.
  std::optional<std::array<double, 4>> region_box;
  std::filesystem::path region_source;
  std::string region_layer, region_where;
  GrowSettings settings;
};

}  // namespace tw
