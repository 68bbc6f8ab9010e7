#include "geo/detail/gdal_support.hpp"

#include <cpl_error.h>

#include <filesystem>
#include <mutex>

#include "geo/input_guard.hpp"

namespace tw::detail {

void ensure_gdal_registered() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

QuietGdalErrors::QuietGdalErrors() {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}

QuietGdalErrors::~QuietGdalErrors() {
  CPLPopErrorHandler();
}

std::string last_gdal_error() {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? std::string(message) : std::string("unknown GDAL error");
}

std::string open_failure(const std::string& path) {
  const char* message = CPLGetLastErrorMsg();
  if (message && *message) return message;
  if (path.starts_with("/vsi")) return "not readable through GDAL's virtual file systems";
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status)) return "no such file";
  if (std::filesystem::is_directory(status)) return "is a folder, not a file";
  return "not a format GDAL can read";
}

bool import_traditional_srs(OGRSpatialReference& srs, const std::string& user_input) {
  if (!import_crs(srs, user_input)) return false;
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return true;
}

std::string to_wkt(const OGRSpatialReference& srs) {
  char* wkt = nullptr;
  const char* options[] = {"FORMAT=WKT2_2018", nullptr};
  srs.exportToWkt(&wkt, options);
  std::string result = wkt ? wkt : "";
  CPLFree(wkt);
  return result;
}

}  // namespace tw::detail
