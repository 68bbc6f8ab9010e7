#pragma once
// `kind: area` feature classes (docs/shape-patterns.md, docs/pipeline.md): polygons filled with
// a structured shape-pattern synthesized from a sketch, rasterized into splat materials and
// height detail, and written as vectors and engine instances.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pipeline/lead.hpp"

namespace tw {

// One stroke material of the sketch and what it becomes.
struct AreaMaterial {
  std::string stroke;   // the sketch's `material`
  std::string splat;    // splat material of the output ("" = <class>_<stroke>)
  double height = 0.0;  // metres added where the stroke covers a pixel (+ ridge, - furrow)
};

struct AreaClassConfig {
  std::string name;
  std::filesystem::path source;
  std::string layer;
  std::string where;  // OGR SQL attribute filter
  std::filesystem::path sketch;
  std::optional<std::filesystem::path> shapes_from;  // hybridization (Section 6)
  double scale = 20.0;                               // metres per sketch unit
  Lead lead = Lead::long_axis;  // where the sketch's +x axis points in each polygon
  double bearing_deg = 0.0;     // lead: bearing
  double jitter = 0.5;
  std::uint64_t seed = 0;
  // Stroke materials named in `materials` or `height`, in the order given; the others map to
  // splat.<class>_<material> with no height.
  std::vector<AreaMaterial> materials;
};

}  // namespace tw
