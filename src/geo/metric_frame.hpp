#pragma once
// Local metric frames: where a heightfield that is not in metres is warped to.
#include <string>

namespace tw {

// WKT of a transverse Mercator on WGS84 centred on (lon0, lat0): scale 1 at the central
// meridian, false origin at the centre, so that x/y are metres east/north of the centre.
// Its PROJ string is
//   +proj=tmerc +lat_0=<lat0> +lon_0=<lon0> +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs
std::string local_transverse_mercator_wkt(double lon0_degrees, double lat0_degrees);

// Metres per degree of latitude and of longitude at a latitude on WGS84 (GeographicLib).
struct MetresPerDegree {
  double latitude = 0.0;   // north-south
  double longitude = 0.0;  // east-west
};
MetresPerDegree metres_per_degree(double latitude_degrees);

}  // namespace tw
