// Fuzz target: the exemplar reader of curve networks (docs/networks.md, "Exemplars") on an
// arbitrary file: an SVG drawing when the bytes start (after blanks) with '<', else whatever OGR
// recognizes (GeoJSON lines and polygons). What read_network_lines accepts has lines of at least
// two finite points with one FID each, and build_planar_network makes of it a graph whose edges
// join existing nodes; what it refuses is a tw::Error.
#include <unistd.h>

#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/warnings.hpp"
#include "fuzz_support.hpp"
#include "network/exemplar.hpp"
#include "offline_gdal.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  tw::fuzz::silence_logging();
  tw::fuzz::start_offline_gdal();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::size_t first = 0;
  while (first < size && std::isspace(data[first])) ++first;
  const bool svg = first < size && data[first] == '<';
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() /
      ("terraweave-fuzz-network-" + std::to_string(::getpid()) + (svg ? ".svg" : ".geojson"));
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  tw::Warnings warnings;  // repairs are expected answers, like errors
  try {
    const tw::NetworkLines lines =
        tw::read_network_lines({.source = path.string(), .scale = 0.5}, warnings);
    if (lines.lines.size() != lines.fids.size()) tw::fuzz::broken_promise("a line without FID");
    for (const auto& line : lines.lines) {
      if (line.size() < 2) tw::fuzz::broken_promise("a line with fewer than 2 points");
      for (const tw::Vec2& p : line) {
        tw::fuzz::expect_finite(p.x, "vertex x");
        tw::fuzz::expect_finite(p.y, "vertex y");
      }
    }
    const tw::Network network = tw::build_planar_network(lines, 0.01, "fuzz", warnings);
    const int nodes = int(network.nodes.size());
    for (const tw::NetworkEdge& e : network.edges) {
      if (e.points.size() < 2) tw::fuzz::broken_promise("an edge with fewer than 2 points");
      if (e.from < 0 || e.from >= nodes || e.to < 0 || e.to >= nodes)
        tw::fuzz::broken_promise("an edge joining a node that does not exist");
    }
  } catch (const tw::Error&) {
    // Refused with a message naming the file, the element or the FID: expected for bad input.
  }
  std::filesystem::remove(path);
  return 0;
}
