#include "pipeline/methods/grown/grown_classes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "core/error.hpp"
#include "core/grid_limits.hpp"
#include "core/log.hpp"
#include "geo/height_sampler.hpp"
#include "ornament/crossings.hpp"
#include "pipeline/grow_region.hpp"

namespace tw::detail {

namespace {

std::vector<Polygon> region_of(const FeatureClassConfig& c, const Heightfield& heightfield,
                               const std::string& key, Warnings& warnings) {
  const GrowConfig& g = *method_options<GrowConfig>(c, kGrownMethodName);
  if (g.region_box) return {box_polygon(*g.region_box)};
  const VectorSource source =
      g.region_source.empty()
          ? VectorSource{c.source.string(), c.layer, c.where}
          : VectorSource{g.region_source.string(), g.region_layer, g.region_where};
  std::vector<Polygon> out;
  try {
    for (PolygonFeature& f : read_polygon_features(source, heightfield, key, warnings))
      out.emplace_back(f.rings.begin(), f.rings.end());
  } catch (const Error& error) {
    fail("{}: {}", key, error.what());
  }
  return out;
}

// The mesh's grid: the heightfield's origin at `resolution` metres (the heightfield's own by
// default), so that the growth does not depend on the output grid unless asked to. Bounded
// before anything is allocated by the check `terraweave grow --resolution` meets when it
// resamples the DEM (core/grid_limits.hpp): the heightfield's extent at that resolution.
GridSpec mesh_grid(const GridSpec& grid, double resolution, const std::string& key) {
  if (resolution <= 0.0) return grid;
  const double columns = std::ceil(grid.width * grid.pixel_width / resolution);
  const double rows = std::ceil(grid.height * grid.pixel_height / resolution);
  require_grid_size(
      columns, rows,
      fmt::format("{}.grow.resolution: {} m over the {:.0f} x {:.0f} m heightfield", key,
                  resolution, grid.width * grid.pixel_width, grid.height * grid.pixel_height));
  GridSpec mesh = grid;
  mesh.pixel_width = mesh.pixel_height = resolution;
  mesh.width = std::max(2, int(columns));
  mesh.height = std::max(2, int(rows));
  return mesh;
}

// The profile's raise (+) or carve (-) in metres, for ornaments.gpkg's height_m.
double profile_height(const FeatureClassConfig& c) {
  switch (c.kind) {
    case FeatureKind::ridge:
      return c.ridge.height;
    case FeatureKind::river:
      return -c.river.depth;
    case FeatureKind::road:
      return 0.0;
  }
  return 0.0;
}

// The heightfield's nodata cells (on its own grid, finer than the mesh's or not) around the
// region's window on the mesh: no grown line passes through one. None without a nodata value.
std::optional<ForbiddenCells> nodata_around(const HeightfieldSource& source, const GridSpec& grid,
                                            const std::vector<Polygon>& region,
                                            const GridSpec& mesh) {
  if (!source.nodata_value()) return std::nullopt;
  Window w = window_around(region, grid);
  // A line keeps within half a mesh vertex of the region's outline.
  const int margin = int(std::ceil(mesh.pixel_width / grid.pixel_width)) + 1;
  const int col1 = std::min(w.col0 + w.width + margin, grid.width),
            row1 = std::min(w.row0 + w.height + margin, grid.height);
  w.col0 = std::max(w.col0 - margin, 0);
  w.row0 = std::max(w.row0 - margin, 0);
  w.width = col1 - w.col0;
  w.height = row1 - w.row0;
  if (w.width < 1 || w.height < 1) return std::nullopt;
  return nodata_cells(grid, w, source.read(w));
}

// What the lines of class `c` keep off, exactly: the existing features, the lines read and the
// lines grown before (each buffered by half its width); `names` gets what each id is.
FootprintIndex keep_off_footprints(const std::vector<FeatureClassConfig>& classes, std::size_t c,
                                   const ExistingFeatures& existing,
                                   const std::vector<std::vector<LineFeature>>& lines,
                                   bool grown_ones, std::vector<std::string>* names) {
  FootprintIndex index;
  for (std::size_t i = 0; i < existing.polygons.size(); ++i) {
    index.add_polygon(existing.polygons[i]);
    if (names) names->push_back(fmt::format("existing polygon {}", i + 1));
  }
  for (std::size_t i = 0; i < existing.lines.size(); ++i) {
    index.add_line(existing.lines[i], 0.5 * existing.line_widths[i]);
    if (names) names->push_back(fmt::format("existing line {}", i + 1));
  }
  for (std::size_t other = 0; other < classes.size(); ++other) {
    const bool grown = has_method_options(classes[other], kGrownMethodName);
    if (other == c || (grown && (!grown_ones || other > c))) continue;
    for (const LineFeature& line : lines[other]) {
      std::vector<Vec2> points = line.points;
      if (line.closed && !points.empty()) points.push_back(points.front());
      index.add_line(points, 0.5 * line.width);
      if (names) names->push_back(fmt::format("{} FID {}", classes[other].name, line.fid));
    }
  }
  return index;
}

}  // namespace

void check_grown_lines(const std::vector<FeatureClassConfig>& classes,
                       const ExistingFeatures& existing,
                       const std::vector<std::vector<LineFeature>>& lines,
                       const std::vector<GrownClass>& grown,
                       const std::map<std::size_t, std::optional<ForbiddenCells>>& cells,
                       std::vector<std::optional<GrowthReport>>& reports) {
  std::vector<std::string> feature_names, set_names;
  const FootprintIndex features =
      keep_off_footprints(classes, classes.size(), existing, lines, false, &feature_names);
  std::vector<GrownLineSet> sets;
  for (const GrownClass& g : grown) {
    const auto found = cells.find(g.class_index);
    const ForbiddenCells* c = found != cells.end() && found->second ? &*found->second : nullptr;
    sets.push_back({&g.lines, 0.5 * classes[g.class_index].width, c});
    set_names.push_back(classes[g.class_index].name);
  }
  const CrossingCheck check = check_crossings(sets, features);
  for (std::size_t s = 0; s < grown.size(); ++s) {
    GrowthReport& r = *reports[grown[s].class_index];
    r.crossings = {check.per_set[s].grown, check.per_set[s].feature, check.per_set[s].forbidden};
  }
  if (check.total.total() == 0) return;
  std::string first;
  for (const Crossing& c : check.first)
    first += (first.empty() ? "" : "; ") + describe(c, set_names, feature_names);
  fail(
      "grow: {} grown crossings ({} between grown lines, {} with features, {} through nodata "
      "cells; a growth bug): {}",
      check.total.total(), check.total.grown, check.total.feature, check.total.forbidden, first);
}

std::vector<GrownClass> grow_classes(const std::vector<FeatureClassConfig>& classes,
                                     const HeightfieldSource& source,
                                     const Heightfield& heightfield,
                                     const ExistingFeatures& existing,
                                     std::vector<std::vector<LineFeature>>& lines,
                                     std::vector<std::optional<GrowthReport>>& reports,
                                     Warnings& warnings) {
  std::vector<GrownClass> out;
  HeightSampler sampler(source);
  std::map<std::size_t, std::optional<ForbiddenCells>> forbidden_cells;  // by class
  // Every class's mesh is bounded before any class grows: a later class's resolution fails
  // the run at once, not after the classes before it.
  for (const FeatureClassConfig& fc : classes)
    if (const GrowConfig* g = method_options<GrowConfig>(fc, kGrownMethodName))
      mesh_grid(heightfield.grid, g->settings.resolution, "features." + fc.name);
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const FeatureClassConfig& fc = classes[c];
    const GrowConfig* grow = method_options<GrowConfig>(fc, kGrownMethodName);
    if (!grow) continue;
    const GrowConfig& g = *grow;
    const std::string key = "features." + fc.name;
    ElementSet set;
    try {
      set = with_settings(read_element_set(g.element), g.settings);
    } catch (const Error& error) {
      fail("{}.grow.element: {}", key, error.what());
    }
    const std::vector<Polygon> region = region_of(fc, heightfield, key, warnings);
    GrowthReport& r = reports.at(c).emplace();
    r.kind = g.kind;
    r.element = g.element.string();
    GrownClass& grown = out.emplace_back();
    grown.class_index = c;
    grown.kind = g.kind;
    grown.height_m = profile_height(fc);
    const GridSpec mesh = mesh_grid(heightfield.grid, g.settings.resolution, key);
    const Window window = window_around(region, mesh);
    if (region.empty() || window.width < 2 || window.height < 2) {
      warnings.add("empty_class", key, std::nullopt,
                   "no region polygon lies on the heightfield: nothing is grown");
      continue;
    }
    // What the lines keep off: every footprint there, widened by this class's half width on
    // each side so that the footprints do not overlap.
    AvoidanceInputs avoided;
    avoided.polygons = existing.polygons;
    for (std::size_t i = 0; i < existing.lines.size(); ++i) {
      avoided.lines.push_back(existing.lines[i]);
      avoided.line_widths.push_back(existing.line_widths[i] + fc.width);
    }
    for (std::size_t other = 0; other < classes.size(); ++other) {
      if (other == c || (has_method_options(classes[other], kGrownMethodName) && other > c))
        continue;
      for (const LineFeature& line : lines[other]) {
        avoided.lines.push_back(line.points);
        if (line.closed && !line.points.empty())
          avoided.lines.back().push_back(line.points.front());
        avoided.line_widths.push_back(line.width + fc.width);
      }
    }
    // The same footprints, exactly, on the candidates' vector lines: a footprint narrower than
    // the mesh's vertex spacing slips through the mask above.
    const FootprintIndex footprints =
        keep_off_footprints(classes, c, existing, lines, true, nullptr);
    const std::optional<ForbiddenCells>& cells = forbidden_cells[c] =
        nodata_around(source, heightfield.grid, region, mesh);
    const KeepOff keep_off{&footprints, 0.5 * fc.width, cells ? &*cells : nullptr};
    Raster<float> heights(window.width, window.height);
    for (int row = 0; row < window.height; ++row)
      for (int col = 0; col < window.width; ++col)
        heights.at(col, row) =
            float(sampler.bilinear(mesh.pixel_centre_world(window.col0 + col, window.row0 + row)));
    GrownRegion result = grow_region(set, g.settings, mesh, window, std::move(heights), region,
                                     avoided, keep_off, key);
    r.ornaments = result.grown.ornaments;
    r.elements = result.grown.elements;
    r.lines = int(result.grown.lines.size());
    r.rejected_crossing = result.grown.rejected_crossing;
    r.rejected_forbidden = result.grown.rejected_forbidden;
    r.rejected_untraceable = result.grown.rejected_untraceable;
    r.rejected_footprint = result.grown.rejected_footprint;
    r.coverage = result.coverage;
    r.coverage_radius_m = result.coverage_radius;
    r.mesh_width = window.width;
    r.mesh_height = window.height;
    for (GrownLine& line : result.grown.lines) {
      // A river's points run downstream: a ditch drains from its higher end.
      if (fc.kind == FeatureKind::river && line.heights.front() < line.heights.back()) {
        std::reverse(line.points.begin(), line.points.end());
        std::reverse(line.heights.begin(), line.heights.end());
      }
      LineFeature& feature = lines[c].emplace_back();
      feature.fid = std::int64_t(lines[c].size());
      feature.points = line.points;
      feature.width = fc.width;
      feature.source = g.element.string();
    }
    grown.lines = std::move(result.grown.lines);
    logger().info(
        "{}: {} ornaments, {} elements, {} lines over {}x{} vertices in {:.1f} s; "
        "coverage within {:.1f} m: {:.3f}",
        key, r.ornaments, r.elements, r.lines, window.width, window.height, result.growth_ms / 1000,
        r.coverage_radius_m, r.coverage);
  }
  check_grown_lines(classes, existing, lines, out, forbidden_cells, reports);
  return out;
}

}  // namespace tw::detail
