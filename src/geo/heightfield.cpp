#include "geo/heightfield.hpp"

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include "core/error.hpp"
#include "core/grid_limits.hpp"
#include "core/log.hpp"
#include "geo/detail/gdal_support.hpp"
#include "geo/detail/warp.hpp"
#include "geo/heightfield_source.hpp"
#include "geo/input_guard.hpp"
#include "geo/metric_frame.hpp"
#include "geo/resample.hpp"

namespace tw {
namespace {

using detail::GdalDatasetPtr;

bool is_metric_north_up(const OGRSpatialReference& srs, const double gt[6]) {
  const bool metric = srs.IsProjected() && std::abs(srs.GetLinearUnits() - 1.0) < 1e-12;
  const bool north_up = gt[2] == 0.0 && gt[4] == 0.0 && gt[1] > 0.0 && gt[5] < 0.0;
  return metric && north_up;
}

Vec2 apply_geotransform(const double gt[6], Vec2 pixel) {
  return {gt[0] + pixel.x * gt[1] + pixel.y * gt[2], gt[3] + pixel.x * gt[4] + pixel.y * gt[5]};
}

// Whether a metric north-up DEM stays in its CRS under options.crs.
bool keeps_its_crs(const OGRSpatialReference& srs, GDALDataset& source, const double gt[6],
                   const std::string& crs) {
  if (crs.empty()) return true;
  if (crs == "local") return false;
  std::string wanted = crs;
  if (crs == "utm") {
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReference from(srs);
    from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> t(
        OGRCreateCoordinateTransformation(&from, &wgs84));
    Vec2 c = apply_geotransform(gt, {source.GetRasterXSize() / 2.0, source.GetRasterYSize() / 2.0});
    if (!t || !t->Transform(1, &c.x, &c.y)) return true;  // the warp would fail the same way
    wanted = utm_zone_epsg(c.x, c.y);
  }
  OGRSpatialReference target;
  return import_crs(target, wanted) && srs.IsSame(&target);
}

// The target CRS (options.crs; the UTM zone or local transverse Mercator of the DEM's centre),
// with the pixel size (metres, measured as
// geodesics on WGS84 between neighbouring pixel centres at the DEM's centre) unless the caller
// asked for a resolution.
detail::WarpTarget local_metric_target(GDALDataset& source, const OGRSpatialReference& srs,
                                       const double gt[6], const HeightfieldOptions& options,
                                       const std::string& path) {
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference source_srs(srs);
  source_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::unique_ptr<OGRCoordinateTransformation> to_lon_lat(
      OGRCreateCoordinateTransformation(&source_srs, &wgs84));
  if (!to_lon_lat) fail("{}: cannot relate its CRS to WGS84: {}", path, detail::last_gdal_error());

  const Vec2 centre_pixel{source.GetRasterXSize() / 2.0, source.GetRasterYSize() / 2.0};
  Vec2 lon_lat[3] = {apply_geotransform(gt, centre_pixel),
                     apply_geotransform(gt, centre_pixel + Vec2{1.0, 0.0}),
                     apply_geotransform(gt, centre_pixel + Vec2{0.0, 1.0})};
  for (Vec2& p : lon_lat) {
    if (!to_lon_lat->Transform(1, &p.x, &p.y)) {
      fail("{}: cannot locate its centre in WGS84: {}", path, detail::last_gdal_error());
    }
  }
  detail::WarpTarget target;
  // By default a geographic DEM goes to its centre's UTM zone (a CRS every GIS names by its
  // EPSG code); other DEMs without a metric north-up grid (feet, rotated) to a local one.
  const std::string asked =
      options.crs.empty() ? (srs.IsGeographic() ? "utm" : "local") : options.crs;
  const std::string crs = asked == "utm" ? utm_zone_epsg(lon_lat[0].x, lon_lat[0].y) : asked;
  if (crs == "local") {
    target.crs_wkt = local_transverse_mercator_wkt(lon_lat[0].x, lon_lat[0].y);
  } else {
    OGRSpatialReference out;
    if (!import_crs(out, crs)) fail("{}: PROJ does not know the output CRS '{}'", path, crs);
    if (!out.IsProjected() || std::abs(out.GetLinearUnits() - 1.0) > 1e-12)
      fail("{}: the output CRS '{}' is not projected in metres", path, crs);
    target.crs_wkt = detail::to_wkt(out);
  }
  if (options.resolution) {
    target.pixel_width = target.pixel_height = *options.resolution;
  } else {
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    geodesic.Inverse(lon_lat[0].y, lon_lat[0].x, lon_lat[1].y, lon_lat[1].x, target.pixel_width);
    geodesic.Inverse(lon_lat[0].y, lon_lat[0].x, lon_lat[2].y, lon_lat[2].x, target.pixel_height);
  }
  logger().info("{}: warping into {} (centre lon {:.6f} lat {:.6f}), {:.3f} x {:.3f} m pixels",
                path, crs == "local" ? "a local transverse Mercator" : crs, lon_lat[0].x,
                lon_lat[0].y, target.pixel_width, target.pixel_height);
  return target;
}

// Metres per unit of the band's values, from GDAL's unit type (GeoTIFF's vertical units).
// DEMs of the USA often hold feet; an empty or unknown unit is taken as metres.
double metres_per_height_unit(GDALRasterBand& band, const std::string& path, Warnings& warnings) {
  std::string unit = band.GetUnitType() ? band.GetUnitType() : "";
  for (char& c : unit) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" ||
      unit == "meters") {
    return 1.0;
  }
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") {
    return 0.3048;
  }
  if (unit == "us-ft" || unit == "ftus" || unit == "us survey foot" || unit == "us_survey_foot") {
    return 1200.0 / 3937.0;
  }
  warnings.add("unknown_unit", "heightfield", std::nullopt,
               fmt::format("{}: unknown height unit '{}'; taking heights as metres", path, unit));
  return 1.0;
}

