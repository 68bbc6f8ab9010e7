#include "pipeline/plan.hpp"

#include <algorithm>
#include <chrono>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/detail/conformance.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/input_check.hpp"
#include "pipeline/detail/plan_stage_cache.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/region.hpp"
#include "pipeline/detail/repair_cache.hpp"
#include "pipeline/detail/ribbon_cache.hpp"
#include "pipeline/detail/stage_clock.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/footprint.hpp"
#include "terrain/splat.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

// The deck heights of bridges and tunnels; plan features come from terrain_features, which
// lists the classes' features in report order.
void report_decks(const TerrainPlan& plan, RunReport& report) {
  std::vector<FeatureReport*> in_order;
  for (FeatureClassReport& c : report.classes)
    for (FeatureReport& f : c.features) in_order.push_back(&f);
  for (std::size_t i = 0; i < plan.features.size(); ++i) {
    const TerrainFeature& f = plan.features[i];
    if (f.structure == Structure::ground || f.width <= 0.0) continue;
    in_order[plan.input_index[i]]->deck_m = {double(plan.profiles[i].front()),
                                             double(plan.profiles[i].back())};
  }
}

// Plans every method of `stage` that the config gives work, in the methods' order, each timed
// as its stage.
void plan_methods(MethodStage stage, MethodContext& context, detail::StageClock& clock) {
  for (MethodPlan& entry : context.plan.methods) {
    const SynthesisMethod& method = *entry.method;
    if (method.stage() != stage || !method.serves(context.config, context.options)) continue;
    clock.start(method.stage_name());
    method.plan(context, entry);
    clock.stop();
  }
}

}  // namespace

namespace detail {

FeatureRibbons synthesis_ribbons(const WorldPlan& plan) {
  FeatureRibbons ribbons;
  ribbons.ribbons = plan.ribbons;
  ribbons.synthesis_junction_discs = plan.synthesis_junction_discs;
  ribbons.synthesis_junctions = plan.synthesis_junctions;
  return ribbons;
}

ExistingFeatures existing_features(const WorldPlan& plan) {
  return {plan.existing.polygons, plan.existing.lines, plan.existing.line_widths};
}

const SynthesisMethod& tasks_method(const WorldPlan& plan) {
  for (const MethodPlan& entry : plan.methods)
    if (entry.method && entry.method->makes_tasks()) return *entry.method;
  fail("plan: no method of the plan makes synthesis tasks");
}

std::vector<StageTiming> plan_after(const PipelineConfig& config, WorldPlan& plan,
                                    const SynthesisMethod& after, Warnings& warnings) {
  const auto first = std::find_if(plan.methods.begin(), plan.methods.end(),
                                  [&](const MethodPlan& e) { return e.method == &after; });
  if (first == plan.methods.end()) fail("plan: no '{}' entry to plan after", after.name());
  PlanOptions options;  // synthesize: the methods after it plan
  const Heightfield heightfield = plan.heights.reader->without_pixels();
  std::vector<std::vector<LineFeature>> lines = plan.lines;
  const FeatureRibbons ribbons = synthesis_ribbons(plan);
  const ExistingFeatures existing = existing_features(plan);
  Warnings read_again;  // the plan's ingest read their inputs and reported their repairs
  MethodContext reading{config, options,   *plan.heights.reader, heightfield, lines,
                        plan,   read_again};
  MethodContext context{config, options, *plan.heights.reader, heightfield, lines, plan, warnings};
  context.existing = &existing;
  context.ribbons = &ribbons;
  std::vector<StageTiming> timings;
  std::vector<MethodPlan*> collected = {&*first};
  for (auto it = std::next(first); it != plan.methods.end(); ++it) {
    const SynthesisMethod& method = *it->method;
    if (method.stage() != MethodStage::placements || !method.serves(config, options)) continue;
    const auto started = std::chrono::steady_clock::now();
    method.ingest(reading, *it);
    method.plan(context, *it);
    timings.push_back(
        {method.stage_name(),
         std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count()});
    collected.push_back(&*it);
  }
  for (MethodPlan* entry : collected) entry->method->collect(context, *entry);
  return timings;
}

}  // namespace detail

std::vector<const SynthesisMethod*> methods_in(const WorldPlan& plan) {
  std::vector<const SynthesisMethod*> methods;
  for (const MethodPlan& entry : plan.methods) methods.push_back(entry.method);
  return methods;
}

