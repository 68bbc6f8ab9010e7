#pragma once
// `terraweave network synthesize|complete|clone` (docs/networks.md): curve networks by example
// over a region, written as a GeoPackage of suggestions and a PNG preview, all or nothing.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "network/growth.hpp"

namespace tw {

struct NetworkCommand {
  std::string mode = "synthesize";  // synthesize, complete, clone
  std::string exemplar;             // OGR "path[:layer]" or .svg (synthesize, complete)
  std::string exemplar_where;       // OGR SQL filter on the exemplar's layer
  std::string exemplar_region;      // polygons cutting the exemplar (a real map)
  double scale = 1.0;               // SVG: metres per unit
  // "minx,miny,maxx,maxy" in the network's CRS, or OGR polygons "path[:layer]"
  std::string region;
  std::string partial;             // complete: the user's lines "path[:layer]", kept as drawn
  std::string map;                 // clone: the map lines "path[:layer]"
  std::string source_region;       // clone: polygons whose lines are the exemplar
  std::string target_region;       // clone: polygons grown into (what is there is kept)
  std::vector<std::string> avoid;  // OGR sources no curve may enter (lines buffered)
  double avoid_width = 10.0;
  double snap = 0.0;  // exemplar repair: ends within it are joined; 0 = 1e-3 of its extent
  NetworkGrowthOptions growth;
  std::filesystem::path out;  // folder: network.gpkg, preview.png
};

struct NetworkCommandResult {
  int exemplar_edges = 0, kept_edges = 0, suggested_edges = 0, nodes = 0;
  NetworkGrowthReport growth;
  double growth_ms = 0.0;
};

// Throws tw::Error naming the file, key or FID at fault; writes every file or none.
NetworkCommandResult run_network_command(const NetworkCommand& command);

}  // namespace tw
