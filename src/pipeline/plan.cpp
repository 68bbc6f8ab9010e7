#include "pipeline/plan.hpp"

#include <algorithm>
#include <chrono>

#include "core/error.hpp"
#include "core/log.hpp"
#include "geo/height_sampler.hpp"
#include "pipeline/detail/areas.hpp"
#include "pipeline/detail/conformance.hpp"
#include "pipeline/detail/grown_classes.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/input_check.hpp"
#include "pipeline/detail/network_classes.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/region.hpp"
#include "pipeline/detail/stage_clock.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/detail/synthesis_cache.hpp"
#include "pipeline/detail/synthesis_defaults.hpp"
#include "raster/footprint.hpp"
#include "synth/pattern_canvas.hpp"

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

std::vector<ChannelMapping> mappings_of(const FeatureClassConfig& c, const Exemplar& exemplar) {
  if (!c.synthesis->channels.empty()) return c.synthesis->channels;
  std::vector<ChannelMapping> mappings = {{"A", "splat." + c.name + "_pattern"}};
  if (exemplar.channel_index("height") >= 0) mappings.push_back({"height", "height"});
  return mappings;
}

// The patterns as the renderer needs them, and their splat materials in order of first use
// (the order an untiled render adds them in). Throws tw::Error naming the class and the channel
// when an exemplar lacks a mapped channel.
void plan_patterns(const PipelineConfig& config, detail::PatternRun run, WorldPlan& plan) {
  plan.splat_materials = splat_materials();
  const auto material_index = [&](const std::string& target) {
    const std::string material = target.substr(6);  // after "splat."
    auto it = std::find(plan.splat_materials.begin(), plan.splat_materials.end(), material);
    if (it == plan.splat_materials.end()) {
      plan.splat_materials.push_back(material);
      it = plan.splat_materials.end() - 1;
    }
    return std::size_t(it - plan.splat_materials.begin());
  };
  for (detail::FeaturePattern& p : run.patterns) {
    const FeatureClassConfig& c = config.features[p.class_index];
    const Exemplar& exemplar = run.exemplars[p.exemplar_index];
    if (!p.synthesized) {  // outside the region: its bands still come in the same order
      if (p.on_ground && ribbon_window(p.ribbon, plan.grid).width > 0)
        for (const ChannelMapping& m : mappings_of(c, exemplar))
          if (m.target != "height") material_index(m.target);
      continue;
    }
    PlannedPattern& planned = plan.patterns.emplace_back();
    planned.class_index = p.class_index;
    planned.feature_index = p.feature_index;
    planned.exemplar_index = p.exemplar_index;
    planned.on_ground = p.on_ground;
    // The render reaches kCanvasHalo cells beyond the pieces (synth/pattern_canvas.hpp).
    const Window on_grid = p.on_ground ? ribbon_window(p.ribbon, plan.grid) : Window{};
    planned.window = on_grid.width > 0 ? grow_window(on_grid, kCanvasHalo, plan.grid) : Window{};
    planned.ribbon = std::move(p.ribbon);
    planned.synthesis = std::move(p.synthesis);
    planned.stitch = c.synthesis->stitch;
    planned.feather = c.synthesis->feather;
    planned.height_detail = float(c.synthesis->height_detail);
    if (planned.window.width == 0) continue;  // off the grid: no band is added
    for (const ChannelMapping& m : mappings_of(c, exemplar)) {
      PatternTarget& target = planned.targets.emplace_back();
      target.exemplar_channel = exemplar.channel_index(m.channel);
      if (target.exemplar_channel < 0) {
        fail("features.{}.synthesis.channels.{}: exemplar {} has no channel '{}' (it has {})",
             c.name, m.channel, exemplar.path, m.channel, fmt::join(exemplar.channel_names, ", "));
      }
      target.to_height = m.target == "height";
      target.is_alpha = m.channel == "A";
      if (target.to_height) continue;
      target.material = material_index(m.target);
    }
  }
  plan.exemplars = std::move(run.exemplars);
}

