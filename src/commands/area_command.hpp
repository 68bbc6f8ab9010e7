#pragma once
// `terraweave area`: a structured shape-pattern (docs/shape-patterns.md) synthesized over every
// polygon of an OGR layer, written as vectors for GIS (a GeoPackage of strokes and instances),
// instance points for engines (CSV) and a PNG preview.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "sketch/hierarchy.hpp"

namespace tw {

struct AreaCommand {
  std::filesystem::path sketch;
  std::optional<std::filesystem::path> shapes_from;  // hybrid: this sketch's shapes on its rows
  std::string polygons;  // OGR source "path" or "path:layer", projected CRS (metres)
  std::string where;     // OGR SQL attribute filter, e.g. "landuse = 'vineyard'"
  double scale = 20.0;   // metres per sketch unit
  // Compass bearing in degrees (clockwise from north) of the sketch's +x axis, or empty for
  // each polygon's long axis.
  std::optional<double> bearing;
  std::uint64_t seed = 1;
  double jitter = 0.5;
  double preview_resolution = 0.5;  // metres per preview pixel (coarser for large extents)
  std::filesystem::path out;        // folder: shapes.gpkg, instances.csv, preview.png
  // Features no shape may touch (roads, rivers, buildings): OGR sources "path[:layer]"; lines
  // are buffered to their width (`width`/OSM tags) or avoid_width metres.
  std::vector<std::string> avoid;
  double avoid_width = 10.0;
  // Metres per cell of the avoidance lattice (over each polygon, sparse: docs/shape-patterns.md);
  // unbounded strokes are written simplified within a quarter of it.
  double resolution = 1.0;
  AnalysisParams analysis;
  // A picture of the sketch's analysis levels (strokes -> shapes -> fibres -> medians -> leads).
  std::optional<std::filesystem::path> analysis_png;
  bool strict = false;  // --strict: any warning fails the command, writing nothing
};

struct AreaCommandResult {
  int polygons = 0, instances = 0, strokes = 0;
  int outside = 0, forbidden = 0, overlapping = 0;  // candidates left out
  double analysis_ms = 0.0, synthesis_ms = 0.0;
};

// Throws tw::Error naming the file, layer or FID at fault; writes every file or none.
AreaCommandResult run_area_command(const AreaCommand& command);

}  // namespace tw
