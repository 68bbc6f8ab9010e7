#include "layers/vrt.hpp"

#include <cpl_string.h>
#include <gdal_utils.h>

#include <string>

#include "core/error.hpp"
#include "layers/detail/gdal_init.hpp"

namespace tw {

void write_vrt_mosaic(const std::filesystem::path& vrt,
                      const std::vector<std::filesystem::path>& sources) {
  if (sources.empty()) fail("{}: a mosaic needs at least one tile", vrt.string());
  detail::ensure_gdal_registered();
  CPLErrorReset();
  std::vector<std::string> names;
  for (const auto& s : sources) names.push_back(s.string());
  std::vector<const char*> pointers;
  for (const auto& n : names) pointers.push_back(n.c_str());
  CPLStringList argv;
  argv.AddString("-q");
  GDALBuildVRTOptions* options = GDALBuildVRTOptionsNew(argv.List(), nullptr);
  int usage_error = 0;
  GDALDatasetH ds = GDALBuildVRT(vrt.c_str(), int(pointers.size()), nullptr, pointers.data(),
                                 options, &usage_error);
  GDALBuildVRTOptionsFree(options);
  if (ds == nullptr || usage_error) {
    if (ds) GDALClose(ds);
    fail("{}: cannot build the VRT mosaic of {} tiles: {}", vrt.string(), sources.size(),
         CPLGetLastErrorMsg());
  }
  // GDALBuildVRT keeps no band descriptions; the tiles' (material names) name the mosaic's.
  if (GDALDatasetH first = GDALOpen(names.front().c_str(), GA_ReadOnly)) {
    for (int b = 1; b <= GDALGetRasterCount(first) && b <= GDALGetRasterCount(ds); ++b)
      GDALSetDescription(GDALGetRasterBand(ds, b), GDALGetDescription(GDALGetRasterBand(first, b)));
    GDALClose(first);
  }
  GDALClose(ds);
  if (CPLGetLastErrorType() >= CE_Failure) {
    fail("{}: cannot write the VRT mosaic: {}", vrt.string(), CPLGetLastErrorMsg());
  }
}

}  // namespace tw
