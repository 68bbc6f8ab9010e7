#pragma once
// `terraweave grow`: FloralSurf ornaments (docs/ornaments.md) grown over a region of a DEM,
// written as lines for GIS (a GeoPackage with heights) and a PNG preview over the hillshade.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "ornament/crossings.hpp"
#include "pipeline/grow_config.hpp"

namespace tw {

// The growth's knobs (resolution, seed, contour, first_fit, trials, max_ornaments,
// coverage_radius, clearance) are those of a pipeline class's `grow:` block: GrowSettings's own
// members, never redeclared here (a member of the same name would shadow the one
// run_grow_command passes on, and its option would change nothing).
struct GrowCommand : GrowSettings {
  std::string dem;  // any raster GDAL reads (warped to a metric CRS as for `run`)
  // "minx,miny,maxx,maxy" in the DEM's (metric) CRS, or an OGR polygon source "path[:layer]"
  std::string region;
  std::string where;               // OGR SQL attribute filter on the region's polygons
  std::filesystem::path element;   // element set JSON (samples/ornaments/*.json)
  std::vector<std::string> avoid;  // OGR sources no ornament may enter (lines buffered)
  double avoid_width = 10.0;
  std::filesystem::path out;     // folder: ornaments.gpkg, preview.png
  bool strict = false;           // --strict: any warning fails the command, writing nothing
};

struct GrowCommandResult {
  int ornaments = 0, elements = 0, lines = 0;
  int rejected_crossing = 0, rejected_forbidden = 0, rejected_untraceable = 0;
  int rejected_footprint = 0;  // candidates onto an avoided footprint (exact, vector space)
  CrossingCounts crossings;    // of the lines written: all 0 (or the command fails)
  int width = 0, height = 0;  // the mesh's vertices a side
  double coverage = 0.0, coverage_radius = 0.0;
  double growth_ms = 0.0;
};

// Throws tw::Error naming the file, key or FID at fault; writes every file or none.
GrowCommandResult run_grow_command(const GrowCommand& command);

}  // namespace tw
