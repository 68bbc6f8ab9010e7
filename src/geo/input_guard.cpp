#include "geo/input_guard.hpp"

#include <cpl_conv.h>
#include <cpl_http.h>
#include <ogr_spatialref.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>

#include "core/error.hpp"

namespace tw {

namespace {

std::atomic<bool> network_allowed{false};

// GDAL's virtual file systems over the network (GDAL 3.6; the _streaming variants share the
// prefixes).
constexpr std::array<std::string_view, 9> kNetworkFileSystems = {
    "/vsicurl", "/vsis3",    "/vsigs",      "/vsiaz",  "/vsiadls",
    "/vsioss",  "/vsiswift", "/vsiwebhdfs", "/vsihdfs"};
// URL schemes GDAL and PROJ fetch, as a path component ("http:" in "http://x" or, once the
// path is normalised, "http:/x").
constexpr std::array<std::string_view, 4> kSchemes = {"http:", "https:", "ftp:", "ftps:"};

// Connection strings of GDAL drivers that talk to a server, as a name's first characters.
constexpr std::array<std::string_view, 19> kServerDrivers = {
    "pg:",    "mysql:", "mssql:",  "oci:",      "odbc:",      "mongodbv3:", "elastic:",
    "carto:", "wfs:",   "wms:",    "wcs:",      "oapif:",     "eeda:",      "ngw:",
    "hana:",  "daas:",  "stacit:", "plscenes:", "amigocloud:"};

}  // namespace

std::string network_part_of(std::string_view path) {
  std::string lower(path);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  for (std::string_view prefix : kNetworkFileSystems) {
    if (lower.find(prefix) != std::string::npos) return std::string(prefix);
  }
  for (std::string_view driver : kServerDrivers) {
    if (lower.starts_with(driver)) return std::string(driver);
  }
  for (std::string_view scheme : kSchemes) {
    for (std::size_t at = lower.find(scheme); at != std::string::npos;
         at = lower.find(scheme, at + 1)) {
      const bool starts_component = at == 0 || lower[at - 1] == '/' || lower[at - 1] == '?' ||
                                    lower[at - 1] == '=' || lower[at - 1] == ':';
      const std::size_t end = at + scheme.size();
      if (starts_component && (end == lower.size() || lower[end] == '/')) {
        return std::string(scheme);
      }
    }
  }
  return {};
}

void check_input_path(const std::string& path, const std::string& key, bool allow_network) {
  if (allow_network) return;
  const std::string part = network_part_of(path);
  if (!part.empty()) {
    fail(
        "{}: '{}' reaches the network ({}); terraweave reads local files unless run with "
        "--allow-network",
        key, path, part);
  }
}

namespace {

// Every CPLHTTPFetch (GeoJSON `crs` links, WFS/WMS drivers, OSR URL imports) ends here while
// the network is off: a failed request, no connection. /vsicurl does not use CPLHTTPFetch.
CPLHTTPResult* refuse_http(const char* url, CSLConstList, GDALProgressFunc, void*,
                           CPLHTTPFetchWriteFunc, void*, void*) {
  auto* result = static_cast<CPLHTTPResult*>(CPLCalloc(1, sizeof(CPLHTTPResult)));
  result->nStatus = 1;
  result->pszErrBuf = CPLStrdup(
      CPLSPrintf("%s: network access is off (terraweave --allow-network)", url ? url : ""));
  return result;
}

}  // namespace

void set_network_access(bool allowed) {
  network_allowed = allowed;
  CPLHTTPSetFetchCallback(allowed ? nullptr : refuse_http, nullptr);
  // Only names ending in this extension may be opened through /vsicurl and the other network
  // file systems: none is, so none is opened (a VRT or a GPKG can name a URL inside).
  CPLSetConfigOption("CPL_VSIL_CURL_ALLOWED_EXTENSIONS",
                     allowed ? nullptr : ".terraweave-network-is-off");
  OSRSetPROJEnableNetwork(allowed ? TRUE : FALSE);
}

bool network_access_allowed() {
  return network_allowed;
}

bool import_crs(OGRSpatialReference& srs, const std::string& text) {
  if (text.empty()) return false;
  const char* options[] = {network_allowed ? "ALLOW_NETWORK_ACCESS=YES" : "ALLOW_NETWORK_ACCESS=NO",
                           "ALLOW_FILE_ACCESS=NO", nullptr};
  return srs.SetFromUserInput(text.c_str(), options) == OGRERR_NONE;
}

}  // namespace tw
