#include "pipeline/run.hpp"

#include <tbb/global_control.h>
#define XXH_INLINE_ALL

#include <algorithm>
#include <chrono>
#include <fstream>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_folder.hpp"
#include "core/progress.hpp"
#include "geo/input_guard.hpp"
#include "layers/export.hpp"
#include "layers/layer_set.hpp"
#include "layers/vrt.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/job_outputs.hpp"
#include "pipeline/detail/manifest.hpp"
#include "pipeline/detail/report_json.hpp"
#include "pipeline/detail/stage_clock.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/detail/tile_stats.hpp"
#include "pipeline/export_layer_files.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"
#include "pipeline/version.hpp"
#include "synth/placements_io.hpp"

namespace tw {

namespace fs = std::filesystem;

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// "tiles/splat_x1_y2.tif" -> "splat": the layer a tile file belongs to.
std::string layer_of_tile_file(const fs::path& name) {
  const std::string stem = name.stem().string();
  return stem.substr(0, stem.rfind("_x"));
}

// Under strict, any warning is an error: raised before anything is staged for writing.
void finish_warnings(const Warnings& warnings, bool strict, RunReport& report) {
  report.warnings = warnings.list();
  fail_if_strict(report.warnings, strict);
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
  const std::string started_utc = detail::utc_timestamp();
  Warnings warnings;
  const bool strict = options.strict || config.strict;
  set_network_access(options.allow_network);
  check_input_paths(config, options.allow_network);
  // Locked first where terraweave wrote before, so that a second run into it fails at once.
  const fs::path dir = options.output_dir.value_or(config.output.dir);
  std::unique_ptr<OutputFolder> output =
      options.write_outputs ? OutputFolder::lock_if_used(dir) : nullptr;
  // Timed quietly: its errors (a URL without --allow-network, a locked folder) stay one line.
  const StageTiming setup{"setup", seconds_since(run_started)};

  PlanOptions plan_options;
  plan_options.backend = options.backend;
  plan_options.synthesize = options.write_outputs;  // validate synthesizes nothing
  plan_options.cache_dir = options.cache_dir;
  WorldPlan plan = plan_world(config, plan_options, warnings);
  RunReport& report = plan.report;
  report.stages.insert(report.stages.begin(), setup);  // before the plan's stages
  report.started_utc = started_utc;
  detail::StageClock clock(report.stages);
  if (!options.write_outputs) {
    for (const MethodPlan& entry : plan.methods) {  // what the plan did not read
      const std::string stage = entry.method->validate_stage();
      if (stage.empty()) continue;
      clock.start(stage);
      entry.method->validate(config, warnings);
      clock.stop();
    }
    finish_warnings(warnings, strict, report);
    report.total_seconds = seconds_since(run_started);
    detail::add_untimed_stage(report.stages, report.total_seconds);
    return std::move(report);
  }
  clock.start("inputs");  // hashes of every input file, for the manifest
  report.inputs = detail::record_inputs(config.inputs);
  clock.stop();
  finish_warnings(warnings, strict, report);
  for (const EngineExportOptions& engine : config.exports) {
    // Tiled runs and tiled exports read the layers back by windows from the GeoTIFFs.
    if ((plan.tile_size > 0 || export_tile_size(engine, 0) > 0) && !config.output.geotiff)
      fail(
          "export.{}: a tiled run or tiled export reads the run's GeoTIFFs; output.formats "
          "needs geotiff",
          to_string(engine.engine));
    if (engine.layers && plan.tile_size > 0)
      fail("export.{}.layers: written by untiled runs (the run is tiled: output.tiles)",
           to_string(engine.engine));
  }

  if (!output) output = std::make_unique<OutputFolder>(dir);
  OutputFolder& transaction = *output;
  const detail::LayerOptions layer_options = detail::layer_options(config);
  const WriteOptions write_options =
      detail::layer_write_options(layer_options, plan.heights.source);
  const std::vector<ExportCurve> curves = detail::export_curves(layer_options, plan.lines);
  const bool tiled = plan.tile_size > 0;
  report.tiles.size = plan.tile_size;
  report.tiles.overlap = plan.tile_overlap;
  // Tile by tile: each is rendered, written and dropped, so memory follows the tile.
  std::map<std::string, std::vector<fs::path>> tile_tifs;  // per layer, for the mosaics
  std::map<fs::path, FileDigest> tile_digests;  // what the tile cache hashed, for the manifest
  // Per tile, each part's time goes to its stage (`render`, `layers`, `preview`, `exports`).
  double render_seconds = 0.0, layer_seconds = 0.0, preview_seconds = 0.0, export_seconds = 0.0;
  Progress progress("render", std::int64_t(plan.tiles.size()), "tile");
  // Tiled: each tile goes through the tile cache, which renders it (or, under --cache, copies
  // its files when nothing it reads changed) and keeps the numbers the report gives of it.
  const std::optional<fs::path> cache_dir =
      options.cache_dir ? options.cache_dir : config.cache_dir;
  std::optional<detail::TileCache> tile_cache;
  if (tiled) tile_cache.emplace(plan, write_options, cache_dir, warnings);
  // The same writer as terraweave render-tile (detail/job_outputs.hpp): the same bytes.
  const auto write_tile = [&](const TileSpec& tile, LayerSet& layers, OutputStager& stager,
                              std::map<std::string, std::string>& facts) {
    facts = detail::tile_facts(plan, layers, tile);
    detail::write_tile_files(layers, tile, dir, stager, write_options);
  };
  detail::MethodTileFacts method_facts;  // per method, its fact of every tile
  for (const TileSpec& tile : plan.tiles) {
    const auto started = std::chrono::steady_clock::now();
    TileReport& tile_report = report.tiles.tiles.emplace_back();
    tile_report.index = tile.index;
    tile_report.ix = tile.ix;
    tile_report.iy = tile.iy;
    tile_report.window = tile.window;
    tile_report.halo_window = tile.halo_window;
    if (!tiled) {
      LayerSet layers = render_tile(plan, tile);
      render_seconds += seconds_since(started);
      const auto writing = std::chrono::steady_clock::now();
      report.forbidden_pixels += detail::forbidden_in(layers, tile.halo_window, tile.window);
      tile_report.xxh64 = detail::layer_bytes_hash(layers);
      detail::widen(
          report.input_height,
          detail::core_range(read_height_window(plan.heights, plan.grid, tile.halo_window),
                             tile.halo_window, tile.window));
      detail::widen(report.output_height, detail::core_range(find_layer(layers, "height")->bands[0],
                                                             tile.halo_window, tile.window));
      detail::add_method_facts(
          plan, detail::method_tile_facts(plan, find_layer(layers, "height")->bands[0], tile),
          "tile", method_facts);
      write_layer_set(layers, dir, transaction, write_options);
      layer_seconds += seconds_since(writing);
      const auto previewing = std::chrono::steady_clock::now();
      if (config.output.preview) {
        std::vector<std::vector<Vec2>> centerlines;
        for (const auto& feature : plan.terrain_features)
          centerlines.push_back(feature.centerline.points);
        write_preview_png(layers, transaction.stage(dir / "preview.png"), centerlines);
      }
      preview_seconds += seconds_since(previewing);
      const auto exporting = std::chrono::steady_clock::now();
      std::optional<Raster<float>> input_height;  // the layers' "before"
      for (const EngineExportOptions& engine : config.exports) {
        if (export_tile_size(engine, 0) > 0) continue;  // tiles: from the files, below
        if (engine.layers && !input_height)
          input_height = read_height_window(plan.heights, plan.grid, tile.window);
        const EngineExportResult exported =
            export_for_engine(layers, curves, engine, dir / "export" / to_string(engine.engine),
                              transaction, input_height ? &*input_height : nullptr);
        for (const std::string& line : exported.settings) logger().info("{}", line);
        for (const std::string& line : exported.warnings) logger().warn("{}", line);
      }
      export_seconds += seconds_since(exporting);
    } else {
      const detail::TileCache::Outcome outcome = tile_cache->render_or_reuse(
          tile, transaction, dir,
          [&](LayerSet& layers, OutputStager& stager, std::map<std::string, std::string>& facts) {
            write_tile(tile, layers, stager, facts);
          });
      for (const auto& [name, staged] : outcome.staged) {
        if (staged.extension() == ".tif") tile_tifs[layer_of_tile_file(name)].push_back(staged);
      }
      tile_digests.insert(outcome.digests.begin(), outcome.digests.end());
      report.forbidden_pixels += std::stoll(outcome.facts.at("forbidden_pixels"));
      tile_report.xxh64 = std::stoull(outcome.facts.at("xxh64"));
      detail::widen(report.input_height, detail::range_of_fact(outcome.facts.at("input_height")));
      detail::widen(report.output_height, detail::range_of_fact(outcome.facts.at("output_height")));
      detail::add_method_facts(plan, outcome.facts, fmt::format("tile {}", tile.index),
                               method_facts);
      if (cache_dir) tile_report.cache = outcome.status;
      render_seconds += seconds_since(started);
    }
    tile_report.seconds = seconds_since(started);
    progress.advance();
  }
  // The tile cache's warnings (a corrupt entry rebuilt, a cache that cannot be written) count
  // as any other, and fail a strict run before anything is committed.
  finish_warnings(warnings, strict, report);
  const auto mosaics = std::chrono::steady_clock::now();
  std::map<std::string, fs::path> layer_files;  // staged height / splat GeoTIFF or mosaic
  if (tiled) {
    for (const auto& [layer, tifs] : tile_tifs)
      write_vrt_mosaic(layer_files[layer] = transaction.stage(dir / (layer + ".vrt")), tifs);
  } else {
    for (const auto& [name, staged] : transaction.staged_files())
      if (name.parent_path().empty() && name.extension() == ".tif")
        layer_files[name.stem().string()] = staged;
  }
  layer_seconds += seconds_since(mosaics);
  const auto tiled_exports = std::chrono::steady_clock::now();
  for (const EngineExportOptions& engine : config.exports) {
    if (!tiled && export_tile_size(engine, 0) == 0) continue;  // written with the layers
    ExportFiles files{layer_files.at("height"), {}, {}};
    if (layer_files.contains("splat")) files.splat = layer_files.at("splat");
    files.crs_wkt = plan.crs_wkt;
    const EngineExportResult exported =
        export_layer_files(files, curves, engine, plan.tile_size,
                           dir / "export" / to_string(engine.engine), transaction);
    for (const std::string& line : exported.settings) logger().info("{}", line);
    for (const std::string& line : exported.warnings) logger().warn("{}", line);
  }
  export_seconds += seconds_since(tiled_exports);
  report.stages.push_back({"render", render_seconds});
  report.stages.push_back({"layers", layer_seconds});
  if (config.output.preview && !tiled) report.stages.push_back({"preview", preview_seconds});
  if (!config.exports.empty()) report.stages.push_back({"exports", export_seconds});
  logger().info(
      "render: {} tiles, {:.3f} s; layers: {:.3f} s; preview: {:.3f} s; exports: {:.3f} s",
      plan.tiles.size(), render_seconds, layer_seconds, preview_seconds, export_seconds);

  clock.start("features.geojson");
  write_curves_geojson(curves, plan.crs_wkt, transaction.stage(dir / "features.geojson"));
  clock.stop();
  detail::write_method_outputs(plan, std::move(method_facts), dir, transaction, report, &clock);
  clock.start("manifest");  // the hash of every output file
  report.output_files = detail::record_outputs(transaction, tile_digests);
  clock.stop();

  // Only report.json itself and the commit (a rename) come after the total.
  report.total_seconds = seconds_since(run_started);
  detail::add_untimed_stage(report.stages, report.total_seconds);
  write_report(transaction.stage(dir / "report.json"),
               detail::report_to_json(report, config, methods_in(plan)));
  transaction.commit();
  report.outputs = transaction.committed();
  logger().info("wrote {} files to {} in {:.2f} s", report.outputs.size(), dir.string(),
                report.total_seconds);
  return std::move(report);
}

}  // namespace tw
