#include "commands/network_command.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <utility>

#include <fmt/format.h>

#include "commands/detail/vector_inputs.hpp"
#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_guard.hpp"
#include "core/warnings.hpp"
#include "geo/geopackage.hpp"
#include "geo/heightfield.hpp"
#include "network/check.hpp"
#include "network/exemplar.hpp"
#include "network/partial.hpp"
#include "network/preview.hpp"
#include "pipeline/lead_direction.hpp"
#include "pipeline/version.hpp"
#include "raster/rasterize.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw {

namespace {

std::optional<std::vector<Polygon>> box_region(const std::string& text, const std::string& key) {
  std::array<double, 4> v{};
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4)
    return std::nullopt;
  if (!(v[0] < v[2] && v[1] < v[3]))
    fail("{} {}: a degenerate (zero-area) box: expected minx,miny,maxx,maxy with min < max", key,
         text);
  return std::vector<Polygon>{{{{v[0], v[1]}, {v[2], v[1]}, {v[2], v[3]}, {v[0], v[3]}}}};
}

std::vector<Polygon> region_of(const std::string& text, const std::string& key,
                               const std::string& crs_wkt) {
  if (text.empty()) fail("{} is required", key);
  if (auto box = box_region(text, key)) return *box;
  return read_region_polygons(text, "", crs_wkt, key);
}

// The exemplar's repair distance: `snap`, or (0) 1/1000 of the lines' extent.
double repair_snap(const NetworkLines& lines, double snap) {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (const auto& l : lines.lines)
    for (Vec2 p : l)
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)},
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  return snap > 0.0 ? snap : 1e-3 * std::max(hi.x - lo.x, hi.y - lo.y);
}

// Snapped (within `snap`, 0: 1/1000 of the lines' extent) and noded.
Network exemplar_network(const NetworkLines& lines, double snap, Warnings& warnings) {
  return build_planar_network(lines, repair_snap(lines, snap), "--exemplar", warnings);
}

ForbiddenMask forbidden_mask(const NetworkCommand& c, const std::vector<Polygon>& region,
                             const std::string& crs_wkt, Warnings& warnings) {
  ForbiddenMask mask;
  mask.grid = forbidden_mask_grid(region);
  Heightfield frame;
  frame.grid = mask.grid;
  frame.crs_wkt = crs_wkt;
  frame.source = "network region";
  const AvoidanceInputs avoided =
      detail::avoided_features(frame, c.avoid, c.avoid_width, "network.avoid", warnings);
  const Window whole = Window::whole(mask.grid);
  burn_polygons(avoided.polygons, mask.grid, whole, mask.cells, 1);
  burn_buffered_lines(avoided.lines, avoided.line_widths, mask.grid, whole, mask.cells, 1);
  return mask;
}

// What made network.gpkg, on each of its layers (docs/networks.md, "Outputs"): the command, its
// inputs as given, the method asked and the one chosen, the seed and the summary's counts (not
// its time: the same seed writes the same bytes).
std::vector<std::pair<std::string, std::string>> network_provenance(const NetworkCommand& c,
                                                                    const NetworkCommandResult& r) {
  std::vector<std::pair<std::string, std::string>> items = {
      {"TERRAWEAVE_VERSION", kTerraweaveVersion},
      {"TERRAWEAVE_COMMAND", "network " + c.mode},
      {"TERRAWEAVE_NETWORK_METHOD", std::string(network_method_name(r.method))},
      {"TERRAWEAVE_NETWORK_CHOSEN", std::string(chosen_network_method(r.growth))},
      {"TERRAWEAVE_SEED", std::to_string(c.growth.seed)}};
  if (!c.lead.empty()) items.emplace_back("TERRAWEAVE_LEAD", c.lead);
  // Exact (17 digits): `--lead-bearing` with it grows the same lines.
  if (r.lead_bearing)
    items.emplace_back("TERRAWEAVE_LEAD_BEARING", fmt::format("{:.17g}", *r.lead_bearing));
  const std::pair<const char*, const std::string*> inputs[] = {
      {"TERRAWEAVE_EXEMPLAR", &c.exemplar},
      {"TERRAWEAVE_PARTIAL", &c.partial},
      {"TERRAWEAVE_MAP", &c.map},
      {"TERRAWEAVE_REGION", &c.region},
      {"TERRAWEAVE_SOURCE_REGION", &c.source_region},
      {"TERRAWEAVE_TARGET_REGION", &c.target_region}};
  for (const auto& [name, value] : inputs)
    if (!value->empty()) items.emplace_back(name, *value);
  const std::pair<const char*, int> counts[] = {{"TERRAWEAVE_SUGGESTED_EDGES", r.suggested_edges},
                                                {"TERRAWEAVE_KEPT_EDGES", r.kept_edges},
                                                {"TERRAWEAVE_NODES", r.nodes},
                                                {"TERRAWEAVE_EXEMPLAR_EDGES", r.exemplar_edges},
                                                {"TERRAWEAVE_SEEDS", r.growth.seeds},
                                                {"TERRAWEAVE_T_JUNCTIONS", r.growth.t_junctions},
                                                {"TERRAWEAVE_SNAPPED", r.growth.snapped}};
  for (const auto& [name, count] : counts) items.emplace_back(name, std::to_string(count));
  return items;
}

