#include "pipeline/methods/areas/area_method.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/area_output.hpp"
#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_report_parts.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/methods/areas/area_report.hpp"
#include "pipeline/methods/areas/areas.hpp"
#include "pipeline/methods/areas/instance_heights.hpp"
#include "raster/footprint.hpp"
#include "raster/stroke_coverage.hpp"
#include "terrain/pattern_layers.hpp"
#include "terrain/splat.hpp"

namespace tw::detail {

using nlohmann::json;

// The areas as the renderer needs them, replacing those the entry held: their splat materials
// after the methods' before them, the output pixels their strokes can touch, their report.
void add_areas(const PipelineConfig& config, AreaRun run, WorldPlan& plan);

// The codec's field lists of its own types (detail/plan_codec.hpp).
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD
TW_FIELDS(ShapeInstance, F(shape) F(lead) F(position) F(rotation) F(scale) F(material) F(unbounded))
TW_FIELDS(PlacedStroke, F(points) F(material) F(width) F(instance))
TW_FIELDS(AreaPattern, F(instances) F(strokes) F(outside) F(forbidden) F(overlapping))
TW_FIELDS(AreaTarget, F(stroke_material) F(material) F(height))
TW_FIELDS(PlannedArea, F(area_class) F(fid) F(pattern) F(targets) F(window))
TW_FIELDS(AreaFeatureReport,
          F(fid) F(area_m2) F(lead_bearing_deg) F(seed) F(shapes) F(strokes) F(outside) F(forbidden)
              F(overlapping) F(forbidden_touched) F(on_nodata) F(canvas_cells))
TW_FIELDS(AreaClassReport, F(name) F(source) F(sketch) F(lead) F(features))
TW_FIELDS(AreasReport, F(classes))
#undef F
#undef TW_FIELDS

namespace {

// `kind: area` classes: per polygon, what was placed and what was left out, and why.
json areas_json(const RunReport& report) {
  json areas = json::array();
  const AreasReport* part = method_report<AreasReport>(report);
  for (const AreaClassReport& a : part ? part->classes : std::vector<AreaClassReport>{}) {
    json features = json::array();
    int shapes = 0;
    std::int64_t touched = 0;
    for (const AreaFeatureReport& f : a.features) {
      features.push_back(
          {{"fid", f.fid},
           {"area_m2", f.area_m2},
           {"lead_bearing_deg", f.lead_bearing_deg},
           {"seed", f.seed},
           {"shapes", f.shapes},
           {"strokes", f.strokes},
           {"left_out",
            {{"outside", f.outside}, {"forbidden", f.forbidden}, {"overlapping", f.overlapping}}},
           {"forbidden_touched", f.forbidden_touched},
           {"on_nodata", f.on_nodata},
           {"canvas_cells", f.canvas_cells}});
      shapes += f.shapes;
      touched += f.forbidden_touched;
    }
    areas.push_back({{"name", a.name},
                     {"source", a.source},
                     {"sketch", a.sketch},
                     {"lead", a.lead},
                     {"shapes", shapes},
                     {"forbidden_touched", touched},
                     {"features", features}});
  }
  return areas;
}

class AreaMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return kAreasMethodName; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig& config, const PlanOptions& options) const override {
    return options.synthesize && !area_classes(config).empty();
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<AreasPlan>();
  }

  std::string validate_stage() const override { return "sketches"; }
  void validate(const PipelineConfig& config, Warnings& warnings) const override {
    check_area_sketches(area_classes(config), warnings);
  }

  void ingest(MethodContext& context, MethodPlan& entry) const override {
    payload_as<AreasPlan>(entry).polygons =
        std::make_shared<const std::vector<std::vector<PolygonFeature>>>(load_area_polygons(
            area_classes(context.config), context.heightfield, context.warnings));
  }

  // The polygons its shape-patterns fill: the lines methods (networks) keep out of them.
  std::vector<Polygon> reserved(const MethodContext& /*context*/,
                                const MethodPlan& entry) const override {
    std::vector<Polygon> out;
    for (const auto& per_class : *payload_as<AreasPlan>(entry).polygons)
      for (const PolygonFeature& f : per_class) out.emplace_back(f.rings.begin(), f.rings.end());
    return out;
  }

