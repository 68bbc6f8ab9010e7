#include "pipeline/version.hpp"

#include <OpenEXR/OpenEXRConfig.h>
#include <OpenImageIO/oiioversion.h>
#include <fmt/format.h>
#include <gdal.h>
#include <gdal_version.h>
#include <ogr_srs_api.h>
#include <GeographicLib/Constants.hpp>

namespace tw {

// The versions built against, as for GeographicLib and OpenImageIO: asking GDAL its own would
// load it (the program loads GDAL on first use, docs/performance.md) in every command and in
// every cache key, which hold this line. libgdal's SONAME pins the version's ABI.
std::string version_line() {
  return fmt::format("terraweave {} (GDAL {}, GeographicLib {}, OpenImageIO {})",
                     kTerraweaveVersion, GDAL_RELEASE_NAME, GEOGRAPHICLIB_VERSION_STRING,
                     OIIO_VERSION_STRING);
}

std::map<std::string, std::string> library_versions() {
  int proj_major = 0, proj_minor = 0, proj_patch = 0;
  OSRGetPROJVersion(&proj_major, &proj_minor, &proj_patch);
  return {{"gdal", GDALVersionInfo("RELEASE_NAME")},
          {"proj", fmt::format("{}.{}.{}", proj_major, proj_minor, proj_patch)},
          {"geographiclib", GEOGRAPHICLIB_VERSION_STRING},
          {"openimageio", OIIO_VERSION_STRING},
          {"openexr", OPENEXR_VERSION_STRING}};
}

}  // namespace tw
