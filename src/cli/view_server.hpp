#pragma once
// `terraweave view RUN --serve [PORT]` (docs/cli.md, docs/networks.md "Drawing"): the run's page
// folder served on 127.0.0.1 by cpp-httplib; with an exemplar, also the drawing page
// (/network.html) whose completion requests call the network library in this process and whose
// accepted lines are saved as a GeoPackage. A shell over library calls, like the rest of cli/.
#include <cstdint>
#include <filesystem>
#include <string>

#include "commands/view.hpp"

namespace tw {

struct ViewServeOptions {
  int port = 8000;             // 0: any free port (printed)
  std::filesystem::path page;  // the written view page; its folder is served
  // The drawing page, when `exemplar` is set.
  std::string exemplar, where;
  double scale = 1.0;  // SVG: metres per unit
  std::uint64_t seed = 1;
  std::filesystem::path save = "drawn_network.gpkg";
};

// Serves until the process is stopped (Ctrl-C, a signal); throws tw::Error when the port cannot
// be bound or the exemplar cannot be read, before anything is served.
void serve_view(const ViewOptions& view, const ViewServeOptions& options);

}  // namespace tw
