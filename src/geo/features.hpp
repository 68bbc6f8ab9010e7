#pragma once
// Vector features (OGR) brought into a heightfield's grid CRS and clipped to its extent.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/vec2.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield.hpp"
#include "geo/line_repair_memo.hpp"
#include "geo/structure.hpp"

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
  // From the columns `bridge`, `tunnel` and `layer` when the source has them (any driver;
  // OSM's conventions, geo/osm_tags.hpp); ground and layer 0 otherwise.
  Structure structure = Structure::ground;
  int layer = 0;
};

// How messy lines are cleaned after clipping (docs/pipeline.md, "repair"). Lengths in metres of
// the grid's CRS.
struct LineRepair {
  double merge_distance = 0.01;  // consecutive vertices closer than this are one vertex
  double spike_angle = 170.0;    // degrees: a vertex turning back by more is a spike, removed
  double min_loop = 2.0;         // a loop (the line meets itself) shorter than this is cut out
};

// The widest feature accepted (100 km): wider is a units mistake, and its pixel footprint
// would overflow the raster stages.
inline constexpr double kMaxFeatureWidth = 1e5;

struct LineClassSpec {
  std::string name;
  VectorSource source;
  std::string width_attribute;  // empty = every feature gets default_width
  double default_width = 0.0;   // metres; used when the attribute is empty, null or unset
  // Widths from the OSM tag table (geo/osm_tags.hpp: columns width, lanes, highway, waterway,
  // natural) where width_attribute gives none, before default_width (0 = no default).
  bool osm_widths = false;
  std::string subject;  // the key warnings name, e.g. "features.rivers"; empty = name
  // Features are clipped to the grid's extent grown by half their width plus this many metres
  // (the reach of the stages beyond the width, e.g. banks and falloff).
  double clip_margin = 0.0;
  LineRepair repair;
  // Where set, each piece's repair is looked up under line_repair_key and stored there when
  // computed (the run cache's, docs/cache.md); the lines and warnings are those of a repair.
  LineRepairMemo repair_memo;
};

// Reads LineString/MultiLineString features (each part becomes a LineFeature with the same
// FID; curves are linearized, Z/M dropped with a `dropped_zm` warning), reprojects them to the
// grid's CRS, clips them to the grid's extent grown by half the width plus spec.clip_margin (a
// part that leaves it and comes back becomes several LineFeatures), and skips (with a log line)
// features fully outside. Closed rings fully inside stay closed curves. Only then is each piece
// judged: duplicate vertices, spikes, loops shorter than repair.min_loop and zero-length parts
// are removed with one `repaired` warning per FID saying what changed; a line that still crosses
// itself is kept (a self-crossing: a junction for the later stages).
// Throws tw::Error naming file, layer and FID for: missing/unreadable file, unknown layer,
// bad where clause, no CRS, non-line geometries, non-finite or huge coordinates, width <= 0 or over
// kMaxFeatureWidth.
// Unusable `width`, `lanes` or `layer` values are skipped with a warning (subject
// "features.<spec.name>", the FID); the two-argument form only logs its warnings.
std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of,
                                            Warnings& warnings);
std::vector<LineFeature> read_line_features(const LineClassSpec& spec, const Heightfield& grid_of);

// The first part of the first line feature of `source`, in the layer's own CRS (which must
// be projected, in metres), with read_line_features' checks on it (finite and plausible
// coordinates, non-zero length; a line crossing itself is kept); a closed ring becomes a
// closed curve.
// `terraweave synth` draws it. width is 0.
LineFeature read_first_line_feature(const VectorSource& source);

// Why `source` (its where clause applied) gives no feature on the grid, for an `empty_source`
// warning: the layer has no rows, the where clause matches none, or its features lie off the
// heightfield though its extent meets it. nullopt when the layer's extent does not meet the grid
// (nothing was to be expected from it there). Same errors as read_line_features.
std::optional<std::string> why_no_features(const VectorSource& source, const Heightfield& grid_of);

struct PolygonFeature {
  std::int64_t fid = 0;
  std::vector<std::vector<Vec2>> rings;  // [0] outer, rest holes; grid CRS metres, not repeating
                                         // the first point
  std::string source;                    // "path:layer"
};

// Reads Polygon/MultiPolygon features (each part becomes a PolygonFeature with the same FID),
// reprojected to the grid's CRS and clipped to its extent. An invalid polygon on the grid
// (self-intersecting or badly nested rings) is made valid by GEOS with a `repaired` warning
// under `subject`. Same errors as read_line_features.
std::vector<PolygonFeature> read_polygon_features(const VectorSource& source,
                                                  const Heightfield& grid_of,
                                                  const std::string& subject, Warnings& warnings);

}  // namespace tw
