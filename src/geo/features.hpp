#pragma once
// Vector features (OGR) brought into a heightfield's grid CRS and clipped to its extent.
#include <cstdint>
#include <string>
#include <vector>

#include "core/vec2.hpp"
#include "geo/heightfield.hpp"

namespace tw {

struct VectorSource {
  std::string path;
  std::string layer;  // empty = the first layer
  std::string where;  // OGR SQL attribute filter; empty = every feature
};

struct LineFeature {
  std::int64_t fid = 0;
  std::vector<Vec2> points;  // grid CRS metres; a closed ring does not repeat its first point
  bool closed = false;
  double width = 0.0;  // metres
  std::string source;  // "path:layer" for messages
};

// The widest feature accepted (100 km): wider is a units mistake, and its pixel footprint
// would overflow the raster stages.
inline constexpr double kMaxFeatureWidth = 1e5;

struct LineClassSpec {
  std::string name;
  VectorSource source;
  std::string width_attribute;  // empty = every feature gets default_width
  double default_width = 0.0;   // metres; used when the attribute is empty, null or unset
};

// Reads LineString/MultiLineString features (each part becomes a LineFeature with the same
// FID), reprojects them to the grid's CRS, clips them to the grid's extent (a part that leaves
// the extent and comes back becomes several LineFeatures), and skips (with a log line)
// features fully outside. Closed rings fully inside stay closed curves.
// Throws tw::Error naming file, layer and FID for: missing/unreadable file, unknown layer,
// bad where clause, no CRS, non-line geometries, zero-length or self-intersecting lines,
// non-finite or huge coordinates, width <= 0 or over kMaxFeatureWidth.
std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of);

// The first part of the first line feature of `source`, in the layer's own CRS (which must
// be projected, in metres), with read_line_features' checks on it (finite and plausible
// coordinates, non-zero length, no self-intersection); a closed ring becomes a closed curve.
// `terraweave synth` draws it. width is 0.
LineFeature read_first_line_feature(const VectorSource& source);

struct PolygonFeature {
  std::int64_t fid = 0;
  std::vector<std::vector<Vec2>> rings;  // [0] outer, rest holes; grid CRS metres, not repeating
                                         // the first point
  std::string source;                    // "path:layer"
};

// Reads Polygon/MultiPolygon features (each part becomes a PolygonFeature with the same FID),
// reprojected to the grid's CRS and clipped to its extent. Same errors as read_line_features.
std::vector<PolygonFeature> read_polygon_features(const VectorSource& source,
                                                  const Heightfield& grid_of);

}  // namespace tw
