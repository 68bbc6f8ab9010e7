#pragma once
// Geodesic lengths on the WGS84 ellipsoid (GeographicLib), to check metric-frame lengths.
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

// Sum of the geodesic lengths of the segments of a polyline given as (lon, lat) in degrees;
// metres on WGS84.
double geodesic_length(const std::vector<Vec2>& lon_lat_degrees);

// Sum of the Euclidean segment lengths of a polyline in a metric CRS.
double planar_length(const std::vector<Vec2>& points);

struct LengthCheck {
  double geodesic_m = 0.0;  // on the ellipsoid
  double metric_m = 0.0;    // in the metric CRS
  double relative_error() const { return metric_m / geodesic_m - 1.0; }
};

// Projects a (lon, lat) polyline into the metric CRS (WKT or "EPSG:n") and compares its
// planar length there with its geodesic length.
LengthCheck check_metric_length(const std::vector<Vec2>& lon_lat_degrees,
                                const std::string& metric_crs);

}  // namespace tw
