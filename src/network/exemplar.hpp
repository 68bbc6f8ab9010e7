#pragma once
// Exemplar networks (docs/networks.md, "Exemplars"): vector lines from any OGR source or an SVG
// file, cut by a polygon when taken from a real map, repaired like other map data (near-junctions
// snapped, duplicates dropped) and noded by GEOS into a planar graph.
#include <cstdint>
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "network/network.hpp"
#include "raster/polygon.hpp"

namespace tw {

struct NetworkSource {
  std::string source{};  // "path[:layer]": any OGR source, or an .svg file
  std::string where{};   // OGR SQL attribute filter
  std::string region{};  // optional polygons "path[:layer]" cutting the lines (a real map)
  // Or the cutting polygons themselves, in the lines' frame (a box given as numbers).
  std::vector<Polygon> region_polygons{};
  double scale = 1.0;    // SVG: metres per SVG unit (y is flipped: north up)
  std::string subject = "exemplar";  // the option or key named in messages
  // An exemplar needs junctions (2); a partial drawing may be one line (1); the map's lines
  // already in a clone's target may be none (0).
  int min_lines = 2;
  // When set, the lines are moved into this CRS (a pipeline's heightfield) as map layers are:
  // a layer without a CRS (or an SVG file) is refused, since it cannot be placed there.
  std::string target_crs_wkt{};
};

struct NetworkLines {
  std::vector<std::vector<Vec2>> lines;  // metres
  std::vector<std::int64_t> fids;        // per line: the feature (SVG: the element's index)
  std::string crs_wkt;                   // of the metres (a geographic source: a local frame)
  std::vector<Polygon> region;           // the cutting polygons, in the same frame
  bool from_polygons = false;            // rings of polygons: shared borders are expected
};

// Throws tw::Error naming the file, the key and the FID at fault (no lines at all, a line with
// fewer than two points, SVG elements that are not lines or paths, a geographic region without
// lines inside).
NetworkLines read_network_lines(const NetworkSource& source, Warnings& warnings);

// The parts of `lines` inside `region` (GEOS intersection, in the lines' frame), each with its
// line's FID; `region` is kept with them (ends on its boundary are cuts).
NetworkLines cut_network_lines(const NetworkLines& lines, const std::vector<Polygon>& region);

// Polygons of an OGR source in the frame of `target_wkt` (the lines' frame).
std::vector<Polygon> read_region_polygons(const std::string& source, const std::string& where,
                                          const std::string& target_wkt,
                                          const std::string& subject);

// The planar graph of the lines: ends within `snap_m` of another end or of another line are
// moved onto it (a warning naming the FID), exact duplicate features dropped (a warning), the
// rest noded by GEOS (crossings become X-junctions, overlaps are dissolved) and chains through
// nodes of degree 2 merged into one edge. Nodes of degree 1 on the region's boundary are marked.
Network build_planar_network(const NetworkLines& lines, double snap_m, const std::string& subject,
                             Warnings& warnings);

// "path[:layer]" split (a colon after the last slash, when the whole text is not a file).
std::pair<std::string, std::string> split_source(const std::string& text);

}  // namespace tw