  void plan(MethodContext& context, MethodPlan& entry) const override {
    AreasPlan& areas = payload_as<AreasPlan>(entry);
    // The whole heightfield, also with a region: a close-up's polygons get the leads of the
    // full run, and polygons beyond the region keep theirs.
    HeightSampler heights(context.source);
    // The shapes avoid what the methods before this one keep out (the curve patterns).
    std::vector<const MethodPlan*> before;
    for (const MethodPlan& e : context.plan.methods) {
      if (&e == &entry) break;
      before.push_back(&e);
    }
    const KeepOut keep_out = [&](const GridSpec& lattice, SparseRaster<std::uint8_t>& forbidden) {
      for (const MethodPlan* e : before) e->method->keep_out(*e, lattice, forbidden);
    };
    areas.run = std::make_shared<AreaRun>(
        synthesize_areas(context.config, *areas.polygons, context.lines, *context.ribbons,
                         *context.existing, keep_out, heights, context.warnings));
  }

  void collect(MethodContext& context, MethodPlan& entry) const override {
    AreasPlan& areas = payload_as<AreasPlan>(entry);
    areas.polygons.reset();
    AreaRun run;
    if (areas.run) run = std::move(*areas.run);
    areas.run.reset();
    add_areas(context.config, std::move(run), context.plan);
  }

  std::vector<Window> windows(const WorldPlan& /*plan*/, const MethodPlan& entry) const override {
    std::vector<Window> out;
    for (const PlannedArea& a : payload_as<AreasPlan>(entry).areas) out.push_back(a.window);
    return out;
  }

  bool renders() const override { return true; }

  // Each area's strokes, material by material, as anti-aliased coverage (a per-pixel function
  // of the world grid) taking its share from the other materials, plus their height detail.
  void render(const WorldPlan& plan, const MethodPlan& entry, const Window& window,
              Raster<float>& height, SplatLayers& splat) const override {
    const AreasPlan& areas = payload_as<AreasPlan>(entry);
    for (const std::size_t i : items_meeting(entry.index, window)) {
      const PlannedArea& area = areas.areas[i];
      const Window part = intersect(area.window, window);
      if (part.width == 0) continue;
      const Raster<float> ones(part.width, part.height, 1.0f);
      for (const AreaTarget& target : area.targets) {
        std::vector<const std::vector<Vec2>*> lines;
        std::vector<double> widths;
        for (const PlacedStroke& s : area.pattern.strokes) {
          if (s.material != target.stroke_material) continue;
          lines.push_back(&s.points);
          widths.push_back(s.width);
        }
        if (lines.empty()) continue;
        const Raster<float> coverage = stroke_coverage(lines, widths, plan.grid, part);
        std::vector<PatternLayerTarget> targets = {{&ones, false, target.material, true}};
        if (target.height != 0.0f) targets.push_back({&ones, true, 0, false});
        add_pattern_to_layers(window, height, splat, part, coverage, targets, target.height);
      }
    }
  }

  std::vector<ContentHash> item_hashes(const WorldPlan& /*plan*/,
                                       const MethodPlan& entry) const override {
    std::vector<ContentHash> out;
    for (const PlannedArea& a : payload_as<AreasPlan>(entry).areas) {  // what render() reads
      Hasher h;
      hash_window(h, a.window);
      h.u64(a.targets.size());
      for (const AreaTarget& t : a.targets)
        h.text(t.stroke_material).u64(t.material).real(t.height);
      h.u64(a.pattern.strokes.size());
      for (const PlacedStroke& s : a.pattern.strokes)
        h.points(s.points).text(s.material).real(s.width);
      out.push_back(h.digest());
    }
    return out;
  }

  // The final height under each instance, from every tile (instance_heights.hpp).
  std::string tile_fact_key() const override { return "instance_heights"; }
  std::string tile_fact(const WorldPlan& plan, const MethodPlan& entry, const Raster<float>& height,
                        const Window& halo, const Window& core) const override {
    return instance_heights_fact(plan.grid, payload_as<AreasPlan>(entry), height, halo, core);
  }

  std::string outputs_stage(const WorldPlan& /*plan*/, const MethodPlan& entry) const override {
    return payload_as<AreasPlan>(entry).names.empty() ? "" : "areas.gpkg";
  }

