#include "pipeline/methods/areas/areas.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/split_mix.hpp"
#include "pipeline/area_canvas.hpp"
#include "pipeline/lead_direction.hpp"
#include "raster/avoidance.hpp"
#include "sketch/area_synthesis.hpp"

namespace tw::detail {

namespace {

// The strokes of the areas synthesized so far (in their plans, which keep them in place).
struct StrokeSet {
  std::vector<const std::vector<Vec2>*> lines;
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

// Everything the polygon's shapes avoid, on its sparse canvas.
SparseAvoidance area_avoidance(const AvoidanceInputs& fixed, const KeepOut& keep_out,
                               const StrokeSet& earlier, AreaCanvas&& canvas) {
  burn_avoidance(fixed, canvas.grid, canvas.forbidden);
  if (keep_out) keep_out(canvas.grid, canvas.forbidden);
  burn_buffered_lines_on(earlier.lines, earlier.widths, canvas.grid, canvas.forbidden, 1);
  return finish_canvas(std::move(canvas));
}

// The shapes whose instance stands on a nodata cell of the heights (where its z would be
// empty) left out with their strokes; how many.
int drop_on_nodata(AreaPattern& pattern, HeightSampler& heights) {
  std::vector<int> index(pattern.instances.size(), -1);
  std::vector<ShapeInstance> kept;
  for (std::size_t i = 0; i < pattern.instances.size(); ++i) {
    const Vec2 p = heights.grid().world_to_pixel(pattern.instances[i].position);
    if (std::isnan(heights.cell(int(std::floor(p.x)), int(std::floor(p.y))))) continue;
    index[i] = int(kept.size());
    kept.push_back(std::move(pattern.instances[i]));
  }
  const int dropped = int(pattern.instances.size() - kept.size());
  if (dropped == 0) return 0;
  std::vector<PlacedStroke> strokes;
  for (PlacedStroke& s : pattern.strokes) {
    if (index[std::size_t(s.instance)] < 0) continue;
    s.instance = index[std::size_t(s.instance)];
    strokes.push_back(std::move(s));
  }
  pattern.instances = std::move(kept);
  pattern.strokes = std::move(strokes);
  return dropped;
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

void check_area_sketches(const std::vector<AreaClassConfig>& areas, Warnings& warnings) {
  for (const AreaClassConfig& a : areas) stroke_materials(a, area_hierarchy(a).sketch, warnings);
}

std::vector<std::vector<PolygonFeature>> load_area_polygons(
    const std::vector<AreaClassConfig>& areas, const Heightfield& heightfield, Warnings& warnings) {
  std::vector<std::vector<PolygonFeature>> out;
  for (const AreaClassConfig& a : areas) {
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
                         const KeepOut& keep_out, HeightSampler& heights, Warnings& warnings) {
  AreaRun run;
  const AvoidanceInputs fixed = fixed_avoidance(lines, ribbons, existing);
  const std::vector<const LineFeature*> roads = road_lines(config.features, lines);
  StrokeSet earlier;
  const double pixel = std::min(heights.grid().pixel_width, heights.grid().pixel_height);
  const std::vector<AreaClassConfig>& classes = area_classes(config);
  for (std::size_t ai = 0; ai < classes.size(); ++ai) {
    const AreaClassConfig& a = classes[ai];
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
    report.lead = std::string(lead_name(a.lead));
    std::map<std::int64_t, int> parts;
    std::map<std::string, double> widest;  // per stroke material placed
    for (const PolygonFeature& f : polygons[ai]) {
      const Polygon polygon(f.rings.begin(), f.rings.end());
      const std::string label = fmt::format("{}: FID {}", key, f.fid);
      AreaSynthesisParams params;
      params.scale = a.scale;
      params.jitter = a.jitter;
      params.seed = feature_seed(config.seed, a.seed, f.fid);
      if (const int part = parts[f.fid]++; part > 0)
        params.seed = feature_seed(params.seed, std::uint64_t(part), f.fid);
      const LeadAngle lead = lead_angle(a.lead, a.bearing_deg, polygon, roads, heights);
      if (lead.fell_back && a.lead == Lead::nearest_road)
        warnings.add("area_no_road", key, f.fid, "no road in the run: rows follow the long axis");
      if (lead.fell_back && a.lead == Lead::contours)
        logger().info("{}: flat or nodata: rows follow the long axis", label);
      params.bearing = lead.radians;

      // Strokes are written within a tenth of an output pixel (at most a quarter of a cell).
      params.tolerance = std::min(0.1 * pixel, 0.25 * config.synthesis_resolution);
      require_area_memory(hierarchy, polygon, params, config.synthesis_resolution, margin, label);
      AreaCanvas canvas = area_canvas(polygon, config.synthesis_resolution, margin);
      const std::int64_t canvas_cells = canvas.allocated_cells;
      const SparseAvoidance avoidance = area_avoidance(fixed, keep_out, earlier, std::move(canvas));
      PlannedArea planned;
      planned.area_class = ai;
      planned.fid = f.fid;
      planned.pattern = synthesize_area(hierarchy, polygon, params, &avoidance);
      const int shapes = int(planned.pattern.instances.size());
      const int on_nodata = drop_on_nodata(planned.pattern, heights);
      if (on_nodata > 0)
        warnings.add("area_on_nodata", key, f.fid,
                     fmt::format("{} of {} shapes stood on nodata heights (no z): left out",
                                 on_nodata, shapes));

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
      fr.on_nodata = on_nodata;
      fr.canvas_cells = canvas_cells;
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
      // The plan's strokes stay where they are when `planned` moves into the run.
      for (const PlacedStroke& s : planned.pattern.strokes) {
        earlier.lines.push_back(&s.points);
        earlier.widths.push_back(s.width);
        widest[s.material] = std::max(widest[s.material], s.width);
      }
      run.splats.push_back({});
      for (const AreaMaterial& m : materials) run.splats.back().push_back(m.splat);
      run.areas.push_back(std::move(planned));
    }
    // A stroke narrower than a pixel covers at most width / pixel of it: its splat weight.
    for (const auto& [material, width] : widest)
      if (width < pixel)
        warnings.add("area_stroke_subpixel", key, std::nullopt,
                     fmt::format("strokes of '{}' are {:.3g} m wide on {:.3g} m pixels: their "
                                 "splat weight reaches at most {:.2f}, the material is nearly "
                                 "invisible (raise `scale`, or lower `resolution`)",
                                 material, width, pixel, width / pixel));
  }
  return run;
}

}  // namespace tw::detail
