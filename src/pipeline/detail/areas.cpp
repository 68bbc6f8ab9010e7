#include "pipeline/detail/areas.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/detail/area_lead.hpp"
#include "raster/avoidance.hpp"
#include "raster/distance.hpp"
#include "raster/footprint.hpp"
#include "raster/rasterize.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw::detail {

namespace {

// The largest avoidance canvas of one polygon (cells): 8 km square at 1 m.
constexpr double kMaxAreaCanvasCells = double(1 << 26);

const char* lead_name(AreaLead lead) {
  switch (lead) {
    case AreaLead::bearing:
      return "bearing";
    case AreaLead::long_axis:
      return "long_axis";
    case AreaLead::nearest_road:
      return "nearest_road";
    case AreaLead::contours:
      return "contours";
  }
  return "";
}

double polygon_area(const Polygon& polygon) {
  double area = 0.0;
  for (std::size_t r = 0; r < polygon.size(); ++r) {
    double twice = 0.0;
    const Ring& ring = polygon[r];
    for (std::size_t i = 0; i < ring.size(); ++i)
      twice += cross(ring[i], ring[(i + 1) % ring.size()]);
    area += (r == 0 ? 0.5 : -0.5) * std::abs(twice);
  }
  return area;
}

// Cells of the synthesis lattice (edges on multiples of `cell` in world coordinates, as the
// curve patterns' canvases) over the polygon's box grown by `margin` metres.
GridSpec canvas_around(const Polygon& polygon, double cell, double margin,
                       const std::string& label) {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
  for (Vec2 p : polygon.front()) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  GridSpec g;
  g.pixel_width = g.pixel_height = cell;
  g.origin_x = std::floor((lo.x - margin) / cell) * cell;
  g.origin_y = std::ceil((hi.y + margin) / cell) * cell;
  const double w = std::ceil((hi.x + margin - g.origin_x) / cell);
  const double h = std::ceil((g.origin_y - (lo.y - margin)) / cell);
  if (w * h > kMaxAreaCanvasCells)
    fail(
        "{}: the polygon's box is {:.0f} x {:.0f} cells of {} m (at most {:.0f} cells); raise "
        "synthesis_resolution or split the polygon",
        label, w, h, cell, kMaxAreaCanvasCells);
  g.width = int(w), g.height = int(h);
  return g;
}

struct StrokeSet {
  std::vector<std::vector<Vec2>> lines;
  std::vector<double> widths;
};

// What every polygon avoids: existing features, the line features' footprints (ribbons, and
// each line buffered to its width, so features shorter than a piece count too), junctions.
AvoidanceInputs fixed_avoidance(const std::vector<std::vector<LineFeature>>& lines,
                                const FeatureRibbons& ribbons, const ExistingFeatures& existing) {
  AvoidanceInputs inputs;
  inputs.polygons = existing.polygons;
  inputs.lines = existing.lines;
  inputs.line_widths = existing.line_widths;
  for (const auto& class_lines : lines)
    for (const LineFeature& line : class_lines) {
      if (line.points.size() < 2 || line.structure != Structure::ground) continue;
      inputs.lines.push_back(line.points);
      if (line.closed) inputs.lines.back().push_back(line.points.front());
      inputs.line_widths.push_back(line.width);
    }
  for (const auto& class_ribbons : ribbons.ribbons)
    for (const Ribbon& r : class_ribbons) inputs.ribbons.push_back(&r);
  inputs.junction_discs = ribbons.synthesis_junction_discs;
  inputs.include_foldovers = false;
  return inputs;
}

AvoidanceMap area_avoidance(const AvoidanceInputs& fixed, const PatternRun* patterns,
                            const StrokeSet& earlier, const GridSpec& canvas) {
  SparseRaster<std::uint8_t> sparse(canvas.width, canvas.height, 0, 0);  // one dense tile
  sparse.add_tile({0, 0});
  burn_avoidance(fixed, canvas, sparse);
  if (patterns)
    for (const FeaturePattern& p : patterns->patterns)
      if (p.on_ground) add_on_lattice(p.opaque, p.canvas, sparse, canvas);
  AvoidanceMap map;
  map.grid = canvas;
  map.window = Window::whole(canvas);
  map.forbidden = std::move(*sparse.tile({0, 0}));
  burn_buffered_lines(earlier.lines, earlier.widths, canvas, map.window, map.forbidden, 1);
  map.distance = distance_to_mask(map.forbidden, canvas.pixel_width, canvas.pixel_height);
  return map;
}

// Canvas pixels under the placed strokes (pixel-centre rule, exact buffers) that are forbidden:
// an independent check of the synthesis's conservative test.
std::int64_t forbidden_touched(const AreaPattern& pattern, const AvoidanceMap& map) {
  std::vector<std::vector<Vec2>> lines;
  std::vector<double> widths;
  for (const PlacedStroke& s : pattern.strokes)
    lines.push_back(s.points), widths.push_back(s.width);
  Raster<std::uint8_t> touched;
  burn_buffered_lines(lines, widths, map.grid, map.window, touched, 1);
  std::int64_t count = 0;
  for (std::size_t i = 0; i < touched.pixels.size(); ++i)
    count += touched.pixels[i] && map.forbidden.pixels[i];
  return count;
}

// Every stroke material of the sketch: those the class names first, in its order, then the
// others in sketch order.
std::vector<AreaMaterial> stroke_materials(const AreaClassConfig& a, const Sketch& sketch,
                                           Warnings& warnings) {
  std::vector<AreaMaterial> out;
  for (const AreaMaterial& m : a.materials) {
    const bool used = std::any_of(sketch.strokes.begin(), sketch.strokes.end(),
                                  [&](const Stroke& s) { return s.material == m.stroke; });
    if (!used) {
      warnings.add(
          "area_material_unused", "features." + a.name, std::nullopt,
          fmt::format("the sketch {} has no stroke of material '{}'", sketch.source, m.stroke));
      continue;
    }
    out.push_back(m);
  }
  for (const Stroke& s : sketch.strokes) {
    if (std::none_of(out.begin(), out.end(),
                     [&](const AreaMaterial& m) { return m.stroke == s.material; }))
      out.push_back({s.material, "", 0.0});
  }
  for (AreaMaterial& m : out)
    if (m.splat.empty()) m.splat = a.name + "_" + m.stroke;
  return out;
}

}  // namespace

