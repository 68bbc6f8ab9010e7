#include "geo/detail/warp.hpp"

#include <cpl_string.h>
#include <gdal_utils.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "core/error.hpp"
#include "core/grid_limits.hpp"

namespace tw::detail {
namespace {

// The argument vector of a GDAL utility, owning copies of its strings: GDAL's *OptionsNew read
// them after the caller's temporaries are gone.
CPLStringList gdal_arguments(const std::vector<std::string>& args) {
  CPLStringList argv;
  for (const std::string& arg : args) argv.AddString(arg.c_str());
  return argv;
}

// GDAL 3.6's gdalwarp has no -b: a virtual dataset of band 1 alone stands in for the source.
GdalDatasetPtr first_band_only(GDALDataset& source, const std::string& label) {
  CPLStringList argv = gdal_arguments({"-of", "VRT", "-b", "1"});
  GDALTranslateOptions* options = GDALTranslateOptionsNew(argv.List(), nullptr);
  int usage_error = 0;
  GDALDatasetH band = GDALTranslate("", GDALDataset::ToHandle(&source), options, &usage_error);
  GDALTranslateOptionsFree(options);
  if (!band || usage_error) fail("{}: cannot select band 1: {}", label, last_gdal_error());
  return GdalDatasetPtr(GDALDataset::FromHandle(band));
}

// The target extent covering the whole source footprint in whole pixels. gdalwarp's own
// choice rounds the pixel count to the nearest, which can drop up to half a pixel (hundreds of
// metres for arc-second DEMs) and with it data and the ends of features at the DEM's edge.
// The footprint's edges are curves in the target CRS: they are sampled densely.
struct Extent {
  double west, south, east, north;
};
Extent covering_extent(GDALDataset& source, const WarpTarget& target, const std::string& label) {
  OGRSpatialReference from(*source.GetSpatialRef());
  from.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRSpatialReference to;
  if (!import_traditional_srs(to, target.crs_wkt)) fail("{}: bad target CRS", label);
  std::unique_ptr<OGRCoordinateTransformation> transform(
      OGRCreateCoordinateTransformation(&from, &to));
  if (!transform) fail("{}: cannot relate it to the metric grid: {}", label, last_gdal_error());
  double gt[6];
  source.GetGeoTransform(gt);
  const double columns = source.GetRasterXSize();
  const double rows = source.GetRasterYSize();
  constexpr int samples = 256;  // per edge
  std::vector<double> xs;
  std::vector<double> ys;
  for (int i = 0; i <= samples; ++i) {
    const double t = double(i) / samples;
    for (const auto& [col, row] : {std::pair{t * columns, 0.0}, std::pair{t * columns, rows},
                                   std::pair{0.0, t * rows}, std::pair{columns, t * rows}}) {
      xs.push_back(gt[0] + col * gt[1] + row * gt[2]);
      ys.push_back(gt[3] + col * gt[4] + row * gt[5]);
    }
  }
  std::vector<int> ok(xs.size());
  transform->Transform(int(xs.size()), xs.data(), ys.data(), nullptr, ok.data());
  Extent bounds{HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) continue;
    bounds = {std::min(bounds.west, xs[i]), std::min(bounds.south, ys[i]),
              std::max(bounds.east, xs[i]), std::max(bounds.north, ys[i])};
  }
  if (!(bounds.west < bounds.east && bounds.south < bounds.north)) {
    fail("{}: cannot find its extent in the metric grid: {}", label, last_gdal_error());
  }
  // Whole pixels from the north-west corner; 1e-9 keeps an exact fit from gaining a pixel.
  const double span_x = (bounds.east - bounds.west) / target.pixel_width;
  const double span_y = (bounds.north - bounds.south) / target.pixel_height;
  if (span_x < 0.5 || span_y < 0.5) {
    fail(
        "{}: {:.6g} x {:.6g} m pixels are coarser than its extent ({:.6g} x {:.6g} m); the grid "
        "would be under one cell",
        label, target.pixel_width, target.pixel_height, bounds.east - bounds.west,
        bounds.north - bounds.south);
  }
  const double width = std::ceil(span_x - 1e-9);
  const double height = std::ceil(span_y - 1e-9);
  require_grid_size(
      width, height,
      fmt::format("{}: {:.6g} x {:.6g} m pixels", label, target.pixel_width, target.pixel_height));
  return {bounds.west, bounds.north - height * target.pixel_height,
          bounds.west + width * target.pixel_width, bounds.north};
}

std::string number(double value) {
  return fmt::format("{:.17g}", value);
}

GdalDatasetPtr run_gdalwarp(GDALDataset& source, const WarpTarget& target, const char* resampling,
                            const std::string& label) {
  const Extent extent = covering_extent(source, target, label);
  // clang-format off
  const std::vector<std::string> args = {
      "-of", "VRT", "-t_srs", target.crs_wkt,
      "-te", number(extent.west), number(extent.south), number(extent.east), number(extent.north),
      "-tr", number(target.pixel_width), number(target.pixel_height),
      "-r", resampling, "-ot", "Float32", "-dstnodata", "nan"};
  // clang-format on
  CPLStringList argv = gdal_arguments(args);
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv.List(), nullptr);
  if (!options) fail("{}: bad warp options: {}", label, last_gdal_error());
  GDALDatasetH source_handle = GDALDataset::ToHandle(&source);
  int usage_error = 0;
  GDALDatasetH warped = GDALWarp("", nullptr, 1, &source_handle, options, &usage_error);
  GDALWarpAppOptionsFree(options);
  if (!warped || usage_error) {
    fail("{}: cannot warp into a metric grid: {}", label, last_gdal_error());
  }
  return GdalDatasetPtr(GDALDataset::FromHandle(warped));
}

}  // namespace

WarpedGrid warp_to_metric_grid(GDALDataset& full_source, const WarpTarget& target,
                               const std::string& label, const char* resampling) {
  WarpedGrid result;
  if (full_source.GetRasterCount() > 1) result.band_one = first_band_only(full_source, label);
  result.warped =
      run_gdalwarp(result.band_one ? *result.band_one : full_source, target, resampling, label);
  return result;
}

}  // namespace tw::detail