void index_plan(WorldPlan& plan) {
  std::vector<Window> features;
  for (const TerrainFeature& f : plan.terrain_features) {
    features.push_back(points_window(f.centerline.points, feature_reach(f), plan.grid));
  }
  plan.feature_index = index_windows(plan.grid, std::move(features));
  std::vector<Window> ribbons;
  for (const auto& class_ribbons : plan.ribbons)
    for (const Ribbon& r : class_ribbons) ribbons.push_back(ribbon_window(r, plan.grid));
  plan.ribbon_index = index_windows(plan.grid, std::move(ribbons));
  for (MethodPlan& entry : plan.methods)
    entry.index = index_windows(plan.grid, entry.method->windows(plan, entry));
}

WorldPlan plan_world(const PipelineConfig& given, const PlanOptions& options, Warnings& warnings) {
  WorldPlan plan;
  RunReport& report = plan.report;
  report.seed = given.seed;
  detail::StageClock clock(report.stages);

  clock.start("ingest");
  const std::optional<fs::path> cache_dir = options.cache_dir ? options.cache_dir : given.cache_dir;
  const std::vector<const SynthesisMethod*>& methods = methods_or_builtin(options.methods);
  detail::check_inputs(given.inputs, cache_dir, methods);
  // Each method's defaults from its inputs (the patterns: synthesis width and delta from the
  // exemplars where a class gives none).
  const PipelineConfig config = with_method_defaults(given, methods);
  // Each stage takes its own options, taken from the config here (detail/stage_options.hpp).
  const detail::HeightfieldInput dem_input = detail::heightfield_input(config);
  const detail::TerrainOptions terrain_options = detail::terrain_options(config);
  const std::shared_ptr<const HeightfieldSource> source =
      detail::open_heightfield_source(dem_input, warnings);
  require_some_height(*source);
  // No pixel is read here: ingest, conformance, the terrain plan and every tile read the
  // windows they touch. A region is a window of the world's grid (detail/region.hpp).
  const Heightfield heightfield = source->without_pixels();
  std::vector<std::vector<LineFeature>> lines;
  // Each line's pieces repaired once: a rerun repairs only the lines that changed
  // (detail/repair_cache.hpp).
  std::optional<detail::RepairCache> repair_cache;
  if (cache_dir) repair_cache.emplace(*cache_dir, warnings);
  const LineRepairMemo repair_memo = repair_cache ? repair_cache->memo() : LineRepairMemo{};
  for (const FeatureClassConfig& feature_class : config.features) {
    const auto started = std::chrono::steady_clock::now();
    // A class whose lines a method makes gets them from its stage, below.
    const auto maker = std::find_if(methods.begin(), methods.end(), [&](const SynthesisMethod* m) {
      return m->makes_lines_of(feature_class);
    });
    lines.push_back(maker != methods.end()
                        ? std::vector<LineFeature>{}
                        : detail::load_feature_class(feature_class, heightfield, warnings,
                                                     repair_memo, methods));
    FeatureClassReport& class_report = report.classes.emplace_back();
    class_report.name = feature_class.name;
    class_report.kind = feature_class.kind;
    class_report.source = maker != methods.end()
                              ? (*maker)->class_source(feature_class)
                              : feature_class.source.string() + ":" + feature_class.layer;
    class_report.ingest_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    plan.class_names.push_back(feature_class.name);
  }
  // Every method has its entry, in the methods' order; each reads its own inputs here.
  MethodContext context{config, options, *source, heightfield, lines, plan, warnings};
  for (const SynthesisMethod* method : methods) {
    MethodPlan& entry = plan.methods.emplace_back(method, method->empty_payload());
    method->ingest(context, entry);
    for (Polygon& polygon : method->reserved(context, entry))
      context.reserved.push_back(std::move(polygon));
  }
  // Before anything is built on the lines: ribbons, synthesis and terrain use the moved ones.
  const auto moves = detail::conform_lines(terrain_options, *source, lines, warnings);
  detail::ExistingFeatures existing =
      detail::load_existing(config.existing, heightfield, config.repair, warnings, repair_memo);
  plan.grid = heightfield.grid;
  plan.output_window = config.region
                           ? detail::region_window(plan.grid, *config.region, heightfield.source)
                           : Window::whole(plan.grid);
  plan.crs_wkt = heightfield.crs_wkt;
  plan.nodata = heightfield.nodata_value;
  report.grid = window_grid(plan.grid, plan.output_window);
  report.crs_wkt = heightfield.crs_wkt;
  report.heightfield = heightfield.source;
  clock.stop();

  // The lines methods make their classes' lines; everything after treats them as read.
  context.existing = &existing;
  plan_methods(MethodStage::lines, context, clock);

  clock.start("ribbons");
  // Through the cache per feature (detail/ribbon_cache.hpp): a moved road makes its own ribbon
  // and searches the junctions near it alone.
  const detail::RibbonOptions ribbon_options = detail::ribbon_options(config, methods);
  std::optional<detail::RibbonCache> ribbon_cache;
  if (cache_dir) ribbon_cache.emplace(*cache_dir, warnings);
  detail::FeatureRibbons ribbons =
      detail::make_feature_ribbons(ribbon_options, lines, heightfield.grid, warnings,
                                   ribbon_cache ? ribbon_cache->steps() : detail::RibbonSteps{});
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    report.classes[c].delta_m = ribbons.delta[c];
    for (std::size_t i = 0; i < lines[c].size(); ++i) {
      FeatureReport& feature = report.classes[c].features.emplace_back();
      feature.fid = lines[c][i].fid;
      feature.length_m = ribbons.lengths[c][i];
      feature.width_m = lines[c][i].width;
      feature.pieces = int(ribbons.ribbons[c][i].pieces.size());
      if (i < moves[c].size()) {  // grown lines are not conformed
        feature.moved_max_m = moves[c][i].max_m;
        feature.moved_mean_m = moves[c][i].mean_m;
      }
      feature.structure = lines[c][i].structure;
      feature.layer = lines[c][i].layer;
    }
  }
  clock.stop();

  // Profiles are sampled once from the unedited terrain (a bound on the earthwork, a feature
  // over nodata are warnings).
  clock.start("terrain");
  plan.terrain_features = detail::terrain_features(terrain_options, lines);
  plan.terrain_params = detail::terrain_params(terrain_options);
  {
    // A rerun whose terrain features and heights are unchanged samples no height here; one
    // with a moved road samples the heights along that road alone.
    const ContentHash heights =
        cache_dir ? detail::heights_identity(dem_input, heightfield) : ContentHash{};
    const ContentHash key =
        detail::terrain_plan_key(heights, plan.terrain_features, plan.terrain_params);
    CacheStatus status;
    plan.terrain = detail::cached_stage<TerrainPlan>(
        cache_dir, "terrain", key, warnings, status, [&](Warnings& w) {
          HeightSampler sampler(*source);
          detail::CachedHeightsAlong along(cache_dir, heights, sample_heights_along(sampler));
          TerrainPlan planned = plan_terrain(heightfield.grid, along.reader(),
                                             plan.terrain_features, plan.terrain_params, w);
          along.store();
          return planned;
        });
  }
  detail::report_earthwork(terrain_options, lines, plan.terrain, report, warnings);
  report_decks(plan.terrain, report);
  clock.stop();

  // The placements methods, in order (the areas avoid the patterns before them).
  context.ribbons = &ribbons;
  plan_methods(MethodStage::placements, context, clock);
  // Collecting the plan: every method's entry as the renderer needs it, its indexes, the tiles.
  clock.start("plan");
  plan.splat_materials = splat_materials();
  for (MethodPlan& entry : plan.methods) entry.method->collect(context, entry);

  plan.existing.polygons = std::move(existing.polygons);
  plan.existing.lines = std::move(existing.lines);
  plan.existing.line_widths = std::move(existing.line_widths);
  plan.junction_discs = std::move(ribbons.junction_discs);
  plan.synthesis_junction_discs = std::move(ribbons.synthesis_junction_discs);
  plan.synthesis_junctions = std::move(ribbons.synthesis_junctions);
  plan.ribbons = std::move(ribbons.ribbons);
  plan.lines = std::move(lines);

  plan.heights.source = heightfield.source;
  plan.heights.reader = source;
  if (!config.heightfield) {
    plan.heights.generated = detail::generated_terrain(dem_input);
  } else {
    plan.heights.file = HeightfieldFile{
        fs::absolute(*config.heightfield).lexically_normal().string(), "", 0, dem_input.options};
  }

  index_plan(plan);
  plan.render.avoidance_max_distance = config.avoidance.max_distance;
  plan.tile_size = config.output.tiles.size;
  plan.tile_overlap = config.output.tiles.overlap;
  plan.tiles = tile_grid(plan.grid, plan.output_window, plan.tile_size, plan.tile_overlap);
  clock.stop();
  return plan;
}

}  // namespace tw