// `window` of band 1 as float heights in metres; the nodata value, NaN and infinities all
// become NaN.
Raster<float> read_heights(GDALRasterBand& band, double metres_per_unit, const std::string& path,
                           const Window& window) {
  int has_nodata = 0;
  const double nodata = band.GetNoDataValue(&has_nodata);
  Raster<float> heights(window.width, window.height);
  std::vector<double> row(std::size_t(heights.width));
  for (int y = 0; y < heights.height; ++y) {
    if (band.RasterIO(GF_Read, window.col0, window.row0 + y, heights.width, 1, row.data(),
                      heights.width, 1, GDT_Float64, 0, 0) != CE_None) {
      fail("{}: cannot read row {}: {}", path, window.row0 + y, detail::last_gdal_error());
    }
    for (int x = 0; x < heights.width; ++x) {
      const double value = row[std::size_t(x)];
      const bool missing = !std::isfinite(value) || (has_nodata && value == nodata);
      const double metres = value * metres_per_unit;
      if (!missing && !(std::abs(metres) <= kMaxAbsHeight)) {
        fail(
            "{}: cell ({}, {}) holds a height of {:.6g} m, beyond +-{:g} m (an undeclared "
            "nodata value? declare it, e.g. gdal_edit.py -a_nodata)",
            path, window.col0 + x, window.row0 + y, metres, kMaxAbsHeight);
      }
      heights.at(x, y) = missing ? std::numeric_limits<float>::quiet_NaN() : float(metres);
    }
  }
  return heights;
}

// The grid of `resolution` m pixels on the native grid's north-west corner, covering it. A
// resolution coarser than the whole extent is refused: its one cell would lie half outside.
GridSpec resampled_grid(const GridSpec& native, double resolution, const std::string& path) {
  const double extent_x = native.width * native.pixel_width;
  const double extent_y = native.height * native.pixel_height;
  if (resolution > extent_x * (1 + 1e-9) || resolution > extent_y * (1 + 1e-9)) {
    fail(
        "{}: resolution {} m is coarser than the heightfield's extent ({:.6g} x {:.6g} m); the "
        "grid would be under one cell",
        path, resolution, extent_x, extent_y);
  }
  const double columns = std::ceil(extent_x / resolution - 1e-9);
  const double rows = std::ceil(extent_y / resolution - 1e-9);
  require_grid_size(columns, rows, fmt::format("{}: resolution {} m", path, resolution));
  return {int(columns), int(rows), native.origin_x, native.origin_y, resolution, resolution};
}

// What an opened GDAL heightfield reads from: band 1 of the file (or of its warp into a local
// metric frame), resampled onto `grid` when it differs from `native`.
struct OpenedRaster {
  GdalDatasetPtr file;
  detail::WarpedGrid warp;  // empty unless warped
  GridSpec native;          // the grid of the band read
  GridSpec grid;            // the heightfield's grid
  std::string crs_wkt;
  std::optional<double> nodata_value;
  double metres_per_unit = 1.0;
  bool resampled = false;
  Resampling resampling = Resampling::bilinear;
  std::string path;
};

class GdalSource final : public HeightfieldSource {
 public:
  explicit GdalSource(OpenedRaster raster)
      : HeightfieldSource(raster.grid, raster.crs_wkt, raster.nodata_value, raster.path),
        raster_(std::move(raster)) {}