  // areas.gpkg (layers strokes and instances), instances.csv and instances.json
  // (docs/shape-patterns.md), the instances' z from the tiles' facts.
  void write_outputs(const WorldPlan& plan, const MethodPlan& entry,
                     MethodOutputs& outputs) const override {
    const AreasPlan& areas = payload_as<AreasPlan>(entry);
    InstanceHeights heights = unknown_instance_heights(areas);
    for (const MethodTileFact& f : outputs.tile_facts)
      add_instance_heights(f.fact, f.where, heights);
    std::vector<AreaResult> results;
    for (std::size_t i = 0; i < areas.areas.size(); ++i) {
      const PlannedArea& a = areas.areas[i];
      results.push_back({areas.names.at(a.area_class), a.fid, a.pattern, heights.at(i)});
    }
    const auto stage = [&](const char* name) {
      return outputs.transaction.stage(outputs.dir / name);
    };
    write_area_geopackage(stage("areas.gpkg"), plan.crs_wkt, results);
    write_instances_csv(stage("instances.csv"), results);
    write_instances_json(stage("instances.json"), results);
  }

  void report_json(const RunReport& report, const PipelineConfig& /*config*/,
                   json& out) const override {
    out["areas"] = areas_json(report);
  }

  json encode_report(const MethodPayload& part, PlanObjects& objects) const override {
    return detail::put_report_part<AreasReport>(part, objects);
  }
  std::unique_ptr<MethodPayload> decode_report(const json& value,
                                               PlanObjects& objects) const override {
    return detail::get_report_part<AreasReport>(value, objects, "areas");
  }

  json encode(const MethodPlan& entry, PlanObjects& objects) const override {
    const AreasPlan& areas = payload_as<AreasPlan>(entry);
    return {{"names", areas.names}, {"areas", objects.put_cbor(detail::encode(areas.areas))}};
  }

  void decode(const json& value, PlanObjects& objects, MethodPlan& entry) const override {
    AreasPlan& areas = payload_as<AreasPlan>(entry);
    const std::string where = "plan " + (objects.dir() / "plan.json").string() + ": ";
    detail::decode(value.at("names"), areas.names, where + "methods.areas.names");
    detail::decode(objects.get_cbor(value.at("areas"), "methods.areas.areas"), areas.areas,
                   where + "methods.areas.areas");
  }
};

}  // namespace

const SynthesisMethod& area_method() {
  static const AreaMethod method;
  return method;
}

const AreasPlan* areas_plan(const WorldPlan& plan) {
  const MethodPlan* entry = find_method_plan(plan, "areas");
  return entry ? &payload_as<AreasPlan>(*entry) : nullptr;
}

AreasPlan* areas_plan(WorldPlan& plan) {
  MethodPlan* entry = find_method_plan(plan, "areas");
  return entry ? &payload_as<AreasPlan>(*entry) : nullptr;
}

void add_areas(const PipelineConfig& config, AreaRun run, WorldPlan& plan) {
  AreasPlan* entry = areas_plan(plan);
  if (!entry) fail("plan: no areas entry to add {} areas to", run.areas.size());
  entry->names.clear();
  entry->areas.clear();
  for (const AreaClassConfig& a : area_classes(config)) entry->names.push_back(a.name);
  for (std::size_t i = 0; i < run.areas.size(); ++i) {
    PlannedArea& area = run.areas[i];
    std::vector<Vec2> points;
    double reach = 0.0;
    for (const PlacedStroke& s : area.pattern.strokes) {
      points.insert(points.end(), s.points.begin(), s.points.end());
      reach = std::max(reach, 0.5 * s.width);
    }
    area.window = points.empty() ? Window{} : points_window(points, reach, plan.grid);
    if (area.window.width > 0) {  // off the grid: no band is added
      for (std::size_t t = 0; t < area.targets.size(); ++t) {
        const std::string& material = run.splats[i][t];
        auto it = std::find(plan.splat_materials.begin(), plan.splat_materials.end(), material);
        if (it == plan.splat_materials.end()) {
          plan.splat_materials.push_back(material);
          it = plan.splat_materials.end() - 1;
        }
        area.targets[t].material = std::size_t(it - plan.splat_materials.begin());
      }
    }
    entry->areas.push_back(std::move(area));
  }
  method_report<AreasReport>(plan.report, kAreasMethodName).classes = std::move(run.reports);
}

}  // namespace tw::detail
