#include "geo/detail/warp.hpp"

#include <gdal_utils.h>

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
  return run_gdalwarp(band_one ? *band_one : full_source, target, "bilinear", label);
}

}  // namespace tw::detail
