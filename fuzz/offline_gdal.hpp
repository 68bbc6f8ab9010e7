#pragma once
// GDAL as the fuzz targets that read files through it need it: every driver, no error printed
// (a refusal is an answer, not a finding), and the bytes are a file, never a pointer to
// somewhere else: no network, no other files.
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>

namespace tw::fuzz {

inline void start_offline_gdal() {
  GDALAllRegister();
  CPLSetConfigOption("CPL_LOG_ERRORS", "OFF");
  CPLSetErrorHandler(CPLQuietErrorHandler);
  CPLSetConfigOption("GDAL_HTTP_TIMEOUT", "1");
  CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS", "none");
}

}  // namespace tw::fuzz