 protected:
  Raster<float> read_window(const Window& window) const override {
    const Window cells =
        raster_.resampled ? resample_source_window(raster_.native, raster_.grid, window) : window;
    Raster<float> native;
    {
      // A GDAL dataset serves one thread at a time; resampling (parallel) runs unlocked.
      std::lock_guard lock(mutex_);
      detail::QuietGdalErrors quiet;
      GDALDataset& dataset = raster_.warp.warped ? *raster_.warp.warped : *raster_.file;
      native =
          read_heights(*dataset.GetRasterBand(1), raster_.metres_per_unit, raster_.path, cells);
    }
    if (!raster_.resampled) return native;
    return resample_heights_window(native, cells, raster_.native, raster_.grid, window,
                                   raster_.resampling);
  }

 private:
  OpenedRaster raster_;
  mutable std::mutex mutex_;
};

}  // namespace

Heightfield read_heightfield(const std::string& path, const HeightfieldOptions& options) {
  Warnings warnings;  // logged as they are raised
  return read_heightfield(path, options, warnings);
}

std::string utm_zone_epsg(double lon_degrees, double lat_degrees) {
  const int zone = std::clamp(int(std::floor((lon_degrees + 180.0) / 6.0)) + 1, 1, 60);
  return fmt::format("EPSG:{}", (lat_degrees >= 0.0 ? 32600 : 32700) + zone);
}

Heightfield read_heightfield(const std::string& path, const HeightfieldOptions& options,
                             Warnings& warnings) {
  return read_whole_heightfield(*open_heightfield(path, options, warnings));
}

std::unique_ptr<HeightfieldSource> open_heightfield(const std::string& path,
                                                    const HeightfieldOptions& options,
                                                    Warnings& warnings) {
  detail::ensure_gdal_registered();
  detail::QuietGdalErrors quiet;
  if (options.resolution && !(std::isfinite(*options.resolution) && *options.resolution > 0.0)) {
    fail("{}: resolution must be a positive number of metres, got {}", path, *options.resolution);
  }
  check_input_path(path, "heightfield", network_access_allowed());  // also for library callers
  OpenedRaster raster;
  raster.path = path;
  raster.resampling = options.resampling;
  raster.file.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  GDALDataset* source = raster.file.get();
  if (!source) fail("{}: cannot open as a raster: {}", path, detail::open_failure(path));
  if (source->GetRasterCount() < 1) fail("{}: has no raster band", path);
  const OGRSpatialReference* srs = source->GetSpatialRef();
  if (!srs || srs->IsEmpty()) {
    fail("{}: has no CRS; a heightfield needs one to place features in metres", path);
  }
  double gt[6];
  if (source->GetGeoTransform(gt) != CE_None) fail("{}: has no geotransform", path);
  int has_nodata = 0;
  const double nodata = source->GetRasterBand(1)->GetNoDataValue(&has_nodata);
  if (has_nodata) raster.nodata_value = nodata;
  raster.metres_per_unit = metres_per_height_unit(*source->GetRasterBand(1), path, warnings);

  if (is_metric_north_up(*srs, gt) && keeps_its_crs(*srs, *source, gt, options.crs)) {
    // Same CRS: the cells as they are, or resampled on the same north-west corner (our
    // resampler: GDAL's cubic warp turns blocky within two cells of a DEM's edges).
    raster.crs_wkt = detail::to_wkt(*srs);
    raster.native = {
        source->GetRasterXSize(), source->GetRasterYSize(), gt[0], gt[3], gt[1], -gt[5]};
    require_grid_size(raster.native.width, raster.native.height, path);
    raster.grid = raster.native;
    if (options.resolution) {
      raster.grid = resampled_grid(raster.native, *options.resolution, path);
      raster.resampled = true;
    }
    return std::make_unique<GdalSource>(std::move(raster));
  }
  // Geographic, non-metre, rotated or another output CRS: warped by GDAL.
  const detail::WarpTarget target = local_metric_target(*source, *srs, gt, options, path);
  raster.crs_wkt = target.crs_wkt;
  raster.warp = detail::warp_to_metric_grid(
      *source, target, path, options.resampling == Resampling::cubic ? "cubic" : "bilinear");
  GDALDataset& warped = *raster.warp.warped;
  if (warped.GetGeoTransform(gt) != CE_None) fail("{}: warped grid has no geotransform", path);
  raster.native = {warped.GetRasterXSize(), warped.GetRasterYSize(), gt[0], gt[3], gt[1], -gt[5]};
  raster.grid = raster.native;
  return std::make_unique<GdalSource>(std::move(raster));
}

}  // namespace tw
