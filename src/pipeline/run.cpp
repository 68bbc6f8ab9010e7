#include "pipeline/run.hpp"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_folder.hpp"
#include "geo/input_guard.hpp"
#include "layers/export.hpp"
#include "layers/layer_set.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/conformance.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/input_check.hpp"
#include "pipeline/detail/patterns.hpp"
#include "pipeline/detail/region.hpp"
#include "pipeline/detail/report_json.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/version.hpp"
#include "raster/avoidance.hpp"
#include "synth/placements_io.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/splat.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

class StageClock {
 public:
  explicit StageClock(std::vector<StageTiming>& timings) : timings_(timings) {}

  void start(std::string stage) {
    stage_ = std::move(stage);
    logger().info("{}...", stage_);
    started_ = std::chrono::steady_clock::now();
  }
  double stop() {
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    timings_.push_back({stage_, seconds});
    logger().info("{}: {:.3f} s", stage_, seconds);
    return seconds;
  }

 private:
  std::vector<StageTiming>& timings_;
  std::string stage_;
  std::chrono::steady_clock::time_point started_;
};

// The avoidance map as a layer: 1 on forbidden pixels, and metres to the nearest of them.
Layer avoidance_layer(AvoidanceMap map) {
  Raster<float> forbidden(map.forbidden.width, map.forbidden.height);
  std::transform(map.forbidden.pixels.begin(), map.forbidden.pixels.end(), forbidden.pixels.begin(),
                 [](std::uint8_t v) { return v ? 1.0f : 0.0f; });
  Layer layer;
  layer.name = "avoidance";
  layer.channels = {"forbidden", "distance"};
  layer.bands.push_back(std::move(forbidden));
  layer.bands.push_back(std::move(map.distance));
  return layer;
}

// Under strict, any warning is an error: raised before anything is staged for writing.
void finish_warnings(const Warnings& warnings, bool strict, RunReport& report) {
  report.warnings = warnings.list();
  if (strict && !report.warnings.empty()) {
    fail("strict: {} warning{} (first: {}); nothing written", report.warnings.size(),
         report.warnings.size() == 1 ? "" : "s", to_string(report.warnings.front()));
  }
}

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

// The run's lines as they were built on (clipped, repaired, conformed), for features.geojson
// and the engines' splines; a closed ring repeats its first point.
std::vector<ExportCurve> export_curves(const PipelineConfig& config,
                                       const std::vector<std::vector<LineFeature>>& lines) {
  std::vector<ExportCurve> curves;
  for (std::size_t c = 0; c < lines.size(); ++c)
    for (const LineFeature& line : lines[c]) {
      ExportCurve& curve = curves.emplace_back();
      curve.feature_class = config.features[c].name;
      curve.kind = std::string(to_string(config.features[c].kind));
      curve.fid = line.fid;
      curve.width = line.width;
      curve.points = line.points;
      if (line.closed && !line.points.empty()) curve.points.push_back(line.points.front());
    }
  return curves;
}

void write_report(const fs::path& path, const nlohmann::json& json) {
  std::ofstream out(path);
  out << json.dump(2) << '\n';
  out.close();
  if (!out) fail("cannot write {}", path.string());
}

}  // namespace