SupportHierarchy area_hierarchy(const AreaClassConfig& a) {
  try {
    SupportHierarchy hierarchy = analyze_sketch(load_sketch(a.sketch));
    if (a.shapes_from)
      hierarchy = hybridize(hierarchy, analyze_sketch(load_sketch(*a.shapes_from)));
    return hierarchy;
  } catch (const Error& error) {
    fail("features.{}: {}", a.name, error.what());
  }
}

void check_area_sketches(const PipelineConfig& config, Warnings& warnings) {
  for (const AreaClassConfig& a : config.areas)
    stroke_materials(a, area_hierarchy(a).sketch, warnings);
}

std::vector<std::vector<PolygonFeature>> load_area_polygons(const PipelineConfig& config,
                                                            const Heightfield& heightfield,
                                                            Warnings& warnings) {
  std::vector<std::vector<PolygonFeature>> out;
  for (const AreaClassConfig& a : config.areas) {
    const std::string key = "features." + a.name;
    try {
      out.push_back(
          read_polygon_features({a.source.string(), a.layer, a.where}, heightfield, key, warnings));
    } catch (const Error& error) {
      fail("{}: {}", key, error.what());
    }
    if (out.back().empty())
      warnings.add("empty_class", key, std::nullopt,
                   fmt::format("no polygon of {} lies on the heightfield", a.source.string()));
  }
  return out;
}

