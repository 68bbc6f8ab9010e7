#pragma once
// Curve networks grown by example (docs/networks.md, "Growth"): a deterministic frontier of open
// stubs (a node and a heading); each stub takes a whole exemplar edge (a piece), turned rigidly
// to its heading, whose end becomes a junction with the exemplar's degree and outgoing angles,
// or is snapped onto the network (T-junctions, closed cells). Pieces that would cross anything,
// leave the region, enter a forbidden cell or come closer than the clearance are rejected; the
// order in which pieces are tried follows the statistics still missing (degree, length and
// bearing histograms), with seeded ties.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>
#include <vector>

#include "core/grid.hpp"
#include "network/network.hpp"
#include "raster/polygon.hpp"

namespace tw {

// How a network is made (docs/networks.md): `quilt`, exemplar blocks chosen by how their lines
// agree in the overlaps and stitched across the seams ("Quilting"); `grow`, whole exemplar pieces
// attached at a frontier of open ends ("Growth"); `layout`, the exemplar's long strokes copied
// first and growth from their junctions ("Layout"; growth alone when it has none).
// `automatic`: over an empty region each of them, and the one meeting the most quality targets
// on the exemplar's statistics; growth to complete a partial network (it grows from the drawn
// ends).
enum class NetworkMethod { automatic, grow, quilt, layout };

// The methods as the command's `--method` and the pipeline key `network.method` name them, in
// the enum's order.
inline constexpr std::array<std::string_view, 4> kNetworkMethodNames = {"automatic", "growth",
                                                                        "quilt", "layout"};
// The method named so; anything else is `automatic` (names are checked where they are read).
inline NetworkMethod network_method_named(std::string_view name) {
  for (std::size_t i = 0; i < kNetworkMethodNames.size(); ++i)
    if (kNetworkMethodNames[i] == name) return NetworkMethod(i);
  return NetworkMethod::automatic;
}

inline std::string_view network_method_name(NetworkMethod method) {
  return kNetworkMethodNames[std::size_t(method)];
}

// Whether a method completes a partial network: growth, and `automatic` (growth there). The quilt
// and the layout lay out the whole region and are refused where lines are drawn, naming the key.
inline bool network_method_completes(NetworkMethod method) {
  return method == NetworkMethod::automatic || method == NetworkMethod::grow;
}

struct NetworkGrowthOptions {
  std::uint64_t seed = 1;
  // Compass degrees: the exemplar's main bearing is turned to it (absent: kept as drawn).
  std::optional<double> lead_bearing{};
  double clearance = 0.0;  // metres between unrelated curves; 0: 6 % of the median edge length
  double snap = 0.0;       // metres an end is pulled onto the network; 0: 35 % of the median
  int candidates = 12;     // pieces tried per stub
  // Pieces are strokes (edges chained across junctions where a line goes on nearly straight,
  // their side junctions kept) rather than single edges.
  bool strokes = true;
  NetworkMethod method = NetworkMethod::automatic;
};

// Cells no curve may enter (non-zero), on any grid in the region's frame.
struct ForbiddenMask {
  GridSpec grid;
  Raster<std::uint8_t> cells;
};

// The grid a forbidden mask of `region` is drawn on: its bounding box and a cell more on every
// side, square cells no finer than a metre and at most 4096 a side (memory follows the region).
GridSpec forbidden_mask_grid(const std::vector<Polygon>& region);

// Forbids every cell of `mask` that overlaps a NaN cell of a heightfield (its nodata: no height
// to build a line on) on `heights_grid`, in the region's frame; `read_heights` gives the heights
// of a window of that grid (the part under the mask only is read). An absent mask is made over
// `region` first, and left absent when no nodata cell lies under it.
void forbid_nodata_cells(std::optional<ForbiddenMask>& mask, const std::vector<Polygon>& region,
                         const GridSpec& heights_grid,
                         const std::function<Raster<float>(const Window&)>& read_heights);

struct NetworkGrowthReport {
  int seeds = 0, stubs = 0, placed = 0, snapped = 0, t_junctions = 0, boundary_ends = 0;
  int rejected_crossing = 0, rejected_region = 0, rejected_forbidden = 0, pruned = 0;
  bool quilted = false;   // the network is the quilt (asked for, or `automatic` chose it)
  bool laid_out = false;  // the exemplar's long strokes were laid out (asked for, or chosen)
};

// The method that made a grown network, as kNetworkMethodNames names it: `quilt`, `layout`, or
// `growth` (also `layout` on an exemplar without long strokes, which is growth byte for byte);
// never `automatic`: what it kept. Reported by the command and in report.json (issue #20).
inline std::string_view chosen_network_method(const NetworkGrowthReport& report) {
  return network_method_name(report.quilted    ? NetworkMethod::quilt
                             : report.laid_out ? NetworkMethod::layout
                                               : NetworkMethod::grow);
}

// The network grown over `region` (polygons, holes allowed). `partial`, when given, is kept as
// drawn (its edges come out with kept = true and their points unchanged) and completed: growth
// starts from its dangling ends. Throws tw::Error for an exemplar without junctions or pieces,
// a degenerate region or one too large for the exemplar's scale. Same inputs, same bytes.
Network grow_network(const Network& exemplar, const std::vector<Polygon>& region,
                     const ForbiddenMask* forbidden, const Network* partial,
                     const NetworkGrowthOptions& options, NetworkGrowthReport* report = nullptr);

// The most cells (region area / median edge length²) a growth takes on: about 10⁷ junctions.
inline constexpr double kMaxNetworkCells = 2.0e7;

}  // namespace tw
