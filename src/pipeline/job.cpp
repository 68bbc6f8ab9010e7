#include "pipeline/job.hpp"

#include <unistd.h>

#include <chrono>
#include <nlohmann/json.hpp>
#include <system_error>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_hash.hpp"
#include "core/file_io.hpp"
#include "core/log.hpp"
#include "core/output_folder.hpp"
#include "core/staging_registry.hpp"
#include "geo/input_guard.hpp"
#include "layers/layer_set.hpp"
#include "layers/write.hpp"
#include "pipeline/detail/job_files.hpp"
#include "pipeline/detail/job_outputs.hpp"
#include "pipeline/detail/manifest.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/detail/tile_stats.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/plan_io.hpp"

namespace tw {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using detail::kJobFormat;
constexpr const char* kTileResultFormat = "terraweave.tile";

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Stages a tile's files beside their final names (temporaries named by host and pid, so two
// workers rendering the same tile never share one) and renames them into place.
class TileStager final : public OutputStager {
 public:
  fs::path stage(const fs::path& final_path) override {
    std::error_code ec;
    fs::create_directories(final_path.parent_path(), ec);
    if (ec) fail("cannot create {}: {}", final_path.parent_path().string(), ec.message());
    staged_.push_back({StagedPath(temporary_beside(final_path)), final_path});
    return staged_.back().temporary.path();
  }
  void commit() {
    for (auto& [temporary, final_path] : staged_) {
      std::error_code ec;
      fs::rename(temporary.path(), final_path, ec);
      if (ec) fail("cannot write {}: {}", final_path.string(), ec.message());
      temporary.release();
    }
    staged_.clear();
  }

 private:
  struct Entry {
    StagedPath temporary;  // removed with the stager unless committed
    fs::path final_path;
  };
  std::vector<Entry> staged_;
};

fs::path tiles_dir(const fs::path& plan_dir, const std::string& plan) {
  return plan_dir / ("tiles-" + plan);
}
fs::path results_dir(const fs::path& plan_dir, const std::string& plan) {
  return plan_dir / ("results-" + plan);
}

// The current folder for the lifetime of the object (finish reloads the pipeline where its
// --set paths were given).
class ScopedCurrentPath {
 public:
  explicit ScopedCurrentPath(const fs::path& dir) : previous_(fs::current_path()) {
    std::error_code ec;
    fs::current_path(dir, ec);
    if (ec) fail("cannot enter {} (where the plan was made): {}", dir.string(), ec.message());
  }
  ~ScopedCurrentPath() {
    std::error_code ignored;
    fs::current_path(previous_, ignored);
  }

 private:
  fs::path previous_;
};

constexpr const char* kFinishedFormat = "terraweave.finished";

void delete_tiles(const fs::path& plan_dir, const std::string& plan) {
  std::error_code ec;
  fs::remove_all(tiles_dir(plan_dir, plan), ec);
  fs::remove_all(results_dir(plan_dir, plan), ec);
}

// finished.json: the plan a finish committed, the hash of the report.json it wrote and the
// files, relative to the output folder.
void record_finished(const fs::path& plan_dir, const std::string& plan, const fs::path& out,
                     const std::vector<fs::path>& outputs) {
  json files = json::array();
  for (const fs::path& f : outputs) files.push_back(f.lexically_relative(out).generic_string());
  const json record = {{"format", kFinishedFormat},
                       {"version", kPlanVersion},
                       {"plan", plan},
                       {"report_xxh3_128", file_digest(out / "report.json").xxh3_128},
                       {"outputs", files}};
  write_file_atomic(plan_dir / "finished.json", record.dump(1) + "\n");
}

// The run finish committed for `plan`, when the output folder still holds it (its report.json
// unchanged since).
std::optional<RunReport> finished_run(const fs::path& plan_dir, const std::string& plan,
                                      const fs::path& out) {
  std::error_code ec;
  if (!fs::is_regular_file(plan_dir / "finished.json", ec) ||
      !fs::is_regular_file(out / "report.json", ec))
    return std::nullopt;
  const json record = read_plan_file(plan_dir / "finished.json", kFinishedFormat);
  if (record.value("plan", "") != plan ||
      record.value("report_xxh3_128", "") != file_digest(out / "report.json").xxh3_128)
    return std::nullopt;
  RunReport report;
  for (const json& f : record.at("outputs")) report.outputs.push_back(out / f.get<std::string>());
  return report;
}

}  // namespace