// The synthesis ribbon's width and delta in the feature's report, and where they came from.
void record_geometry(const SynthesisConfig& s, FeatureReport& feature) {
  FeatureSynthesisReport& r = *feature.synthesis;
  r.width_m = s.width.value_or(feature.width_m);
  r.width_from = s.width_of_feature ? "feature" : s.width_from_exemplar ? "exemplar" : "config";
  r.delta_m = s.delta.value_or(0.0);
  r.delta_from = s.delta_from_exemplar ? "exemplar" : "config";
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

void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan,
                  Warnings& warnings) {
  for (std::size_t c = 0; c < config.features.size(); ++c)
    if (config.features[c].synthesis && plan.report.classes[c].grow)
      plan.report.classes[c].grow->synthesis.emplace();
  for (const FeaturePattern& p : patterns.patterns) {
    if (!p.synthesized) continue;  // left out by a region (PatternOptions::wanted)
    FeatureClassReport& feature_class = plan.report.classes[p.class_index];
    FeatureReport& feature = feature_class.features[p.feature_index];
    feature.synthesis = p.report;
    record_geometry(*config.features[p.class_index].synthesis, feature);
    feature.cache = p.cache;
    plan.report.pattern_violations += p.report.violations;
    if (feature_class.grow) {
      const bool bare = std::size_t(p.report.empty_pieces) == p.synthesis.placements.size();
      ++(bare ? feature_class.grow->synthesis->no_room : feature_class.grow->synthesis->dressed);
    }
  }
  // Bare lines are no error (short lines between joints), but a class none of whose lines
  // took its pattern is a setting that does not fit (too wide, too long pieces).
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    const auto& grow = plan.report.classes[c].grow;
    if (!grow || !grow->synthesis || grow->synthesis->dressed > 0 || grow->synthesis->no_room == 0)
      continue;
    warnings.add("grown_undressed", "features." + config.features[c].name, std::nullopt,
                 fmt::format("synthesis dressed 0 of {} grown lines: every piece had no room "
                             "(a narrower synthesis.width or a shorter delta may fit)",
                             grow->synthesis->no_room));
  }
  plan_patterns(config, std::move(patterns), plan);
}

void add_areas(const PipelineConfig& config, AreaRun run, WorldPlan& plan) {
  plan.area_names.clear();
  plan.areas.clear();
  for (const AreaClassConfig& a : config.areas) plan.area_names.push_back(a.name);
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
    plan.areas.push_back(std::move(area));
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

}  // namespace detail

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
  std::vector<Window> patterns;
  for (const PlannedPattern& p : plan.patterns) patterns.push_back(p.window);
  plan.pattern_index = index_windows(plan.grid, std::move(patterns));
  std::vector<Window> areas;
  for (const PlannedArea& a : plan.areas) areas.push_back(a.window);
  plan.area_index = index_windows(plan.grid, std::move(areas));
}