RunReport run_pipeline(const PipelineConfig& config, const RunOptions& options) {
  const auto run_started = std::chrono::steady_clock::now();
  std::optional<tbb::global_control> thread_limit;
  if (options.threads < 0 || options.threads > kMaxThreads) {
    fail("threads: must be in [1, {}] (0: every core), got {}", kMaxThreads, options.threads);
  }
  if (options.threads > 0) {
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism, options.threads);
  }
  RunReport report;
  report.seed = config.seed;
  Warnings warnings;
  const bool strict = options.strict || config.strict;
  StageClock clock(report.stages);
  set_network_access(options.allow_network);
  check_input_paths(config, options.allow_network);
  // Locked first where terraweave wrote before, so that a second run into it fails at once.
  const fs::path dir = options.output_dir.value_or(config.output.dir);
  std::unique_ptr<OutputFolder> output =
      options.write_outputs ? OutputFolder::lock_if_used(dir) : nullptr;

  clock.start("ingest");
  detail::check_inputs(config);
  Heightfield heightfield = detail::load_heightfield(config, warnings);
  report.grid = heightfield.grid;
  report.crs_wkt = heightfield.crs_wkt;
  report.heightfield = heightfield.source;
  std::vector<std::vector<LineFeature>> lines;
  for (const FeatureClassConfig& feature_class : config.features) {
    const auto started = std::chrono::steady_clock::now();
    lines.push_back(detail::load_feature_class(feature_class, heightfield, warnings));
    FeatureClassReport& class_report = report.classes.emplace_back();
    class_report.name = feature_class.name;
    class_report.kind = feature_class.kind;
    class_report.source = feature_class.source.string() + ":" + feature_class.layer;
    class_report.ingest_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  }
  // Before anything is built on the lines: ribbons, synthesis and terrain use the moved ones.
  const auto moves = detail::conform_lines(config, heightfield, lines, warnings);
  detail::ExistingFeatures existing =
      detail::load_existing(config.existing, heightfield, config.repair, warnings);
  if (config.region) {  // features were read on the whole heightfield, the rest is the region
    heightfield = detail::crop_to_region(heightfield, *config.region,
                                         config.resolution.value_or(heightfield.grid.pixel_width),
                                         config.resampling);
    report.grid = heightfield.grid;
  }
  clock.stop();

  clock.start("ribbons");
  const detail::FeatureRibbons ribbons =
      detail::make_feature_ribbons(config, lines, heightfield.grid, warnings);
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    report.classes[c].delta_m = ribbons.delta[c];
    for (std::size_t i = 0; i < lines[c].size(); ++i) {
      FeatureReport& feature = report.classes[c].features.emplace_back();
      feature.fid = lines[c][i].fid;
      feature.length_m = ribbons.lengths[c][i];
      feature.width_m = lines[c][i].width;
      feature.pieces = int(ribbons.ribbons[c][i].pieces.size());
      feature.moved_max_m = moves[c][i].max_m;
      feature.moved_mean_m = moves[c][i].mean_m;
      feature.structure = lines[c][i].structure;
      feature.layer = lines[c][i].layer;
    }
  }
  clock.stop();
  if (!options.write_outputs) {
    // Validate plans the terrain too (applying nothing) for its warnings: a feature over
    // nodata, a bound on the earthwork.
    const TerrainPlan plan =
        plan_terrain(heightfield.height, heightfield.grid, detail::terrain_features(config, lines),
                     detail::terrain_params(config), warnings);
    detail::report_earthwork(config, lines, plan, report, warnings);
    finish_warnings(warnings, strict, report);
    report.total_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - run_started).count();
    return report;
  }

  clock.start("avoidance");
  AvoidanceMap avoidance = detail::build_run_avoidance(existing, ribbons, heightfield.grid);
  report.forbidden_pixels =
      std::count(avoidance.forbidden.pixels.begin(), avoidance.forbidden.pixels.end(), 1);
  clock.stop();

  detail::PatternRun patterns;
  if (!config.synthesis_order.empty()) {
    clock.start("synthesis");
    patterns = detail::synthesize_patterns(config, lines, ribbons, existing, {options.backend});
    for (const detail::FeaturePattern& p : patterns.patterns) {
      FeatureReport& feature = report.classes[p.class_index].features[p.feature_index];
      feature.synthesis = p.report;
      report.pattern_violations += p.report.violations;
    }
    clock.stop();
  }

  clock.start("terrain");
  const std::vector<TerrainFeature> features = detail::terrain_features(config, lines);
  const TerrainParams params = detail::terrain_params(config);
  const Window whole = Window::whole(heightfield.grid);
  const TerrainPlan terrain_plan =
      plan_terrain(heightfield.height, heightfield.grid, features, params, warnings);
  detail::report_earthwork(config, lines, terrain_plan, report, warnings);
  report_decks(terrain_plan, report);
  apply_terrain(heightfield.height, heightfield.grid, whole, terrain_plan);
  SplatLayers splat = compute_splat(heightfield.grid, whole, features, params, heightfield.height);
  detail::apply_patterns(patterns, config, heightfield.grid, heightfield.height, splat);
  clock.stop();

  finish_warnings(warnings, strict, report);
  clock.start("layers");
  if (!output) output = std::make_unique<OutputFolder>(dir);
  OutputFolder& transaction = *output;
  LayerSet layers;
  layers.grid = heightfield.grid;
  layers.crs_wkt = heightfield.crs_wkt;
  layers.nodata = heightfield.nodata_value;
  layers.layers.push_back(height_layer(std::move(heightfield.height)));
  layers.layers.push_back(splat_layer(std::move(splat)));
  layers.layers.push_back(avoidance_layer(std::move(avoidance)));
  WriteOptions write_options;
  write_options.exr = config.output.exr;
  write_options.geotiff = config.output.geotiff;
  write_options.preview = false;  // drawn below, with the centerlines on top
  write_options.exr_half = config.output.exr_half;
  write_options.geotiff_options = config.output.tiff;
  write_options.geotiff_options.metadata = {
      {"TERRAWEAVE_VERSION", kTerraweaveVersion},
      {"TERRAWEAVE_PIPELINE", config.file.empty() ? "-" : config.file.filename().string()},
      {"TERRAWEAVE_SEED", std::to_string(config.seed)},
      {"TERRAWEAVE_HEIGHTFIELD", fs::path(heightfield.source).filename().string()}};
  write_layer_set(layers, dir, transaction, write_options);
  if (config.output.preview) {
    std::vector<std::vector<Vec2>> centerlines;
    for (const auto& feature : features) centerlines.push_back(feature.centerline.points);
    write_preview_png(layers, transaction.stage(dir / "preview.png"), centerlines);
  }
  const std::vector<ExportCurve> curves = export_curves(config, lines);
  write_curves_geojson(curves, layers.crs_wkt, transaction.stage(dir / "features.geojson"));
  for (const EngineExportOptions& engine : config.exports) {
    const EngineExportResult exported = export_for_engine(
        layers, curves, engine, dir / "export" / to_string(engine.engine), transaction);
    for (const std::string& line : exported.settings) logger().info("{}", line);
  }
  // Placements: placements/<class>_<fid>.json (a multi-part FID adds _<part>). The backend
  // field is left out so that every backend writes the same bytes.
  std::map<std::string, int> parts;
  for (const detail::FeaturePattern& p : patterns.patterns) {
    const FeatureClassConfig& c = config.features[p.class_index];
    std::string name = fmt::format("{}_{}", c.name, lines[p.class_index][p.feature_index].fid);
    if (const int part = parts[name]++; part > 0) name += fmt::format("_{}", part);
    const std::string file = "placements/" + name + ".json";
    Synthesis saved = p.synthesis;
    saved.backend.clear();
    save_placements(saved, patterns.exemplars[p.exemplar_index].path,
                    transaction.stage(dir / file).string());
    report.classes[p.class_index].features[p.feature_index].synthesis->placements = file;
  }
  clock.stop();

  report.total_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - run_started).count();
  write_report(transaction.stage(dir / "report.json"), detail::report_to_json(report, config));
  transaction.commit();
  report.outputs = transaction.committed();
  logger().info("wrote {} files to {} in {:.2f} s", report.outputs.size(), dir.string(),
                report.total_seconds);
  return report;
}

}  // namespace tw
