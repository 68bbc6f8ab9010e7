#pragma once
// The directions of leads (pipeline/lead.hpp) over a polygon: the nearest road's, the terrain's
// contours', the polygon's long axis, a compass bearing.
#include <optional>
#include <vector>

#include "geo/features.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/config.hpp"
#include "pipeline/lead.hpp"
#include "raster/polygon.hpp"

namespace tw {

// The lines of the run's `kind: road` classes (`lines` per class of `classes`).
std::vector<const LineFeature*> road_lines(const std::vector<FeatureClassConfig>& classes,
                                           const std::vector<std::vector<LineFeature>>& lines);

// The polygon of a region that a lead is read on: its largest (the first of equal ones).
const Polygon& lead_polygon(const std::vector<Polygon>& region);

// A lead's angle over `polygon`, radians counter-clockwise from +x. `nearest_road` without a
// road and `contours` over flat or nodata terrain fall back to the polygon's long axis and say so
// (`fell_back`: the caller names it in its warning or log).
struct LeadAngle {
  double radians = 0.0;
  bool fell_back = false;
};
LeadAngle lead_angle(Lead lead, double bearing_deg, const Polygon& polygon,
                     const std::vector<const LineFeature*>& roads, HeightSampler& heights);

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
