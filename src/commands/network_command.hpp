#pragma once
// `terraweave network synthesize|complete|clone` (docs/networks.md): curve networks by example
// over a region, written as a GeoPackage of suggestions and a PNG preview, all or nothing.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "network/exemplar.hpp"
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
  // `--lead long_axis`: growth.lead_bearing from the region's (largest polygon's) long axis, as
  // a pipeline's `lead: long_axis`; "" none. (The other leads read a run's roads and DEM.)
  std::string lead;
  std::filesystem::path out;  // folder: network.gpkg, preview.png
};

struct NetworkCommandResult {
  int exemplar_edges = 0, kept_edges = 0, suggested_edges = 0, nodes = 0;
  NetworkMethod method =
      NetworkMethod::automatic;  // as asked; chosen_network_method(growth) made it
  NetworkGrowthReport growth;
  double growth_ms = 0.0;
  std::optional<double> lead_bearing;  // the compass bearing the exemplar was turned to
};

// Throws tw::Error naming the file, key or FID at fault; writes every file or none.
NetworkCommandResult run_network_command(const NetworkCommand& command);

// The line the CLI prints: the counts, the time and the method asked and chosen ("method
// automatic, chose layout").
std::string network_command_summary(const NetworkCommandResult& result);

// The interactive loop (`terraweave view RUN --serve --exemplar ...`, docs/networks.md,
// "Drawing"): the same reading and growth as the command, called per request.

// The exemplar as the command reads it: lines, snapped (0: 1/1000 of their extent), noded.
Network read_network_exemplar(const NetworkSource& source, double snap, Warnings& warnings);

// Suggestions completing `drawn` (lines in the map's metric CRS, FIDs numbering them in
// messages) over `region`, off `forbidden` cells (the run's avoidance layer): the drawing's parts
// inside the region are kept exactly and grown from, as `network complete` does; GEOS checks the
// result, by options.method (quilt and layout only where the region holds no drawn line). Throws
// tw::Error (lines crossing each other, a degenerate or too large region, quilt or layout asked
// to complete drawn lines) with nothing else done.
std::vector<std::vector<Vec2>> complete_drawing(const Network& exemplar, const NetworkLines& drawn,
                                                const std::vector<Polygon>& region,
                                                const ForbiddenMask* forbidden,
                                                const NetworkGrowthOptions& options,
                                                NetworkGrowthReport* report = nullptr);

// The drawn and accepted lines as the GeoPackage layer "lines" (field origin: "drawn" or
// "suggested") in `crs_wkt`, written to a temporary file and renamed: whole or not at all.
void write_drawn_network(const std::filesystem::path& path, const std::string& crs_wkt,
                         const std::vector<std::vector<Vec2>>& lines,
                         const std::vector<std::string>& origins);

// A drawing saved by write_drawn_network, read back as written (the same doubles, in order):
// layer "lines", its `origin` per line into `origins`. Throws tw::Error naming the file when it
// is no such GeoPackage or its CRS is not `crs_wkt` (it cannot be shown on this run's map).
std::vector<std::vector<Vec2>> read_drawn_network(const std::filesystem::path& path,
                                                  const std::string& crs_wkt,
                                                  std::vector<std::string>& origins);

}  // namespace tw
