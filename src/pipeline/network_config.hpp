#pragma once
// A line class grown as a curve network by example (docs/networks.md, "In pipelines"): the
// class's `network:` block, the same knobs as `terraweave network synthesize|complete`.
#include <array>
#include <cstdint>
#include <optional>
#include <string>

#include "pipeline/lead.hpp"
#include "pipeline/method_options.hpp"

namespace tw {

// The network method's name (SynthesisMethod::name()): a line class's `network:` block is its
// options, method_options<NetworkClassConfig>(feature_class, kNetworkMethodName).
inline constexpr const char* kNetworkMethodName = "network";

struct NetworkClassConfig : MethodOptionsOf<NetworkClassConfig> {
  std::string exemplar;         // "path[:layer]" of any OGR source, or an .svg file
  std::string exemplar_where;   // OGR SQL filter on the exemplar's layer
  std::string exemplar_region;  // polygons "path[:layer]" cutting the exemplar (a real map)
  double scale = 1.0;           // SVG: metres per unit
  // `region`: [minx, miny, maxx, maxy] in the heightfield's CRS, or polygons {source, layer,
  // where}; required.
  std::optional<std::array<double, 4>> region_box;
  std::string region_source, region_layer, region_where;
  std::string partial;     // the user's lines "path[:layer]" (heightfield's CRS), completed
  std::uint64_t seed = 1;  // default: the run's seed
  // The direction the exemplar's main bearing is turned to over the region (absent: as drawn);
  // `lead_bearing: DEG` is `lead: { bearing: DEG }`.
  std::optional<Lead> lead;
  double lead_bearing_deg = 0.0;  // lead: bearing, compass degrees
  double clearance = 0.0;         // metres; 0: the exemplar's own (6 % of its median edge)
  double snap = 0.0;              // metres; 0: 35 % of the median edge
  int candidates = 12;
  // automatic, growth, quilt or layout (docs/networks.md, "Which method"); quilt and layout are
  // refused with `partial` (completing a drawing is growth).
  std::string method = "automatic";
  // Off the existing features and the lines of the classes before it (and their widths).
  bool avoid = true;
};

}  // namespace tw