void write_geopackage(const std::filesystem::path& path, const std::string& crs_wkt,
                      const Network& grown, const NetworkLines* kept,
                      const std::vector<std::pair<std::string, std::string>>& provenance) {
  GeoPackageWriter gpkg = create_geopackage(path, crs_wkt);
  const std::vector<int> degree = grown.degrees();
  {
    OGRLayer* layer = &gpkg.create_layer("suggestions", wkbLineString);
    gpkg.add_fields(*layer,
                    {{"from_node", OFTInteger}, {"to_node", OFTInteger}, {"length_m", OFTReal}});
    gpkg.set_metadata(*layer, provenance);
    if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
    GIntBig fid = 1;
    for (const NetworkEdge& e : grown.edges) {
      if (e.kept) continue;
      OGRFeature f(layer->GetLayerDefn());
      f.SetFID(fid++);
      f.SetField("from_node", e.from);
      f.SetField("to_node", e.to);
      f.SetField("length_m", polyline_length(e.points));
      OGRLineString ls;
      for (Vec2 p : e.points) ls.addPoint(p.x, p.y);
      f.SetGeometry(&ls);
      if (layer->CreateFeature(&f) != OGRERR_NONE) fail("{}: cannot write", path.string());
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  }
  {
    OGRLayer* layer = &gpkg.create_layer("nodes", wkbPoint);
    gpkg.add_fields(*layer, {{"degree", OFTInteger}, {"on_boundary", OFTInteger}});
    gpkg.set_metadata(*layer, provenance);
    if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
    for (std::size_t n = 0; n < grown.nodes.size(); ++n) {
      OGRFeature f(layer->GetLayerDefn());
      f.SetFID(GIntBig(n));
      f.SetField("degree", degree[n]);
      f.SetField("on_boundary", grown.on_boundary.empty() ? 0 : int(grown.on_boundary[n]));
      OGRPoint p(grown.nodes[n].x, grown.nodes[n].y);
      f.SetGeometry(&p);
      if (layer->CreateFeature(&f) != OGRERR_NONE) fail("{}: cannot write", path.string());
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  }
  if (kept) {
    OGRLayer* layer = &gpkg.create_layer("kept", wkbLineString);
    gpkg.add_fields(*layer, {{"source_fid", OFTInteger64}});
    gpkg.set_metadata(*layer, provenance);
    if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
    for (std::size_t i = 0; i < kept->lines.size(); ++i) {
      OGRFeature f(layer->GetLayerDefn());
      f.SetFID(GIntBig(i + 1));
      f.SetField("source_fid", GIntBig(kept->fids[i]));
      OGRLineString ls;
      for (Vec2 p : kept->lines[i]) ls.addPoint(p.x, p.y);
      f.SetGeometry(&ls);
      if (layer->CreateFeature(&f) != OGRERR_NONE) fail("{}: cannot write", path.string());
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  }
}

}  // namespace

NetworkCommandResult run_network_command(const NetworkCommand& c) {
  const std::string cmd = "network " + c.mode;
  if (c.mode != "synthesize" && c.mode != "complete" && c.mode != "clone")
    fail("network: unknown mode '{}' (synthesize, complete, clone)", c.mode);
  if (c.out.empty()) fail("{}: --out is required", cmd);
  if (!c.lead.empty() && c.lead != "long_axis")
    fail(
        "{}: --lead {}: the command follows long_axis only (nearest_road and contours read a "
        "run's roads and heightfield: give a pipeline's network class `lead: {}`)",
        cmd, c.lead, c.lead);
  if (!c.lead.empty() && c.growth.lead_bearing)
    fail("{}: give --lead or --lead-bearing, not both", cmd);
  if (c.mode == "complete" && !network_method_completes(c.growth.method))
    fail(
        "{}: --method {} cannot complete a drawing: completing is growth from its ends (use "
        "growth or automatic)",
        cmd, network_method_name(c.growth.method));
  std::vector<std::filesystem::path> inputs;
  for (const std::string& s : {c.exemplar, c.partial, c.map})
    if (!s.empty()) inputs.push_back(split_source(s).first);
  require_safe_output(c.out, true, {.command = "network", .option = "--out", .inputs = inputs});
  Warnings warnings;
  NetworkSource exemplar_source;
  std::optional<NetworkLines> kept_lines;
  std::vector<Polygon> region;
  NetworkLines exemplar_lines;
  if (c.mode == "clone") {
    if (c.map.empty()) fail("{}: --map is required", cmd);
    if (c.source_region.empty()) fail("{}: --source-region is required", cmd);
    if (c.target_region.empty()) fail("{}: --target-region is required", cmd);
    // A box is the source's polygon itself (it would be opened as a file name otherwise).
    const std::optional<std::vector<Polygon>> source_box =
        box_region(c.source_region, "--source-region");
    exemplar_lines =
        read_network_lines({.source = c.map,
                            .where = c.exemplar_where,
                            .region = source_box ? "" : c.source_region,
                            .region_polygons = source_box.value_or(std::vector<Polygon>{}),
                            .scale = c.scale,
                            .subject = "--map (in --source-region)"},
                           warnings);
    region = region_of(c.target_region, "--target-region", exemplar_lines.crs_wkt);
    // What is already in the target is kept: the map's lines inside it, if any.
    kept_lines = read_network_lines({.source = c.map,
                                     .where = c.exemplar_where,
                                     .region_polygons = region,
                                     .scale = c.scale,
                                     .subject = "--map (in --target-region)",
                                     .min_lines = 0},
                                    warnings);
    if (kept_lines->lines.empty()) kept_lines.reset();  // the target is grown from scratch
  } else {
    if (c.exemplar.empty()) fail("{}: --exemplar is required", cmd);
    exemplar_lines = read_network_lines({.source = c.exemplar,
                                         .where = c.exemplar_where,
                                         .region = c.exemplar_region,
                                         .scale = c.scale,
                                         .subject = "--exemplar"},
                                        warnings);
    region = region_of(c.region, "--region", exemplar_lines.crs_wkt);
    if (c.mode == "complete") {
      if (c.partial.empty()) fail("{}: --partial is required", cmd);
      NetworkLines partial = read_network_lines(
          {.source = c.partial, .scale = c.scale, .subject = "--partial", .min_lines = 1},
          warnings);
      kept_lines = std::move(partial);
    }
  }
  const Network exemplar = exemplar_network(exemplar_lines, c.snap, warnings);
  std::optional<Network> partial;
  if (kept_lines && c.mode == "clone")  // map data: noded and repaired as the exemplar is
    partial = kept_map_network(*kept_lines, repair_snap(exemplar_lines, c.snap),
                               "--map (in --target-region)", warnings);
  else if (kept_lines)  // the user's drawing: kept exactly, never crossing itself
    partial = partial_network(*kept_lines, region, "--partial", c.partial, warnings);
  if (partial && c.mode == "clone" && !network_method_completes(c.growth.method))
    fail(
        "{}: --method {}: --target-region {} holds {} lines of --map, and completing them is "
        "growth from their ends (use growth or automatic, or a target without lines)",
        cmd, network_method_name(c.growth.method), c.target_region, kept_lines->lines.size());
  std::optional<ForbiddenMask> forbidden;
  if (!c.avoid.empty()) forbidden = forbidden_mask(c, region, exemplar_lines.crs_wkt, warnings);

  NetworkGrowthOptions growth = c.growth;
  if (c.lead == "long_axis")
    growth.lead_bearing = compass_degrees(long_axis_bearing(lead_polygon(region)));

  NetworkCommandResult result;
  const auto t0 = std::chrono::steady_clock::now();
  Network grown;
  try {
    grown = grow_network(exemplar, region, forbidden ? &*forbidden : nullptr,
                         partial ? &*partial : nullptr, growth, &result.growth);
  } catch (const Error& e) {
    fail("{} {}: {}", c.mode == "clone" ? "--target-region" : "--region",
         c.mode == "clone" ? c.target_region : c.region, e.what());
  }
  result.growth_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  // The safety net: GEOS checks what is about to be written; any problem is a growth bug.
  const NetworkCheck check = check_network(grown, region, forbidden ? &*forbidden : nullptr);
  if (check.total() != 0)
    fail("{}: {} crossings, {} outside the region, {} through avoided cells (a growth bug): {}",
         cmd, check.crossings, check.outside, check.forbidden, check.first);
  result.method = c.growth.method;
  result.lead_bearing = growth.lead_bearing;
  result.exemplar_edges = int(exemplar.edges.size());
  result.nodes = int(grown.nodes.size());
  for (const NetworkEdge& e : grown.edges) (e.kept ? result.kept_edges : result.suggested_edges)++;

  OutputTransaction transaction;
  write_geopackage(transaction.stage(c.out / "network.gpkg"), exemplar_lines.crs_wkt, grown,
                   kept_lines ? &*kept_lines : nullptr, network_provenance(c, result));
  Network kept_view, suggested_view;
  for (const NetworkEdge& e : grown.edges) (e.kept ? kept_view : suggested_view).edges.push_back(e);
  kept_view.nodes = suggested_view.nodes = grown.nodes;
  write_network_png(transaction.stage(c.out / "preview.png"),
                    {{region,
                      {{&suggested_view, {30, 110, 40}, 2.0}, {&kept_view, {40, 40, 40}, 2.5}},
                      forbidden ? &*forbidden : nullptr}},
                    1024);
  transaction.commit();
  logger().info("{}: {} suggested edges, {} kept, {} nodes in {:.0f} ms by {}", cmd,
                result.suggested_edges, result.kept_edges, result.nodes, result.growth_ms,
                chosen_network_method(result.growth));
  return result;
}

std::string network_command_summary(const NetworkCommandResult& r) {
  return fmt::format(
      "{} suggested edges, {} kept, {} nodes (exemplar: {} edges) in {:.0f} ms; method {}, chose "
      "{}; {} seeds, {} T-junctions, {} snapped onto nodes; 0 crossings",
      r.suggested_edges, r.kept_edges, r.nodes, r.exemplar_edges, r.growth_ms,
      network_method_name(r.method), chosen_network_method(r.growth), r.growth.seeds,
      r.growth.t_junctions, r.growth.snapped);
}

}  // namespace tw

namespace tw {

Network read_network_exemplar(const NetworkSource& source, double snap, Warnings& warnings) {
  return exemplar_network(read_network_lines(source, warnings), snap, warnings);
}

std::vector<std::vector<Vec2>> complete_drawing(const Network& exemplar, const NetworkLines& drawn,
                                                const std::vector<Polygon>& region,
                                                const ForbiddenMask* forbidden,
                                                const NetworkGrowthOptions& options,
                                                NetworkGrowthReport* report) {
  Warnings warnings;
  // The drawing's parts inside the region are kept and completed (a line crossing its boundary
  // is cut there: the cut is no dangling end to grow from); what lies outside is not touched.
  const NetworkLines inside = cut_network_lines(drawn, region);
  std::optional<Network> partial;
  if (!inside.lines.empty() && !network_method_completes(options.method))
    fail(
        "method {} cannot complete a drawing (the region holds drawn lines): completing is "
        "growth from their ends (use growth or automatic)",
        network_method_name(options.method));
  if (!inside.lines.empty())
    partial = partial_network(inside, region, "drawing", "(lines numbered from 1)", warnings);
  const Network grown =
      grow_network(exemplar, region, forbidden, partial ? &*partial : nullptr, options, report);
  // The drawing may cross what is forbidden (the user drew it); the suggestions may not.
  Network suggested;
  suggested.nodes = grown.nodes;
  for (const NetworkEdge& e : grown.edges)
    if (!e.kept) suggested.edges.push_back(e);
  const NetworkCheck check = check_network(grown, region, nullptr);
  const int entered = forbidden ? check_network(suggested, region, forbidden).forbidden : 0;
  if (check.total() + entered != 0)
    fail(
        "completion: {} crossings, {} outside the region, {} through avoided cells (a growth "
        "bug): {}",
        check.crossings, check.outside, entered, check.first);
  std::vector<std::vector<Vec2>> suggestions;
  for (NetworkEdge& e : suggested.edges) suggestions.push_back(std::move(e.points));
  return suggestions;
}

void write_drawn_network(const std::filesystem::path& path, const std::string& crs_wkt,
                         const std::vector<std::vector<Vec2>>& lines,
                         const std::vector<std::string>& origins) {
  if (lines.empty()) fail("{}: nothing to save (no lines drawn or accepted)", path.string());
  for (std::size_t i = 0; i < lines.size(); ++i)
    if (lines[i].size() < 2) fail("{}: line {} has fewer than two points", path.string(), i + 1);
  OutputTransaction transaction;
  const std::filesystem::path staged = transaction.stage(path);
  {
    GeoPackageWriter gpkg = create_geopackage(staged, crs_wkt);
    OGRLayer* layer = &gpkg.create_layer("lines", wkbLineString);
    gpkg.add_fields(*layer, {{"origin", OFTString}});
    if (layer->StartTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      OGRFeature f(layer->GetLayerDefn());
      f.SetFID(GIntBig(i + 1));
      f.SetField("origin", i < origins.size() ? origins[i].c_str() : "drawn");
      OGRLineString ls;
      for (Vec2 p : lines[i]) ls.addPoint(p.x, p.y);
      f.SetGeometry(&ls);
      if (layer->CreateFeature(&f) != OGRERR_NONE) fail("{}: cannot write", path.string());
    }
    if (layer->CommitTransaction() != OGRERR_NONE) fail("{}: cannot write", path.string());
  }
  transaction.commit();
}

std::vector<std::vector<Vec2>> read_drawn_network(const std::filesystem::path& path,
                                                  const std::string& crs_wkt,
                                                  std::vector<std::string>& origins) {
  GDALAllRegister();
  const std::unique_ptr<GDALDataset> ds(GDALDataset::Open(
      path.string().c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr));
  OGRLayer* layer = ds ? ds->GetLayerByName("lines") : nullptr;
  if (!layer) fail("{}: not a saved drawing (no GeoPackage layer 'lines')", path.string());
  OGRSpatialReference run;
  const OGRSpatialReference* own = layer->GetSpatialRef();
  if (!crs_wkt.empty() && run.importFromWkt(crs_wkt.c_str()) == OGRERR_NONE &&
      (!own || !own->IsSame(&run)))
    fail("{}: the drawing is not in the run's CRS", path.string());
  const int origin_field = layer->GetLayerDefn()->GetFieldIndex("origin");
  std::vector<std::vector<Vec2>> lines;
  origins.clear();
  for (auto& f : *layer) {
    const OGRGeometry* g = f->GetGeometryRef();
    if (!g || wkbFlatten(g->getGeometryType()) != wkbLineString)
      fail("{}: FID {}: not a line", path.string(), f->GetFID());
    const OGRLineString* ls = g->toLineString();
    std::vector<Vec2>& line = lines.emplace_back();
    for (int i = 0; i < ls->getNumPoints(); ++i) line.push_back({ls->getX(i), ls->getY(i)});
    origins.push_back(origin_field >= 0 && f->GetFieldAsString(origin_field) == std::string("drawn")
                          ? "drawn"
                          : "suggested");
  }
  return lines;
}

}  // namespace tw
