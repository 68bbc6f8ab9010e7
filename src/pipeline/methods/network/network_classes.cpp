#include "pipeline/methods/network/network_classes.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/height_sampler.hpp"
#include "network/check.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"
#include "network/partial.hpp"
#include "pipeline/lead_direction.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/rasterize.hpp"

namespace tw::detail {

namespace {

std::vector<Polygon> region_of(const NetworkClassConfig& n, const Heightfield& heightfield,
                               const std::string& key, Warnings& warnings) {
  if (n.region_box) {
    const auto& b = *n.region_box;
    return {{{{b[0], b[1]}, {b[2], b[1]}, {b[2], b[3]}, {b[0], b[3]}}}};
  }
  std::vector<Polygon> out;
  try {
    for (PolygonFeature& f :
         read_polygon_features(VectorSource{n.region_source, n.region_layer, n.region_where},
                               heightfield, key, warnings))
      out.emplace_back(f.rings.begin(), f.rings.end());
  } catch (const Error& error) {
    fail("{}: {}", key, error.what());
  }
  if (out.empty()) fail("{}: no region polygon lies on the heightfield", key);
  return out;
}

// Cells no edge may enter: the existing features, the polygons the other methods reserve (the
// area classes': their shape-patterns come later and fill them) and the lines of the classes before
// `c`, each widened by this class's width (so that the footprints do not overlap), on a grid over
// the region of at most 4096 cells a side and no finer than a metre.
ForbiddenMask forbidden_mask(const std::vector<FeatureClassConfig>& classes, std::size_t c,
                             const std::vector<Polygon>& region, const ExistingFeatures& existing,
                             const std::vector<Polygon>& reserved,
                             const std::vector<std::vector<LineFeature>>& lines) {
  ForbiddenMask mask;
  mask.grid = forbidden_mask_grid(region);
  const double own = classes[c].width;
  std::vector<std::vector<Vec2>> avoided = existing.lines;
  std::vector<double> widths;
  for (double w : existing.line_widths) widths.push_back(w + own);
  for (std::size_t other = 0; other < c; ++other)
    for (const LineFeature& line : lines[other]) {
      avoided.push_back(line.points);
      if (line.closed && !line.points.empty()) avoided.back().push_back(line.points.front());
      widths.push_back(line.width + own);
    }
  // Classes after `c` that are read (not grown) are there already too.
  for (std::size_t other = c + 1; other < classes.size(); ++other) {
    if (lines_made_by_a_method(classes[other])) continue;
    for (const LineFeature& line : lines[other]) {
      avoided.push_back(line.points);
      if (line.closed && !line.points.empty()) avoided.back().push_back(line.points.front());
      widths.push_back(line.width + own);
    }
  }
  const Window whole = Window::whole(mask.grid);
  mask.cells = Raster<std::uint8_t>(mask.grid.width, mask.grid.height);
  burn_polygons(existing.polygons, mask.grid, whole, mask.cells, 1);
  burn_polygons(reserved, mask.grid, whole, mask.cells, 1);
  burn_buffered_lines(avoided, widths, mask.grid, whole, mask.cells, 1);
  return mask;
}

// The user's lines in the heightfield's CRS, kept as drawn (network/partial.hpp).
Network partial_network(const NetworkClassConfig& n, const std::vector<Polygon>& region,
                        const Heightfield& heightfield, const std::string& key,
                        Warnings& warnings) {
  NetworkLines lines;
  try {
    lines = read_network_lines({.source = n.partial,
                                .scale = n.scale,
                                .subject = key,
                                .min_lines = 1,
                                .target_crs_wkt = heightfield.crs_wkt},
                               warnings);
  } catch (const Error& error) {
    const std::string what = error.what();
    if (what.starts_with(key)) throw;
    fail("{}: {}", key, what);
  }
  return tw::partial_network(lines, region, key, n.partial, warnings);
}

// The compass bearing the exemplar is turned to: the lead over the region's largest polygon (the
// first of equal ones), or none without a lead. A `nearest_road` without roads and `contours`
// over flat or nodata terrain follow the long axis, with a warning.
std::optional<double> lead_bearing(const NetworkClassConfig& n, const std::vector<Polygon>& region,
                                   const std::vector<const LineFeature*>& roads,
                                   HeightSampler& heights, const std::string& key,
                                   Warnings& warnings) {
  if (!n.lead) return std::nullopt;
  if (*n.lead == Lead::bearing) return n.lead_bearing_deg;
  const LeadAngle lead =
      lead_angle(*n.lead, n.lead_bearing_deg, lead_polygon(region), roads, heights);
  if (lead.fell_back)
    warnings.add(*n.lead == Lead::nearest_road ? "network_no_road" : "network_flat", key + ".lead",
                 std::nullopt,
                 *n.lead == Lead::nearest_road
                     ? "no road in the run: the network follows the region's long axis"
                     : "flat or nodata terrain over the region: the network follows its long axis");
  return compass_degrees(lead.radians);
}

}  // namespace

void grow_network_classes(const std::vector<FeatureClassConfig>& classes,
                          const HeightfieldSource& source, const Heightfield& heightfield,
                          const ExistingFeatures& existing, const std::vector<Polygon>& reserved,
                          std::vector<std::vector<LineFeature>>& lines,
                          std::vector<std::optional<NetworkClassReport>>& reports,
                          Warnings& warnings) {
  HeightSampler sampler(source);
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const FeatureClassConfig& fc = classes[c];
    const NetworkClassConfig* network = method_options<NetworkClassConfig>(fc, kNetworkMethodName);
    if (!network) continue;
    const NetworkClassConfig& n = *network;
    const std::string key = "features." + fc.name + ".network";
    NetworkLines exemplar_lines;
    Network exemplar;
    try {
      exemplar_lines = read_network_lines({.source = n.exemplar,
                                           .where = n.exemplar_where,
                                           .region = n.exemplar_region,
                                           .scale = n.scale,
                                           .subject = key + ".exemplar"},
                                          warnings);
      Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
      for (const auto& l : exemplar_lines.lines)
        for (Vec2 p : l)
          lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
          hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      // Ends within 1/1000 of the exemplar's extent are joined, as the command does.
      exemplar = build_planar_network(exemplar_lines, 1e-3 * std::max(hi.x - lo.x, hi.y - lo.y),
                                      key + ".exemplar", warnings);
    } catch (const Error& error) {
      const std::string what = error.what();
      if (what.starts_with(key + ".exemplar")) throw;
      fail("{}.exemplar: {}", key, what);
    }
    const std::vector<Polygon> region = region_of(n, heightfield, key + ".region", warnings);
    std::optional<Network> partial;
    if (!n.partial.empty())
      partial = partial_network(n, region, heightfield, key + ".partial", warnings);
    std::optional<ForbiddenMask> forbidden;
    if (n.avoid) forbidden = forbidden_mask(classes, c, region, existing, reserved, lines);
    forbid_nodata_cells(forbidden, region, source.grid(),
                        [&](const Window& w) { return source.read(w); });
    NetworkGrowthOptions options;
    options.seed = n.seed;
    // The roads there now: read ones, and an earlier network class's grown lanes.
    options.lead_bearing =
        lead_bearing(n, region, road_lines(classes, lines), sampler, key, warnings);
    options.clearance = n.clearance;
    options.snap = n.snap;
    options.candidates = n.candidates;
    options.method = network_method_named(n.method);
    NetworkGrowthReport report;
    const auto t0 = std::chrono::steady_clock::now();
    Network grown;
    try {
      grown = grow_network(exemplar, region, forbidden ? &*forbidden : nullptr,
                           partial ? &*partial : nullptr, options, &report);
    } catch (const Error& error) {
      fail("{}.region: {}", key, error.what());
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    // The safety net: GEOS checks the lines before anything is built on them.
    const NetworkCheck check = check_network(grown, region, forbidden ? &*forbidden : nullptr);
    if (check.total() != 0)
      fail("{}: {} crossings, {} outside the region, {} through avoided cells (a growth bug): {}",
           key, check.crossings, check.outside, check.forbidden, check.first);
    for (const NetworkEdge& e : grown.edges) {
      LineFeature& feature = lines[c].emplace_back();
      feature.fid = std::int64_t(lines[c].size());
      feature.points = e.points;
      // A river's points run downstream: it drains from its higher end.
      if (fc.kind == FeatureKind::river &&
          sampler.bilinear(feature.points.front()) < sampler.bilinear(feature.points.back()))
        std::reverse(feature.points.begin(), feature.points.end());
      feature.width = fc.width;
      feature.source = n.exemplar;
    }
    NetworkClassReport& r = reports.at(c).emplace();
    r.exemplar = n.exemplar;
    r.method = network_method_name(options.method);
    if (n.lead) {
      r.lead = std::string(lead_name(*n.lead));
      r.lead_bearing_deg = *options.lead_bearing;
    }
    r.chosen = chosen_network_method(report);
    r.exemplar_edges = int(exemplar.edges.size());
    r.lines = int(lines[c].size());
    r.kept = int(std::count_if(grown.edges.begin(), grown.edges.end(),
                               [](const NetworkEdge& e) { return e.kept; }));
    r.placed = report.placed;
    r.snapped = report.snapped;
    r.t_junctions = report.t_junctions;
    r.boundary_ends = report.boundary_ends;
    r.pruned = report.pruned;
    r.rejected_crossing = report.rejected_crossing;
    r.rejected_region = report.rejected_region;
    r.rejected_forbidden = report.rejected_forbidden;
    if (lines[c].empty())
      warnings.add("empty_class", "features." + fc.name, std::nullopt,
                   "the network grew no line in its region");
    logger().info("{}: {} lines ({} placed, {} snapped, {} T-junctions) in {:.0f} ms by {}", key,
                  lines[c].size(), report.placed, report.snapped, report.t_junctions, ms, r.chosen);
  }
}

}  // namespace tw::detail