namespace detail {

void delete_temporaries(const fs::path& plan_dir) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(plan_dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.starts_with(".") && name.find(".tmp-") != std::string::npos) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

void delete_other_plans(const fs::path& plan_dir, const std::string& plan) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(plan_dir, ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if ((name.starts_with("tiles-") || name.starts_with("results-")) && !name.ends_with(plan)) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

json read_job(const fs::path& plan_dir) {
  std::error_code ec;
  if (fs::exists(plan_dir / "completing.json", ec))
    fail(
        "{}: complete-plan was interrupted while it replaced the plan's files (completing.json); "
        "run it again: terraweave complete-plan {}",
        plan_dir.string(), plan_dir.string());
  if (!fs::is_regular_file(plan_dir / "job.json", ec))
    fail("{}: missing; plan again (terraweave plan PIPELINE --out DIR)",
         (plan_dir / "job.json").string());
  json job = read_plan_file(plan_dir / "job.json", kJobFormat);
  const std::string hash = plan_hash(plan_dir);
  if (job.value("plan", "") != hash)
    fail("{}: job.json belongs to plan {}, plan.json is {}; plan again ({})", plan_dir.string(),
         job.value("plan", ""), hash, plan_again(plan_dir));
  return job;
}

std::string plan_again(const fs::path& plan_dir) {
  try {
    const json job = read_plan_file(plan_dir / "job.json", kJobFormat);
    std::string command =
        fmt::format("terraweave plan {} --out {}", job.at("pipeline").get<std::string>(),
                    job.at("output_dir").get<std::string>());
    for (const json& o : job.at("overrides")) command += " --set " + o.get<std::string>();
    if (job.contains("variables") && job["variables"].is_string())
      command += " --vars " + job["variables"].get<std::string>();
    if (job.value("synthesis_tasks", std::size_t(0)) > 0) command += " --synthesis tasks";
    if (job.contains("cache") && job["cache"].is_string())
      command += " --cache " + job["cache"].get<std::string>();
    if (job.contains("backend") && job["backend"].is_string())
      command += " --backend " + job["backend"].get<std::string>();
    return command;
  } catch (const std::exception&) {  // job.json unreadable: the generic form
    return "terraweave plan PIPELINE --out DIR";
  }
}

PipelineConfig job_config(const json& job) {
  const fs::path pipeline = job.at("pipeline").get<std::string>();
  if (content_hash(read_file_bytes(pipeline)) != job.value("pipeline_xxh3_128", ""))
    fail("{}: changed since it was planned (plan again)", pipeline.string());
  std::vector<Override> overrides;
  for (const json& o : job.at("overrides"))
    overrides.push_back(parse_override(o.get<std::string>()));
  // The variables file of `plan --vars` (before, the tasks read the pipeline without it: a
  // ${name} was an error, issue #24 item 2).
  Variables variables;
  if (job.contains("variables") && job["variables"].is_string()) {
    const fs::path file = job["variables"].get<std::string>();
    if (content_hash(read_file_bytes(file)) != job.value("variables_xxh3_128", ""))
      fail("{}: changed since it was planned (plan again)", file.string());
    variables = load_variables(file);
  }
  const ScopedCurrentPath cwd(job.at("cwd").get<std::string>());
  return load_pipeline(pipeline, overrides, variables);
}

std::optional<fs::path> job_cache(const json& job) {
  if (!job.contains("cache") || job["cache"].is_null()) return std::nullopt;
  return fs::path(job["cache"].get<std::string>());
}

}  // namespace detail

PlannedJob plan_job(const PipelineConfig& config, const PlanJobOptions& options) {
  const auto started = std::chrono::steady_clock::now();
  set_network_access(options.allow_network);
  check_input_paths(config, options.allow_network);
  const fs::path out = fs::absolute(options.output_dir).lexically_normal();
  // The folder's lock while the plan is written: not while a run or a finish writes there.
  const OutputFolder lock(out);
  Warnings warnings;
  PlanOptions plan_options;
  plan_options.backend = options.backend;
  // --cache, else the pipeline's cache key; absolute, as every worker reads it.
  std::optional<fs::path> cache = options.cache_dir ? options.cache_dir : config.cache_dir;
  if (cache) cache = fs::absolute(*cache).lexically_normal();
  plan_options.cache_dir = cache;
  plan_options.synthesize = !options.synthesis_tasks;
  if (options.synthesis_tasks && config.region)
    fail(
        "region: a close-up synthesizes only what reaches it, in the plan; use --synthesis inline");
  if (config.output.tiles.size <= 0)
    fail(
        "output.tiles.size: a distributed run renders tiles; set it (e.g. --set "
        "output.tiles.size=512)");
  WorldPlan plan = plan_world(config, plan_options, warnings);
  const fs::path plan_dir = out / ".terraweave" / "plan";
  std::optional<json> syntheses;
  if (options.synthesis_tasks)
    syntheses =
        detail::plan_synthesis_tasks(config, plan, options.backend, cache, plan_dir, warnings);
  // The methods after the one whose syntheses are tasks plan in complete-plan, after the tasks
  // (they may avoid its placements); with no synthesis to wait for, the plan is complete here.
  if (syntheses && syntheses->at("features").empty()) {
    detail::plan_after(config, plan, detail::tasks_method(plan), warnings);
    index_plan(plan);
  }
  plan.report.warnings = warnings.list();
  fail_if_strict(plan.report.warnings, options.strict || config.strict);
  // job.json is written last, so the old plan.json is deleted first: a plan.json beside an
  // older job.json would be a mixed plan. An earlier plan's completion journal and finish
  // record go too (they would name this plan's hash when the inputs did not change).
  std::error_code ec;
  fs::remove(plan_dir / "completing.json", ec);
  fs::remove(plan_dir / "finished.json", ec);
  fs::remove(plan_dir / "plan.json", ec);
  const std::string hash = save_plan(plan, plan_dir);
  const std::size_t pending = detail::write_synthesis_tasks(plan_dir, syntheses, hash);
  const json job = {
      {"format", kJobFormat},
      {"version", kPlanVersion},
      {"plan", hash},
      {"pipeline", fs::absolute(config.file).string()},
      {"pipeline_xxh3_128", content_hash(read_file_bytes(config.file))},
      {"overrides", options.overrides},
      {"variables",
       options.variables.empty() ? json() : json(fs::absolute(options.variables).string())},
      {"variables_xxh3_128",
       options.variables.empty() ? json() : json(content_hash(read_file_bytes(options.variables)))},
      {"cwd", fs::current_path().string()},
      {"output_dir", out.string()},
      {"exr", config.output.exr},
      {"geotiff", config.output.geotiff},
      {"cache", cache ? json(cache->string()) : json()},
      {"backend", options.backend ? json(*options.backend) : json()},
      {"plan_seconds", seconds_since(started)},
      // What complete-plan must find: without these, a deleted syntheses.json would read as
      // "no syntheses" and finish would commit a world without its syntheses (issue #24).
      {"synthesis_tasks", pending},
      {"syntheses_complete", pending == 0},
      // syntheses.json is checked against it (detail::read_syntheses).
      {"syntheses_xxh3_128", pending > 0 ? json(detail::syntheses_hash(*syntheses)) : json()},
  };
  write_file_atomic(plan_dir / "job.json", job.dump(1) + "\n");
  detail::delete_other_plans(plan_dir, hash);
  logger().info("plan {}: {} tiles, {} syntheses to run in {}", hash, plan.tiles.size(), pending,
                plan_dir.string());
  return {plan_dir, hash, plan.tiles.size(), plan.report.warnings.size(), pending};
}

fs::path find_plan_dir(const fs::path& path) {
  std::error_code ec;
  if (fs::is_regular_file(path / "plan.json", ec)) return path;
  if (fs::is_regular_file(path / ".terraweave" / "plan" / "plan.json", ec))
    return path / ".terraweave" / "plan";
  fail("{}: no plan here (neither plan.json nor .terraweave/plan/plan.json; run terraweave plan)",
       path.string());
}

TileJobResult render_job_tile(const fs::path& plan_dir, int tile) {
  test_pause_point("render-tile");
  const auto started = std::chrono::steady_clock::now();
  const json job = detail::read_job(plan_dir);
  const std::string hash = plan_hash(plan_dir);
  detail::require_complete_plan(plan_dir, hash);
  const WorldPlan plan = load_plan_for_tile(plan_dir, tile);
  const TileSpec& spec = plan.tiles[std::size_t(tile)];
  const WriteOptions write = detail::layer_write_options(
      detail::layer_options(detail::job_config(job)), plan.heights.source);
  const fs::path dir = tiles_dir(plan_dir, hash);
  // Through the tile cache, as terraweave run renders a tile (keys only without a cache).
  Warnings warnings;  // a corrupt entry is rebuilt (run does not report it either)
  detail::TileCache cache(plan, write, detail::job_cache(job), warnings);
  TileStager stager;
  const detail::TileCache::Outcome outcome = cache.render_or_reuse(
      spec, stager, dir,
      [&](LayerSet& layers, OutputStager& to, std::map<std::string, std::string>& facts) {
        facts = detail::tile_facts(plan, layers, spec);
        detail::write_tile_files(layers, spec, dir, to, write);
      });
  stager.commit();

  TileJobResult result;
  result.tile = tile;
  json files = json::array();
  // With a cache, the tile cache hashed each file as it kept it (or checked the entry it
  // reused): those digests, not a second read. Without one, the files were just written: hashed
  // from the page cache in 1 MiB chunks (the same XXH3-128 as content_hash of their bytes).
  for (const auto& [relative, staged] : outcome.staged) {
    const auto cached = outcome.digests.find(relative);
    const FileDigest digest =
        cached != outcome.digests.end() ? cached->second : file_digest(dir / relative);
    result.files.push_back(relative);
    files.push_back({{"file", relative.generic_string()},
                     {"bytes", digest.bytes},
                     {"xxh3_128", digest.xxh3_128}});
  }
  result.seconds = seconds_since(started);
  const CacheStatus& status = outcome.status;
  json record = {{"format", kTileResultFormat},
                 {"version", kPlanVersion},
                 {"plan", hash},
                 {"tile", tile},
                 {"files", files},
                 {"forbidden_pixels", std::stoll(outcome.facts.at("forbidden_pixels"))},
                 {"xxh64", std::stoull(outcome.facts.at("xxh64"))},
                 {"input_height", outcome.facts.at("input_height")},
                 {"output_height", outcome.facts.at("output_height")},
                 {"cache", {{"reused", status.reused}, {"why", status.why}, {"key", status.key}}},
                 {"seconds", result.seconds}};
  for (const MethodPlan& entry : plan.methods)  // the methods' tile facts, under their keys
    if (const std::string key = entry.method->tile_fact_key(); !key.empty())
      record[key] = outcome.facts.at(key);
  // Last: a result names only complete files.
  write_file_atomic(results_dir(plan_dir, hash) / fmt::format("tile-{}.json", tile),
                    record.dump(1) + "\n");
  return result;
}

RunReport finish_job(const fs::path& plan_dir) {
  const auto started = std::chrono::steady_clock::now();
  const fs::path out =
      read_plan_file(plan_dir / "job.json", kJobFormat).at("output_dir").get<std::string>();
  OutputFolder transaction(out);         // the lock, then every check, then the commit
  detail::delete_temporaries(plan_dir);  // a killed finish's record (finished.json)
  const json job = detail::read_job(plan_dir);
  const std::string hash = plan_hash(plan_dir);
  // Finished already (a rerun, or a requeued job after a kill during the clean-up): the output
  // folder holds this plan's run, so only the clean-up is left to do.
  if (std::optional<RunReport> done = finished_run(plan_dir, hash, out)) {
    delete_tiles(plan_dir, hash);
    logger().info("plan {} was finished already: {} files in {}", hash, done->outputs.size(),
                  out.string());
    return *done;
  }
  detail::require_complete_plan(plan_dir, hash);
  const bool cached = detail::job_cache(job).has_value();
  const PipelineConfig config = detail::job_config(job);
  WorldPlan plan = load_plan(plan_dir);

  std::vector<detail::RenderedTile> tiles;
  const fs::path dir = tiles_dir(plan_dir, hash);
  for (const TileSpec& spec : plan.tiles) {
    const fs::path result_path =
        results_dir(plan_dir, hash) / fmt::format("tile-{}.json", spec.index);
    std::error_code ec;
    if (!fs::is_regular_file(result_path, ec))
      fail("tile {} (x{} y{}) was not rendered: no {} (terraweave render-tile {} --tile {})",
           spec.index, spec.ix, spec.iy, result_path.string(), plan_dir.string(), spec.index);
    const json result = read_plan_file(result_path, kTileResultFormat);
    if (result.value("plan", "") != hash || result.value("tile", -1) != spec.index)
      fail("{}: belongs to plan {} tile {}, not plan {} tile {}", result_path.string(),
           result.value("plan", ""), result.value("tile", -1), hash, spec.index);
    detail::RenderedTile& rendered = tiles.emplace_back();
    rendered.tile = spec;
    rendered.seconds = result.value("seconds", 0.0);
    rendered.forbidden_pixels = result.value("forbidden_pixels", std::int64_t(0));
    rendered.xxh64 = result.value("xxh64", std::uint64_t(0));
    rendered.input_height = result.value("input_height", std::string());
    rendered.output_height = result.value("output_height", std::string());
    for (const MethodPlan& entry : plan.methods)
      if (const std::string key = entry.method->tile_fact_key(); !key.empty())
        rendered.method_facts[key] = result.value(key, std::string());
    if (cached && result.contains("cache")) {  // as run reports it: only with a cache
      const json& c = result["cache"];
      rendered.cache = CacheStatus{c.at("reused").get<bool>(), c.at("why").get<std::string>(),
                                   c.at("key").get<std::string>()};
    }
    for (const json& file : result.at("files")) {
      const fs::path relative = file.at("file").get<std::string>();
      const std::string bytes = read_file_bytes(dir / relative);
      const std::string digest = content_hash(bytes);
      if (digest != file.value("xxh3_128", ""))
        fail("tile {}: {} does not match its recorded hash (render the tile again)", spec.index,
             (dir / relative).string());
      const fs::path staged = transaction.stage(out / relative);
      fs::create_hard_link(dir / relative, staged, ec);
      if (ec) write_file_atomic(staged, bytes);  // another file system, or no links
      rendered.files.push_back({relative, bytes.size(), digest, staged});
    }
  }
  RunReport report = detail::write_job_outputs(plan, tiles, out, transaction);
  // As run_pipeline: the manifest's inputs, height ranges and features.geojson.
  report.inputs = detail::record_inputs(config.inputs);
  report.started_utc = detail::utc_timestamp();
  for (const detail::RenderedTile& t : tiles) {
    detail::widen(report.input_height, detail::range_of_fact(t.input_height));
    detail::widen(report.output_height, detail::range_of_fact(t.output_height));
  }
  write_curves_geojson(detail::export_curves(detail::layer_options(config), plan.lines),
                       plan.crs_wkt, transaction.stage(out / "features.geojson"));
  double render_seconds = 0.0;  // the tiles' own, summed (on any number of workers)
  for (const detail::RenderedTile& t : tiles) render_seconds += t.seconds;
  report.stages.push_back({"render", render_seconds});
  report.stages.push_back({"finish", seconds_since(started)});
  report.output_files = detail::record_outputs(transaction);
  detail::write_job_report(plan, report, config, out, transaction);
  transaction.commit();
  report.outputs = transaction.committed();
  // Then the record that this plan is in the output folder, then the clean-up (the tiles are
  // the output folder's now: links or copies). A kill before the record: a rerun finishes
  // again (the same bytes); after it: a rerun only cleans up.
  record_finished(plan_dir, hash, out, report.outputs);
  delete_tiles(plan_dir, hash);
  logger().info("finished plan {}: {} files in {}", hash, report.outputs.size(), out.string());
  return report;
}

}  // namespace tw
