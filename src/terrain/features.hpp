#pragma once
// Linear terrain features (roads, rivers, ridges) as the terrain module sees them: a
// centerline in world metres, a width and the profile parameters of the feature's kind.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "geo/structure.hpp"
#include "ribbon/curve.hpp"

namespace tw {

enum class FeatureKind { road, river, ridge };

std::string_view to_string(FeatureKind kind);

// A graded road: the longitudinal profile is the terrain along the centerline smoothed over
// `smoothing` metres, then limited to `max_grade`; the cross-section is level over the road
// and its shoulders, then blends into the terrain over `falloff` metres (cut and fill).
struct RoadProfile {
  double max_grade = 0.08;      // rise over run
  double shoulder_width = 3.0;  // metres on each side of the road surface
  double falloff = 15.0;        // metres of cut/fill slope beyond the shoulders
  double smoothing = 60.0;      // metres of the moving average along the centerline
  // Bounds on the earthwork (metres below / above the terrain): where grading would cut or
  // fill more, the road follows the terrain at that bound, breaking the grade locally (a
  // warning). Unset: unbounded.
  std::optional<double> max_cut;
  std::optional<double> max_fill;
};

// A carved river: the water surface follows the terrain downstream (the centerline's
// direction) but never rises; the bed is `depth` below it across the width, with banks that
// blend into the terrain over bank_width + falloff metres. Rivers only ever lower terrain.
struct RiverProfile {
  double depth = 2.5;       // metres below the water surface
  double bank_width = 6.0;  // metres of bank on each side
  double falloff = 20.0;    // metres beyond the banks
  double min_slope = 0.0;   // the surface drops at least this much per metre downstream
  // The bed is never more than this below the terrain: where the never-rising surface would
  // cut deeper (a line across a spur), the surface rises to meet the terrain (a warning).
  // Unset: kDefaultCarveDepths x depth.
  std::optional<double> max_carve;
};

inline constexpr double kDefaultCarveDepths = 2.0;
// The bound in metres (max_carve, or its default).
inline double max_carve(const RiverProfile& river) {
  return river.max_carve.value_or(kDefaultCarveDepths * river.depth);
}

// A raised ridge: the crest (the width) is raised by `height`, the flanks fall off over
// `falloff` metres; a larger `sharpness` gives a narrower, more pointed crest.
struct RidgeProfile {
  double height = 8.0;
  double falloff = 60.0;
  double sharpness = 1.5;
};

struct TerrainFeature {
  FeatureKind kind = FeatureKind::road;
  std::int64_t fid = 0;  // named in error messages
  std::string subject;   // the key warnings name, e.g. "features.rivers"; empty = the kind
  Curve centerline;      // world metres; for rivers, points run downstream
  double width = 0.0;    // metres: road surface, river bed, or ridge crest
  // A bridge or tunnel leaves the ground under it untouched and paints no splat; its profile
  // is its deck, straight between the features it joins at its ends (docs/osm.md).
  Structure structure = Structure::ground;
  int layer = 0;  // features on different layers never meet at grade
  RoadProfile road;
  RiverProfile river;
  RidgeProfile ridge;
};

// Metres from the centerline within which the feature changes heights or splat weights.
double feature_reach(const TerrainFeature& feature);

// Throws tw::Error naming the FID when a feature has fewer than two distinct points, a
// non-finite point, or a width / profile parameter out of range.
void validate_feature(const TerrainFeature& feature);

}  // namespace tw
