#pragma once
// What a run's inputs may reach (docs/robustness.md, "Network and files"). Network access is off
// unless the user allows it (--allow-network): a path that would make GDAL send a request is
// refused before GDAL sees it, and GDAL's and PROJ's own switches stay off as a second line of
// defence (a local VRT that points at a URL). CRS text never names a file to read.
#include <string>
#include <string_view>

class OGRSpatialReference;

namespace tw {

// The part of `path` that reaches the network: a GDAL network file system ("/vsicurl",
// "/vsis3", ..., also nested as in /vsizip//vsicurl/...), a URL scheme ("https:") or a
// server driver's connection string ("pg:" for "PG:host=..."); "" for a local path.
std::string network_part_of(std::string_view path);

// Throws tw::Error "<key>: <path> reaches the network (<part>); ..." unless allowed.
void check_input_path(const std::string& path, const std::string& key, bool allow_network);

// Turns GDAL's network file systems, PROJ's grid downloads and URL CRSs on or off for the
// process (GDAL's configuration is process-wide). Off until set.
void set_network_access(bool allowed);
bool network_access_allowed();

// OGRSpatialReference::SetFromUserInput (WKT, "EPSG:n", a PROJ string, ...) without file
// access and, unless network access is on, without network access. False when not a CRS.
bool import_crs(OGRSpatialReference& srs, const std::string& text);

}  // namespace tw
