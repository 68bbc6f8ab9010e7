#pragma once
// The lead direction fields of `kind: area` classes (pipeline/area_config.hpp): the direction of
// the nearest line feature, and the terrain's contour direction over a polygon.
#include <optional>
#include <vector>

#include "geo/features.hpp"
#include "geo/height_sampler.hpp"
#include "raster/polygon.hpp"

namespace tw {

// A compass bearing in degrees, in [0, 360) (clockwise from north), of the angle `radians`
// counter-clockwise from +x; and back. One convention for reports, instances and `lead.bearing`.
double compass_degrees(double radians);
double angle_from_compass(double degrees);

// The angle (radians counter-clockwise from +x, in [0, pi)) of the segment of `lines` nearest
// to the polygon's outer ring (0 distance when they cross); none without a segment.
std::optional<double> nearest_line_angle(const Polygon& polygon,
                                         const std::vector<const LineFeature*>& lines);

// The contour direction over the polygon, in [0, pi): perpendicular to the dominant gradient of
// the heights (the principal axis of the gradients' structure tensor, sampled on a 32 x 32
// lattice over the polygon's box, inside the polygon, nodata skipped); none where the polygon
// is flat (mean gradient below 0.1 %) or over nodata.
std::optional<double> contour_angle(const Polygon& polygon, HeightSampler& heights);

}  // namespace tw
