#include "pipeline/detail/area_method.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/detail/pattern_method.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "raster/footprint.hpp"
#include "raster/stroke_coverage.hpp"
#include "terrain/pattern_layers.hpp"
#include "terrain/splat.hpp"

namespace tw::detail {

using nlohmann::json;

namespace {

class AreaMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return "areas"; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig& config, const PlanOptions& options) const override {
    return options.synthesize && !config.areas.empty();
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<AreasPlan>();
  }

  void ingest(MethodContext& context, MethodPlan& entry) const override {
    payload_as<AreasPlan>(entry).polygons =
        std::make_shared<const std::vector<std::vector<PolygonFeature>>>(
            load_area_polygons(context.config, context.heightfield, context.warnings));
  }

  void plan(MethodContext& context, MethodPlan& entry) const override {
    AreasPlan& areas = payload_as<AreasPlan>(entry);
    // The whole heightfield, also with a region: a close-up's polygons get the leads of the
    // full run, and polygons beyond the region keep theirs.
    HeightSampler heights(context.source);
    const PatternsPlan* patterns = patterns_plan(context.plan);
    const PatternRun* run = patterns && patterns->run ? patterns->run.get() : nullptr;
    areas.run = std::make_shared<AreaRun>(
        synthesize_areas(context.config, *areas.polygons, context.lines, *context.ribbons,
                         *context.existing, run, heights, context.warnings));
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
  for (const AreaClassConfig& a : config.areas) entry->names.push_back(a.name);
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
  plan.report.areas = std::move(run.reports);
}

AreaRun synthesize_plan_areas(const PipelineConfig& config, const WorldPlan& plan,
                              const PatternRun* patterns, Warnings& warnings) {
  // The plan's ingest read these polygons and reported their repairs already.
  Warnings read_again;
  const Heightfield heightfield = plan.heights.reader->without_pixels();
  const std::vector<std::vector<PolygonFeature>> polygons =
      load_area_polygons(config, heightfield, read_again);
  HeightSampler heights(*plan.heights.reader);
  return synthesize_areas(config, polygons, plan.lines, synthesis_ribbons(plan),
                          existing_features(plan), patterns, heights, warnings);
}

}  // namespace tw::detail
