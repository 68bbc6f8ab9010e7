#include "commands/grow_command.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>

#include "commands/detail/vector_inputs.hpp"
#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_guard.hpp"
#include "core/warnings.hpp"
#include "geo/heightfield_source.hpp"
#include "layers/layer_set.hpp"
#include "layers/write.hpp"
#include "ornament/crossings.hpp"
#include "ornament/grow.hpp"
#include "pipeline/grow_region.hpp"
#include "raster/rasterize.hpp"

namespace tw {

namespace {

// "minx,miny,maxx,maxy" as a rectangle, or nullopt when the text is not four numbers.
std::optional<Polygon> bbox_polygon(const std::string& text) {
  std::array<double, 4> v{};
  char tail = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4) {
    // Four comma-separated words that name no file were meant as a box, not a file name.
    if (std::count(text.begin(), text.end(), ',') == 3 && !std::filesystem::exists(text))
      fail(
          "--region {}: neither a polygon file nor a box of four numbers minx,miny,maxx,maxy "
          "(in the DEM's CRS)",
          text);
    return std::nullopt;
  }
  if (!(v[0] < v[2] && v[1] < v[3])) fail("--region {}: expected minx,miny,maxx,maxy", text);
  return box_polygon(v);
}

std::vector<Polygon> region_polygons(const GrowCommand& c, const Heightfield& frame,
                                     Warnings& warnings) {
  if (auto box = bbox_polygon(c.region)) return {*box};
  std::vector<Polygon> out;
  for (PolygonFeature& f : read_polygon_features(detail::vector_source(c.region, c.where), frame,
                                                 "grow.region", warnings)) {
    out.emplace_back(f.rings.begin(), f.rings.end());
  }
  if (out.empty()) fail("--region {}: no polygon inside the DEM", c.region);
  return out;
}

}  // namespace

GrowCommandResult run_grow_command(const GrowCommand& c) {
  if (c.out.empty()) fail("grow: --out is required");
  require_safe_output(
      c.out, true,
      {.command = "grow", .option = "--out", .inputs = {std::filesystem::path(c.dem), c.element}});
  const ElementSet set = read_element_set(c.element);
  Warnings warnings;
  HeightfieldOptions options;
  if (c.resolution > 0.0) options.resolution = c.resolution;
  options.resampling = Resampling::cubic;
  const std::unique_ptr<HeightfieldSource> dem = open_heightfield(c.dem, options, warnings);
  const Heightfield frame = dem->without_pixels();
  const GridSpec& grid = frame.grid;
  const std::vector<Polygon> region = region_polygons(c, frame, warnings);
  const Window window = window_around(region, grid);

  AvoidanceInputs avoided;
  if (!c.avoid.empty())
    avoided = detail::avoided_features(frame, c.avoid, c.avoid_width, "grow.avoid", warnings);
  // The lines are their kind's width (a hedge bank 2 m, as in a run): footprints keep apart.
  const double width = grown_kind_width(set.kind);
  const FootprintIndex footprints = footprints_of(avoided);
  for (double& w : avoided.line_widths) w += width;  // the mesh's mask: footprints apart
  Raster<float> dem_heights = dem->read(window);
  const ForbiddenCells cells = nodata_cells(grid, window, dem_heights);
  const KeepOff keep_off{&footprints, 0.5 * width, &cells};
  const GrownRegion grown_region =
      grow_region(with_settings(set, c), c, grid, window, std::move(dem_heights), region, avoided,
                  keep_off, "--region " + c.region);
  const GrowthResult& grown = grown_region.grown;
  const Raster<float>& heights = grown_region.heights;

  GrowCommandResult result;
  result.growth_ms = grown_region.growth_ms;
  result.ornaments = grown.ornaments;
  result.elements = grown.elements;
  result.lines = int(grown.lines.size());
  result.rejected_crossing = grown.rejected_crossing;
  result.rejected_forbidden = grown.rejected_forbidden;
  result.rejected_untraceable = grown.rejected_untraceable;
  result.rejected_footprint = grown.rejected_footprint;
  result.width = window.width;
  result.height = window.height;
  result.coverage_radius = grown_region.coverage_radius;
  result.coverage = grown_region.coverage;

  LayerSet preview;
  preview.grid = grid;
  preview.grid.width = window.width;
  preview.grid.height = window.height;
  preview.grid.origin_x = grid.origin_x + window.col0 * grid.pixel_width;
  preview.grid.origin_y = grid.origin_y - window.row0 * grid.pixel_height;
  preview.crs_wkt = frame.crs_wkt;
  preview.layers.push_back(height_layer(heights));
  // The safety net: the lines about to be written, checked exactly (docs/ornaments.md,
  // "Crossings"); any crossing is a growth bug and nothing is written.
  const CrossingCheck check = check_crossings({{&grown.lines, 0.5 * width, &cells}}, footprints);
  result.crossings = check.total;
  if (check.total.total() != 0) {
    std::string first;
    for (const Crossing& x : check.first)
      first += (first.empty() ? "" : "; ") + describe(x, {"ornaments"}, {});
    fail(
        "grow: {} grown crossings ({} between grown lines, {} with avoided features, {} through "
        "nodata cells; a growth bug): {}",
        check.total.total(), check.total.grown, check.total.feature, check.total.forbidden, first);
  }
  std::vector<std::vector<Vec2>> drawn;
  for (const GrownLine& line : grown.lines) drawn.push_back(line.points);

  fail_if_strict(warnings.list(), c.strict);
  OutputTransaction transaction;
  write_ornament_geopackage(transaction.stage(c.out / "ornaments.gpkg"), frame.crs_wkt,
                            {{"ornaments", set.kind, 0.0, &grown.lines, {}}});
  write_preview_png(preview, transaction.stage(c.out / "preview.png"), drawn);
  transaction.commit();
  logger().info(
      "grow: {} ornaments, {} elements, {} lines over {}x{} vertices in {:.0f} ms; "
      "coverage within {:.1f} m: {:.3f}",
      result.ornaments, result.elements, result.lines, window.width, window.height,
      result.growth_ms, result.coverage_radius, result.coverage);
  return result;
}

}  // namespace tw
