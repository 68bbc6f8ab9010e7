#include "geo/geodesic.hpp"

#include <ogr_spatialref.h>
#include <GeographicLib/Geodesic.hpp>

#include <memory>

#include "core/error.hpp"
#include "geo/detail/gdal_support.hpp"

namespace tw {

double geodesic_length(const std::vector<Vec2>& lon_lat_degrees) {
  const GeographicLib::Geodesic& wgs84 = GeographicLib::Geodesic::WGS84();
  double total = 0.0;
  for (std::size_t i = 1; i < lon_lat_degrees.size(); ++i) {
    const Vec2 a = lon_lat_degrees[i - 1];
    const Vec2 b = lon_lat_degrees[i];
    double s12 = 0.0;
    wgs84.Inverse(a.y, a.x, b.y, b.x, s12);
    total += s12;
  }
  return total;
}

double planar_length(const std::vector<Vec2>& points) {
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += distance(points[i - 1], points[i]);
  return total;
}

LengthCheck check_metric_length(const std::vector<Vec2>& lon_lat_degrees,
                                const std::string& metric_crs) {
  detail::ensure_gdal_registered();
  detail::QuietGdalErrors quiet;
  OGRSpatialReference geographic;
  geographic.SetWellKnownGeogCS("WGS84");
  geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference metric;
  if (!detail::import_traditional_srs(metric, metric_crs)) fail("unknown CRS '{}'", metric_crs);
  std::unique_ptr<OGRCoordinateTransformation> transform(
      OGRCreateCoordinateTransformation(&geographic, &metric));
  if (!transform) fail("no transformation from WGS84 to '{}'", metric_crs);
  std::vector<Vec2> projected;
  for (const Vec2& p : lon_lat_degrees) {
    double x = p.x;
    double y = p.y;
    if (!transform->Transform(1, &x, &y)) {
      fail("cannot project ({}, {}) into '{}'", p.x, p.y, metric_crs);
    }
    projected.push_back({x, y});
  }
  return {geodesic_length(lon_lat_degrees), planar_length(projected)};
}

}  // namespace tw
