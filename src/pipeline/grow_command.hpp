#pragma once
// `terraweave grow`: FloralSurf ornaments (docs/ornaments.md) grown over a region of a DEM,
// written as lines for GIS (a GeoPackage with heights) and a PNG preview over the hillshade.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "pipeline/grow_config.hpp"

namespace tw {

// The growth's knobs (resolution, seed, contour, first_fit, trials, max_ornaments,
// coverage_radius, clearance) are those of a pipeline class's `grow:` block.
struct GrowCommand : GrowSettings {
  std::string dem;  // any raster GDAL reads (warped to a metric CRS as for `run`)
  // "minx,miny,maxx,maxy" in the DEM's (metric) CRS, or an OGR polygon source "path[:layer]"
  std::string region;
  std::string where;               // OGR SQL attribute filter on the region's polygons
  std::filesystem::path element;   // element set JSON (samples/ornaments/*.json)
  std::vector<std::string> avoid;  // OGR sources no ornament may enter (lines buffered)
  double avoid_width = 10.0;
  double resolution = 0.0;  // metres per mesh vertex; 0 = the DEM's own
  std::uint64_t seed = 1;
  bool contour = false;    // align elements to the contour direction instead of their growth frame
  bool first_fit = false;  // the greedy variant (paper's Figure 6), for comparison
  int trials = 10;
  int max_ornaments = 32;
  double coverage_radius = 0.0;  // metres; 0 = half the element set's scale
  std::filesystem::path out;     // folder: ornaments.gpkg, preview.png
};

struct GrowCommandResult {
  int ornaments = 0, elements = 0, lines = 0;
  int rejected_crossing = 0, rejected_forbidden = 0, rejected_untraceable = 0;
  int width = 0, height = 0;  // the mesh's vertices a side
  double coverage = 0.0, coverage_radius = 0.0;
  double growth_ms = 0.0;
};

// Throws tw::Error naming the file, key or FID at fault; writes every file or none.
GrowCommandResult run_grow_command(const GrowCommand& command);

}  // namespace tw