AreaRun synthesize_areas(const PipelineConfig& config,
                         const std::vector<std::vector<PolygonFeature>>& polygons,
                         const std::vector<std::vector<LineFeature>>& lines,
                         const FeatureRibbons& ribbons, const ExistingFeatures& existing,
                         const PatternRun* patterns, HeightSampler& heights, Warnings& warnings) {
  AreaRun run;
  const AvoidanceInputs fixed = fixed_avoidance(lines, ribbons, existing);
  std::vector<const LineFeature*> roads;
  for (std::size_t c = 0; c < config.features.size(); ++c)
    if (config.features[c].kind == FeatureKind::road)
      for (const LineFeature& line : lines[c]) roads.push_back(&line);
  StrokeSet earlier;
  for (std::size_t ai = 0; ai < config.areas.size(); ++ai) {
    const AreaClassConfig& a = config.areas[ai];
    const std::string key = "features." + a.name;
    const SupportHierarchy hierarchy = area_hierarchy(a);
    const std::vector<AreaMaterial> materials = stroke_materials(a, hierarchy.sketch, warnings);
    double thickest = 0.0;
    for (const Stroke& s : hierarchy.sketch.strokes) thickest = std::max(thickest, s.thickness);
    const double margin = 0.5 * thickest * a.scale + 2.0 * config.synthesis_resolution;

    AreaClassReport& report = run.reports.emplace_back();
    report.name = a.name;
    report.source = a.source.string() + ":" + a.layer;
    report.sketch = a.sketch.string();
    report.lead = lead_name(a.lead);
    std::map<std::int64_t, int> parts;
    for (const PolygonFeature& f : polygons[ai]) {
      const Polygon polygon(f.rings.begin(), f.rings.end());
      const std::string label = fmt::format("{}: FID {}", key, f.fid);
      AreaSynthesisParams params;
      params.scale = a.scale;
      params.jitter = a.jitter;
      params.seed = feature_seed(config.seed, a.seed, f.fid);
      if (const int part = parts[f.fid]++; part > 0)
        params.seed = feature_seed(params.seed, std::uint64_t(part), f.fid);
      std::optional<double> angle;
      switch (a.lead) {
        case AreaLead::bearing:
          angle = angle_from_compass(a.bearing_deg);
          break;
        case AreaLead::long_axis:
          break;
        case AreaLead::nearest_road:
          angle = nearest_line_angle(polygon, roads);
          if (!angle)
            warnings.add("area_no_road", key, f.fid,
                         "no road in the run: rows follow the long axis");
          break;
        case AreaLead::contours:
          angle = contour_angle(polygon, heights);
          if (!angle) logger().info("{}: flat or nodata: rows follow the long axis", label);
          break;
      }
      params.bearing = angle.value_or(long_axis_bearing(polygon));

      const GridSpec canvas = canvas_around(polygon, config.synthesis_resolution, margin, label);
      const AvoidanceMap avoidance = area_avoidance(fixed, patterns, earlier, canvas);
      PlannedArea planned;
      planned.area_class = ai;
      planned.fid = f.fid;
      planned.pattern = synthesize_area(hierarchy, polygon, params, &avoidance);

      AreaFeatureReport& fr = report.features.emplace_back();
      fr.fid = f.fid;
      fr.area_m2 = polygon_area(polygon);
      fr.lead_bearing_deg = compass_degrees(params.bearing);
      fr.seed = params.seed;
      fr.shapes = int(planned.pattern.instances.size());
      fr.strokes = int(planned.pattern.strokes.size());
      fr.outside = planned.pattern.outside;
      fr.forbidden = planned.pattern.forbidden;
      fr.overlapping = planned.pattern.overlapping;
      fr.forbidden_touched = forbidden_touched(planned.pattern, avoidance);
      if (fr.forbidden_touched != 0)
        fail("{}: {} stroke pixels on forbidden ones (a synthesis bug)", label,
             fr.forbidden_touched);
      logger().info(
          "{}: {} shapes, {} strokes (left out: {} outside, {} forbidden, {} overlapping), "
          "lead {:.1f} deg",
          label, fr.shapes, fr.strokes, fr.outside, fr.forbidden, fr.overlapping,
          fr.lead_bearing_deg);

      for (const AreaMaterial& m : materials)
        planned.targets.push_back({m.stroke, 0, float(m.height)});
      for (const PlacedStroke& s : planned.pattern.strokes) {
        earlier.lines.push_back(s.points);
        earlier.widths.push_back(s.width);
      }
      run.splats.push_back({});
      for (const AreaMaterial& m : materials) run.splats.back().push_back(m.splat);
      run.areas.push_back(std::move(planned));
    }
  }
  return run;
}

}  // namespace tw::detail
