#include "pipeline/version.hpp"

#include <OpenImageIO/oiioversion.h>
#include <fmt/format.h>
#include <gdal.h>
#include <GeographicLib/Constants.hpp>

namespace tw {

std::string version_line() {
  return fmt::format("terraweave {} (GDAL {}, GeographicLib {}, OpenImageIO {})",
                     kTerraweaveVersion, GDALVersionInfo("RELEASE_NAME"),
                     GEOGRAPHICLIB_VERSION_STRING, OIIO_VERSION_STRING);
}

}  // namespace tw
