#include "commands/area_command.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <chrono>
#include <cmath>
#include <memory>

#include "commands/detail/analysis_png.hpp"
#include "commands/detail/vector_inputs.hpp"
#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_guard.hpp"
#include "core/warnings.hpp"
#include "geo/features.hpp"
#include "geo/heightfield.hpp"
#include "pipeline/area_canvas.hpp"
#include "pipeline/lead_direction.hpp"
#include "pipeline/area_output.hpp"
#include "raster/avoidance.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw {

namespace {

// A grid over the layer's extent in its own CRS, for geo's polygon reader (which reprojects to
// and clips by a grid): the polygons come back as they are, repaired where GEOS must.
Heightfield frame_of(const VectorSource& source) {
  const detail::OpenLayer opened = detail::open_layer(source);
  OGRLayer* layer = opened.layer;
  const OGRSpatialReference* srs = layer->GetSpatialRef();
  if (!srs || !srs->IsProjected()) {
    fail("{}: the polygons need a projected CRS in metres (reproject with ogr2ogr -t_srs)",
         source.path);
  }
  OGREnvelope extent;
  if (layer->GetExtent(&extent, TRUE) != OGRERR_NONE) fail("{}: empty layer", source.path);
  Heightfield frame;
  char* wkt = nullptr;
  srs->exportToWkt(&wkt);
  frame.crs_wkt = wkt;
  CPLFree(wkt);
  const double pad = 1.0;
  frame.grid.pixel_width = frame.grid.pixel_height = 1.0;
  frame.grid.origin_x = std::floor(extent.MinX) - pad;
  frame.grid.origin_y = std::ceil(extent.MaxY) + pad;
  frame.grid.width = int(std::ceil(extent.MaxX) - std::floor(extent.MinX) + 2 * pad);
  frame.grid.height = int(std::ceil(extent.MaxY) - std::floor(extent.MinY) + 2 * pad);
  frame.source = source.path;
  return frame;
}

// The thickest stroke's half width, and two cells: what the canvas reaches beyond the polygon.
double canvas_margin(const SupportHierarchy& h, double scale, double cell) {
  double thickest = 0.0;
  for (const Stroke& s : h.sketch.strokes) thickest = std::max(thickest, s.thickness);
  return 0.5 * thickest * scale + 2.0 * cell;
}

double elapsed_ms(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

}  // namespace

AreaCommandResult run_area_command(const AreaCommand& c) {
  if (c.out.empty()) fail("area: --out is required");
  std::vector<std::filesystem::path> inputs = {c.sketch};
  if (c.shapes_from) inputs.push_back(*c.shapes_from);
  require_safe_output(c.out, true, {.command = "area", .option = "--out", .inputs = inputs});
  if (!(c.resolution > 0.0)) fail("area: --resolution must be > 0 metres, got {}", c.resolution);
  const auto started = std::chrono::steady_clock::now();
  SupportHierarchy hierarchy = analyze_sketch(load_sketch(c.sketch), c.analysis);
  if (c.shapes_from) {
    hierarchy =
        hybridize(hierarchy, analyze_sketch(load_sketch(*c.shapes_from), c.analysis), c.analysis);
  }
  AreaCommandResult result;
  result.analysis_ms = elapsed_ms(started);

  const VectorSource source = detail::vector_source(c.polygons, c.where);
  const Heightfield frame = frame_of(source);
  Warnings warnings;
  const std::vector<PolygonFeature> features =
      read_polygon_features(source, frame, "area.polygons", warnings);
  if (features.empty()) fail("{}: no polygon to fill", c.polygons);

  const AvoidanceInputs avoided =
      detail::avoided_features(frame, c.avoid, c.avoid_width, "area.avoid", warnings);

  const auto synthesis_started = std::chrono::steady_clock::now();
  std::vector<AreaResult> results;
  std::vector<Polygon> polygons;
  for (std::size_t k = 0; k < features.size(); ++k) {
    const PolygonFeature& f = features[k];
    const Polygon polygon(f.rings.begin(), f.rings.end());
    AreaSynthesisParams params;
    params.scale = c.scale;
    params.jitter = c.jitter;
    // One seed per polygon part: the same part gets the same shapes whatever else is in the file.
    params.seed = c.seed * 0x9E3779B97F4A7C15ull + std::uint64_t(f.fid) * 0x100000001B3ull + k;
    params.bearing = c.bearing ? angle_from_compass(*c.bearing) : long_axis_bearing(polygon);
    params.tolerance = 0.25 * c.resolution;
    const std::string label = fmt::format("{}: FID {}", c.polygons, f.fid);
    const double cell = c.avoid.empty() ? 0.0 : c.resolution;
    const double margin = canvas_margin(hierarchy, c.scale, c.resolution);
    require_area_memory(hierarchy, polygon, params, cell, margin, label);
    AreaResult& r = results.emplace_back();
    r.area_class = c.sketch.stem().string();
    r.fid = f.fid;
    std::optional<SparseAvoidance> avoidance;
    if (!c.avoid.empty()) {
      AreaCanvas canvas = area_canvas(polygon, c.resolution, margin);
      burn_avoidance(avoided, canvas.grid, canvas.forbidden);
      avoidance = finish_canvas(std::move(canvas));
    }
    r.pattern = synthesize_area(hierarchy, polygon, params, avoidance ? &*avoidance : nullptr);
    if (avoidance) {
      if (const std::int64_t touched = forbidden_touched(r.pattern, *avoidance))
        fail("{}: {} stroke cells on forbidden ones (a synthesis bug)", label, touched);
    }
    result.instances += int(r.pattern.instances.size());
    result.strokes += int(r.pattern.strokes.size());
    result.outside += r.pattern.outside;
    result.forbidden += r.pattern.forbidden;
    result.overlapping += r.pattern.overlapping;
    polygons.push_back(polygon);
  }
  result.polygons = int(features.size());
  result.synthesis_ms = elapsed_ms(synthesis_started);

  fail_if_strict(warnings.list(), c.strict);
  OutputTransaction transaction;
  write_area_geopackage(transaction.stage(c.out / "shapes.gpkg"), frame.crs_wkt, results);
  write_instances_csv(transaction.stage(c.out / "instances.csv"), results);
  write_area_preview(transaction.stage(c.out / "preview.png"), polygons, avoided, results,
                     c.preview_resolution);
  if (c.analysis_png) detail::write_analysis_png(transaction.stage(*c.analysis_png), hierarchy);
  transaction.commit();
  logger().info(
      "area: {} instances, {} strokes in {} polygons ({:.1f} ms analysis, {:.1f} ms "
      "synthesis)",
      result.instances, result.strokes, result.polygons, result.analysis_ms, result.synthesis_ms);
  return result;
}

}  // namespace tw
