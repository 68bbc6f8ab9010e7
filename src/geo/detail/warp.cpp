#include "geo/detail/warp.hpp"

#include <gdal_utils.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace tw::detail {
namespace {

std::vector<char*> argv_of(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);
  return argv;
}

// GDAL 3.6's gdalwarp has no -b: a virtual dataset of band 1 alone stands in for the source.
GdalDatasetPtr first_band_only(GDALDataset& source, const std::string& label) {
  std::vector<char*> argv = argv_of({"-of", "VRT", "-b", "1"});
  GDALTranslateOptions* options = GDALTranslateOptionsNew(argv.data(), nullptr);
  int usage_error = 0;
  GDALDatasetH band = GDALTranslate("", GDALDataset::ToHandle(&source), options, &usage_error);
  GDALTranslateOptionsFree(options);
  if (!band || usage_error) fail("{}: cannot select band 1: {}", label, last_gdal_error());
  return GdalDatasetPtr(GDALDataset::FromHandle(band));
}

GdalDatasetPtr run_gdalwarp(GDALDataset& source, const WarpTarget& target, const char* resampling,
                            const std::string& label) {
  // clang-format off
  const std::vector<std::string> args = {
      "-of", "MEM", "-t_srs", target.crs_wkt,
      "-tr", fmt::format("{:.17g}", target.pixel_width), fmt::format("{:.17g}", target.pixel_height),
      "-r", resampling, "-ot", "Float32", "-dstnodata", "nan"};
  // clang-format on
  std::vector<char*> argv = argv_of(args);
  GDALWarpAppOptions* options = GDALWarpAppOptionsNew(argv.data(), nullptr);
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

GdalDatasetPtr warp_to_metric_grid(GDALDataset& full_source, const WarpTarget& target,
                                   const std::string& label) {
  GdalDatasetPtr band_one;
  if (full_source.GetRasterCount() > 1) band_one = first_band_only(full_source, label);
  GDALDataset& source = band_one ? *band_one : full_source;
  GdalDatasetPtr bilinear = run_gdalwarp(source, target, "bilinear", label);
  int has_nodata = 0;
  source.GetRasterBand(1)->GetNoDataValue(&has_nodata);
  if (!has_nodata) return bilinear;

  GdalDatasetPtr nearest = run_gdalwarp(source, target, "near", label);
  GDALRasterBand* heights = bilinear->GetRasterBand(1);
  GDALRasterBand* nearest_band = nearest->GetRasterBand(1);
  const int width = heights->GetXSize();
  std::vector<float> row(width);
  std::vector<float> nearest_row(width);
  for (int y = 0; y < heights->GetYSize(); ++y) {
    if (heights->RasterIO(GF_Read, 0, y, width, 1, row.data(), width, 1, GDT_Float32, 0, 0) !=
            CE_None ||
        nearest_band->RasterIO(GF_Read, 0, y, width, 1, nearest_row.data(), width, 1, GDT_Float32,
                               0, 0) != CE_None) {
      fail("{}: cannot read the warped grid: {}", label, last_gdal_error());
    }
    bool changed = false;
    for (int x = 0; x < width; ++x) {
      if (std::isnan(nearest_row[x]) && !std::isnan(row[x])) {
        row[x] = std::nanf("");
        changed = true;
      }
    }
    if (changed && heights->RasterIO(GF_Write, 0, y, width, 1, row.data(), width, 1, GDT_Float32, 0,
                                     0) != CE_None) {
      fail("{}: cannot write the warped grid: {}", label, last_gdal_error());
    }
  }
  return bilinear;
}

}  // namespace tw::detail
