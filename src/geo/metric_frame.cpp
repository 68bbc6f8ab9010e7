#include "geo/metric_frame.hpp"

#include <ogr_spatialref.h>
#include <GeographicLib/Geodesic.hpp>

#include <cmath>
#include <numbers>

#include "core/error.hpp"
#include "geo/detail/gdal_support.hpp"

namespace tw {

std::string local_transverse_mercator_wkt(double lon0_degrees, double lat0_degrees) {
  OGRSpatialReference srs;
  const std::string proj = fmt::format(
      "+proj=tmerc +lat_0={:.12g} +lon_0={:.12g} +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m "
      "+no_defs",
      lat0_degrees, lon0_degrees);
  if (srs.importFromProj4(proj.c_str()) != OGRERR_NONE) {
    fail("cannot build the local metric frame '{}'", proj);
  }
  return detail::to_wkt(srs);
}

MetresPerDegree metres_per_degree(double latitude_degrees) {
  // Measured as short geodesics (0.001 degree) centred on the latitude, so the figures are
  // those of the ellipsoid rather than of a sphere.
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  constexpr double step = 1e-3;
  double north_south = 0.0;
  double east_west = 0.0;
  wgs84.Inverse(latitude_degrees - step / 2, 0.0, latitude_degrees + step / 2, 0.0, north_south);
  // Along the parallel: over 0.001 degree the geodesic and the parallel differ by far less
  // than a millimetre per degree.
  wgs84.Inverse(latitude_degrees, 0.0, latitude_degrees, step, east_west);
  return {north_south / step, east_west / step};
}

}  // namespace tw