WorldPlan plan_world(const PipelineConfig& given, const PlanOptions& options, Warnings& warnings) {
  WorldPlan plan;
  RunReport& report = plan.report;
  report.seed = given.seed;
  detail::StageClock clock(report.stages);

  clock.start("ingest");
  detail::check_inputs(given);
  // Synthesis width and delta from the exemplars where a class gives none.
  const PipelineConfig config = detail::with_exemplar_defaults(given);
  const std::shared_ptr<const HeightfieldSource> source =
      detail::open_heightfield_source(config, warnings);
  require_some_height(*source);
  // No pixel is read here: ingest, conformance, the terrain plan and every tile read the
  // windows they touch. A region is a window of the world's grid (detail/region.hpp).
  const Heightfield heightfield = source->without_pixels();
  std::vector<std::vector<LineFeature>> lines;
  for (const FeatureClassConfig& feature_class : config.features) {
    const auto started = std::chrono::steady_clock::now();
    // A grown class's lines come from the growth stage, below.
    lines.push_back(feature_class.grow || feature_class.network
                        ? std::vector<LineFeature>{}
                        : detail::load_feature_class(feature_class, heightfield, warnings));
    FeatureClassReport& class_report = report.classes.emplace_back();
    class_report.name = feature_class.name;
    class_report.kind = feature_class.kind;
    class_report.source = feature_class.network
                              ? feature_class.network->exemplar
                              : feature_class.source.string() + ":" + feature_class.layer;
    class_report.ingest_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    plan.class_names.push_back(feature_class.name);
  }
  const std::vector<std::vector<PolygonFeature>> area_polygons =
      detail::load_area_polygons(config, heightfield, warnings);
  // Before anything is built on the lines: ribbons, synthesis and terrain use the moved ones.
  const auto moves = detail::conform_lines(config, *source, lines, warnings);
  detail::ExistingFeatures existing =
      detail::load_existing(config.existing, heightfield, config.repair, warnings);
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

  // Grown lines avoid the lines read and the existing features; everything after treats them
  // as the class's features.
  if (std::any_of(config.features.begin(), config.features.end(),
                  [](const FeatureClassConfig& c) { return bool(c.grow); })) {
    clock.start("grow");
    plan.grown = detail::grow_classes(config, *source, heightfield, existing, lines, report.classes,
                                      warnings);
    for (const FeatureClassReport& c : report.classes)
      if (c.grow)
        report.grown_crossings +=
            c.grow->crossings.grown + c.grow->crossings.feature + c.grow->crossings.forbidden;
    clock.stop();
  }

  // Networks grow after the grown classes, off everything before them; once, in the plan, so
  // that every tile and worker sees the same lines.
  if (std::any_of(config.features.begin(), config.features.end(),
                  [](const FeatureClassConfig& c) { return bool(c.network); })) {
    clock.start("network");
    detail::grow_network_classes(config, *source, heightfield, existing, lines, report.classes,
                                 warnings);
    clock.stop();
  }

  clock.start("ribbons");
  detail::FeatureRibbons ribbons =
      detail::make_feature_ribbons(config, lines, heightfield.grid, warnings);
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    report.classes[c].delta_m = ribbons.delta[c];
    for (std::size_t i = 0; i < lines[c].size(); ++i) {
      if (report.classes[c].grow && ribbons.ribbons[c][i].pieces.empty())
        ++report.classes[c].grow->short_lines;
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
  plan.terrain_features = detail::terrain_features(config, lines);
  plan.terrain_params = detail::terrain_params(config);
  {
    HeightSampler heights(*source);
    plan.terrain = plan_terrain(heights, plan.terrain_features, plan.terrain_params, warnings);
  }
  detail::report_earthwork(config, lines, plan.terrain, report, warnings);
  report_decks(plan.terrain, report);
  clock.stop();

  std::optional<detail::PatternRun> patterns;
  if (options.synthesize && !config.synthesis_order.empty()) {
    clock.start("synthesis");
    detail::SynthesisCache cache(options.cache_dir ? options.cache_dir : config.cache_dir,
                                 warnings);
    detail::PatternOptions pattern_options;
    pattern_options.backend = options.backend;
    pattern_options.cache = &cache;
    if (config.region) {  // the patterns whose render reaches the region, and what they avoid
      const GridSpec output = window_grid(plan.grid, plan.output_window);
      const double reach = (kCanvasHalo + 2) * std::max(output.pixel_width, output.pixel_height);
      pattern_options.wanted = [output, reach](const GridSpec& canvas) {
        return canvas.origin_x - reach < output.origin_x + output.width * output.pixel_width &&
               output.origin_x < canvas.origin_x + canvas.width * canvas.pixel_width + reach &&
               canvas.origin_y - canvas.height * canvas.pixel_height - reach < output.origin_y &&
               output.origin_y - output.height * output.pixel_height < canvas.origin_y + reach;
      };
    }
    patterns = detail::synthesize_patterns(config, lines, ribbons, existing, pattern_options);
    clock.stop();
  }
  // Areas after the curve patterns, which they avoid.
  detail::AreaRun areas;
  if (options.synthesize && !config.areas.empty()) {
    clock.start("areas");
    // The whole heightfield, also with a region: a close-up's polygons get the leads of the
    // full run, and polygons beyond the region keep theirs.
    HeightSampler heights(*source);
    areas = detail::synthesize_areas(config, area_polygons, lines, ribbons, existing,
                                     patterns ? &*patterns : nullptr, heights, warnings);
    clock.stop();
  }
  // Collecting the plan: patterns and areas into its indexes, the tiles.
  clock.start("plan");
  if (patterns) {
    detail::add_patterns(config, std::move(*patterns), plan, warnings);
  } else {
    plan.splat_materials = splat_materials();
  }
  detail::add_areas(config, std::move(areas), plan);

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
    plan.heights.generated = detail::generated_terrain(config);
  } else {
    plan.heights.file =
        HeightfieldFile{fs::absolute(*config.heightfield).lexically_normal().string(), "", 0,
                        detail::heightfield_options(config)};
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
