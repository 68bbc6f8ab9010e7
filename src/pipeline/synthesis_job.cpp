#include "pipeline/synthesis_job.hpp"

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/log.hpp"
#include "core/output_folder.hpp"
#include "pipeline/detail/job_files.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/synthesis_cache.hpp"
#include "pipeline/detail/synthesis_defaults.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"
#include "pipeline/plan_io.hpp"

namespace tw {

namespace fs = std::filesystem;
using nlohmann::json;
using Scope = detail::PatternOptions::Scope;

namespace {

fs::path syntheses_path(const fs::path& plan_dir) {
  return plan_dir / "syntheses.json";
}
fs::path results_dir(const fs::path& plan_dir) {
  return plan_dir / "synthesis-results";
}

std::optional<std::string> job_backend(const json& job) {
  if (!job.contains("backend") || job["backend"].is_null()) return std::nullopt;
  return job["backend"].get<std::string>();
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

detail::PatternRun synthesize(const PipelineConfig& config, const WorldPlan& plan,
                              const detail::PatternOptions& options) {
  return detail::synthesize_patterns(config, plan.lines, detail::synthesis_ribbons(plan),
                                     detail::existing_features(plan), options);
}

}  // namespace

namespace detail {

std::string syntheses_hash(json list) {
  list.erase("plan");
  list.erase("completed");
  return content_hash(list.dump());
}

void check_synthesis_graph(const json& features, const fs::path& file,
                           const std::string& what_to_do) {
  const std::string where = file.string();
  if (!features.is_array()) fail("{}: `features` is not a list; {}", where, what_to_do);
  const std::size_t n = features.size();
  std::vector<std::vector<std::size_t>> after(n);
  const auto name = [&](std::size_t i) { return features[i].value("name", std::string("?")); };
  for (std::size_t i = 0; i < n; ++i) {
    const json& entry = features[i];
    if (!entry.is_object() || !entry.contains("index") || entry["index"] != i)
      fail("{}: features[{}]: `index` is not {}; {}", where, i, i, what_to_do);
    if (!entry.contains("after") || !entry["after"].is_array())
      fail("{}: feature {} ({}): `after` is not a list; {}", where, i, name(i), what_to_do);
    for (const json& a : entry["after"]) {
      if (!a.is_number_integer() || a.get<std::int64_t>() < 0 ||
          a.get<std::int64_t>() >= std::int64_t(n))
        fail("{}: feature {} ({}) depends on {}, which is not in the list (features 0 to {}); {}",
             where, i, name(i), a.dump(), int(n) - 1, what_to_do);
      const std::size_t d = a.get<std::size_t>();
      if (d == i) fail("{}: feature {} ({}) depends on itself; {}", where, i, name(i), what_to_do);
      after[i].push_back(d);
    }
  }
  // A cycle, named by its features (depth-first, without recursion: lists may be long).
  std::vector<int> state(n, 0);  // 0 unseen, 1 on the path, 2 done
  std::vector<std::size_t> parent(n, n);
  for (std::size_t root = 0; root < n; ++root) {
    if (state[root] != 0) continue;
    std::vector<std::pair<std::size_t, std::size_t>> stack{{root, 0}};
    state[root] = 1;
    while (!stack.empty()) {
      auto& [node, next] = stack.back();
      if (next == after[node].size()) {
        state[node] = 2;
        stack.pop_back();
        continue;
      }
      const std::size_t d = after[node][next++];
      if (state[d] == 1) {
        std::string cycle = std::to_string(d);
        for (std::size_t at = node; at != d; at = parent[at])
          cycle = std::to_string(at) + " -> " + cycle;
        fail("{}: a dependency cycle: feature {} -> {} ({} depends on {}); {}", where, d, cycle,
             name(node), name(d), what_to_do);
      }
      if (state[d] == 0) {
        state[d] = 1;
        parent[d] = node;
        stack.push_back({d, 0});
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i)
    for (const std::size_t d : after[i])
      if (d > i)
        fail(
            "{}: feature {} ({}) depends on {}, which is synthesized after it (a feature avoids "
            "only earlier ones); {}",
            where, i, name(i), d, what_to_do);
}

json read_syntheses(const fs::path& plan_dir, const json& job) {
  const fs::path file = syntheses_path(plan_dir);
  const json list = read_plan_file(file, kSynthesesFormat);
  const std::string what_to_do = "plan again (" + plan_again(plan_dir) + ")";
  check_synthesis_graph(list.contains("features") ? list["features"] : json(), file, what_to_do);
  if (syntheses_hash(list) != job.value("syntheses_xxh3_128", ""))
    fail("{}: does not match its hash in job.json (edited or corrupt after planning); {}",
         file.string(), what_to_do);
  return list;
}

json plan_synthesis_tasks(const PipelineConfig& config, const WorldPlan& plan,
                          const std::optional<std::string>& backend,
                          const std::optional<fs::path>& cache, const fs::path& plan_dir,
                          Warnings& warnings) {
  SynthesisCache statuses(cache, warnings);
  PatternOptions options;
  options.backend = backend;
  options.cache = &statuses;
  options.scope = Scope::keys;
  // The keys of the syntheses plan_world would run: with the exemplars' width and delta where the
  // pipeline gives none (the tasks read the pipeline so too).
  const PatternRun run = synthesize(with_exemplar_defaults(config), plan, options);
  json features = json::array();
  std::vector<int> waves;
  for (std::size_t i = 0; i < run.patterns.size(); ++i) {
    const FeaturePattern& p = run.patterns[i];
    const bool task = !p.cache.reused;
    int wave = -1;  // tasks only: one more than the deepest task it waits for
    if (task) {
      wave = 0;
      for (const std::size_t a : p.after) wave = std::max(wave, waves[a] + 1);
    }
    waves.push_back(wave);
    features.push_back({{"index", i},
                        {"name", p.name},
                        {"class", config.features[p.class_index].name},
                        {"fid", plan.lines[p.class_index][p.feature_index].fid},
                        {"key", p.key.hex()},
                        {"cache", {{"reused", p.cache.reused}, {"why", p.cache.why}}},
                        {"after", p.after},
                        {"task", task},
                        {"wave", task ? json(wave) : json()}});
  }
  return {{"format", kSynthesesFormat},
          {"version", kPlanVersion},
          {"store", (cache ? *cache : plan_dir / "syntheses").string()},
          {"features", features}};
}

std::size_t write_synthesis_tasks(const fs::path& plan_dir, const std::optional<json>& syntheses,
                                  const std::string& plan) {
  std::error_code ec;
  fs::remove_all(results_dir(plan_dir), ec);
  fs::remove_all(plan_dir / "syntheses", ec);  // an earlier plan's store (without a cache)
  if (!syntheses || syntheses->at("features").empty()) {
    fs::remove(syntheses_path(plan_dir), ec);
    return 0;
  }
  json list = *syntheses;
  list["plan"] = plan;
  write_file_atomic(syntheses_path(plan_dir), list.dump(1) + "\n");
  return list["features"].size();
}

void require_syntheses_file(const fs::path& plan_dir, const json& job) {
  std::error_code ec;
  if (fs::is_regular_file(syntheses_path(plan_dir), ec)) return;
  const std::size_t tasks = job.value("synthesis_tasks", std::size_t(0));
  if (tasks > 0 && !job.value("syntheses_complete", false))
    fail(
        "{}: missing, but plan {} has {} syntheses to run and complete; its patterns cannot be "
        "recovered without it: plan again (terraweave plan ... --synthesis tasks)",
        syntheses_path(plan_dir).string(), job.value("plan", ""), tasks);
}

void require_complete_plan(const fs::path& plan_dir, const std::string& plan) {
  const json job = read_job(plan_dir);
  require_syntheses_file(plan_dir, job);
  std::error_code ec;
  if (!fs::is_regular_file(syntheses_path(plan_dir), ec)) return;
  const json list = read_syntheses(plan_dir, job);
  if (list.value("plan", "") == plan)
    fail(
        "plan {}: its syntheses are not in the plan yet (terraweave synth-feature {} --feature I "
        "for every task of syntheses.json, then terraweave complete-plan {})",
        plan, plan_dir.string(), plan_dir.string());
}

}  // namespace detail

namespace {

// A synthesis whose key is not the plan's: what it reads changed after planning. An exemplar is
// named by its file (the most common case: an exemplar image edited or replaced).
[[noreturn]] void key_changed(const fs::path& plan_dir, const PipelineConfig& config,
                              const detail::FeaturePattern& pattern, std::size_t index) {
  const FeatureClassConfig& c = config.features.at(pattern.class_index);
  std::string changed;
  for (const fs::path& path : c.synthesis->exemplars) {
    std::error_code ec;
    const auto written = fs::last_write_time(path, ec);
    const auto planned = fs::last_write_time(plan_dir / "plan.json", ec);
    if (!ec && written > planned) changed += (changed.empty() ? "" : ", ") + path.string();
  }
  const std::string what_to_do = "plan again (" + detail::plan_again(plan_dir) + ")";
  if (!changed.empty())
    fail("{}: feature {} ({}): features.{}.synthesis.exemplars {} changed after planning; {}",
         syntheses_path(plan_dir).string(), index, pattern.name, c.name, changed, what_to_do);
  fail(
      "{}: feature {} ({}): what its synthesis reads (its line, features.{}.synthesis keys, "
      "exemplars, the earlier features it avoids) is not what was planned; {}",
      syntheses_path(plan_dir).string(), index, pattern.name, c.name, what_to_do);
}

// The store's entries read back: one found corrupt fails the job (a run rebuilds it; a job must
// not), naming the entry's file, the feature and the command that makes it again.
detail::PatternRun synthesize_from_store(const PipelineConfig& config, const WorldPlan& plan,
                                         const detail::PatternOptions& options,
                                         const Warnings& warnings, const json& list,
                                         const fs::path& plan_dir) {
  try {
    return synthesize(config, plan, options);
  } catch (const Error&) {
    for (const Warning& w : warnings.list()) {
      if (w.code != "cache_corrupt") continue;
      std::string index = "N";
      for (const json& f : list.at("features"))
        if (w.fid && f.value("fid", std::int64_t(-1)) == *w.fid &&
            "features." + f.value("class", std::string()) == w.subject)
          index = f.at("index").dump();
      std::string message = w.message;
      if (message.ends_with(": rebuilt")) message.resize(message.size() - 9);
      fail(
          "{}: FID {}: synthesis store {}; delete that file and synthesize the feature again "
          "(terraweave synth-feature {} --feature {})",
          w.subject, w.fid.value_or(-1), message, plan_dir.string(), index);
    }
    throw;
  }
}

}  // namespace

SynthesisJobResult synthesize_job_feature(const fs::path& plan_dir, int feature) {
  test_pause_point("synth-feature");
  const auto started = std::chrono::steady_clock::now();
  const json job = detail::read_job(plan_dir);
  const std::string hash = plan_hash(plan_dir);
  const json list = detail::read_syntheses(plan_dir, job);
  if (list.value("plan", "") != hash)
    fail("{}: belongs to plan {}, plan.json is {} (complete already, or planned again)",
         syntheses_path(plan_dir).string(), list.value("plan", ""), hash);
  const json& features = list.at("features");
  if (feature < 0 || std::size_t(feature) >= features.size())
    fail("--feature {}: the plan has {} syntheses (0 to {})", feature, features.size(),
         int(features.size()) - 1);
  const json& entry = features[std::size_t(feature)];
  SynthesisJobResult result;
  result.feature = feature;
  result.name = entry.at("name").get<std::string>();
  if (!entry.at("task").get<bool>()) return result;  // reused from the cache by the plan

  // With the exemplars' width and delta where the pipeline gives none, as the plan read it.
  const PipelineConfig config = detail::with_exemplar_defaults(detail::job_config(job));
  const WorldPlan plan = load_plan(plan_dir);
  Warnings warnings;  // a store entry of a dependency that is corrupt: an error below
  detail::SynthesisCache store(fs::path(list.at("store").get<std::string>()), warnings);
  detail::PatternOptions options;
  options.backend = job_backend(job);
  options.cache = &store;
  options.scope = Scope::one;
  options.feature = std::size_t(feature);
  options.after = entry.at("after").get<std::vector<std::size_t>>();
  detail::PatternRun run = synthesize_from_store(config, plan, options, warnings, list, plan_dir);
  if (run.patterns.empty())
    fail("{}: feature {} ({}) is not in the plan's features any more; plan again ({})",
         syntheses_path(plan_dir).string(), feature, result.name, detail::plan_again(plan_dir));
  if (run.patterns.back().key.hex() != entry.at("key").get<std::string>())
    key_changed(plan_dir, config, run.patterns.back(), std::size_t(feature));
  const std::vector<std::uint8_t> report =
      json::to_cbor(detail::encode(run.patterns.back().report));
  // Last: a report names a stored synthesis.
  write_file_atomic(results_dir(plan_dir) / (entry.at("key").get<std::string>() + ".cbor"),
                    std::string(report.begin(), report.end()));
  result.synthesized = true;
  result.seconds = seconds_since(started);
  return result;
}

namespace {

constexpr const char* kCompletingFormat = "terraweave.completing";
fs::path journal_path(const fs::path& plan_dir) {
  return plan_dir / "completing.json";
}

// Writes `text` to `path` unless it holds it already (a rerun rewrites only what is missing).
void write_if_changed(const fs::path& path, const std::string& text) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == text.size() && !ec &&
      read_file_bytes(path) == text)
    return;
  write_file_atomic(path, text);
}

}  // namespace

namespace detail {

bool resume_completion(const fs::path& plan_dir, std::string* plan, std::size_t* warnings) {
  std::error_code ec;
  if (!fs::is_regular_file(journal_path(plan_dir), ec)) return false;
  const json journal = read_plan_file(journal_path(plan_dir), kCompletingFormat);
  const json& files = journal.at("files");
  // The order of a first completion: tasks.json and plan.json (the plan), then job.json (which
  // names it), then syntheses.json (`completed`). Every step is a whole file renamed into place.
  for (const char* name : {"tasks.json", "plan.json", "job.json", "syntheses.json"})
    write_if_changed(plan_dir / name, files.at(name).get<std::string>());
  const std::string complete = journal.at("to").get<std::string>();
  delete_unused_objects(plan_dir,
                        plan_objects(json::parse(files.at("plan.json").get<std::string>())));
  delete_other_plans(plan_dir, complete);
  fs::remove(journal_path(plan_dir), ec);
  if (ec) fail("cannot delete {}: {}", journal_path(plan_dir).string(), ec.message());
  if (plan) *plan = complete;
  if (warnings) *warnings = journal.value("warnings", std::size_t(0));
  return true;
}

}  // namespace detail

PlannedJob complete_job_plan(const fs::path& plan_dir, bool strict) {
  const fs::path out =
      read_plan_file(plan_dir / "job.json", detail::kJobFormat).at("output_dir").get<std::string>();
  const OutputFolder lock(out);  // as plan: not while a run or a finish writes there
  // Crash safety (issue #24): a completion killed after its journal was written is finished
  // from the journal; one killed before it changed nothing but new objects and temporaries.
  detail::delete_temporaries(plan_dir);
  const auto tile_count = [&plan_dir] {
    return read_plan_file(plan_dir / "tasks.json", kTasksFormat).at("tiles").size();
  };
  {
    std::string complete;
    std::size_t warnings = 0;
    if (detail::resume_completion(plan_dir, &complete, &warnings)) {
      logger().info("plan {}: an interrupted completion finished", complete);
      return {plan_dir, complete, tile_count(), warnings, 0};
    }
  }
  json job = detail::read_job(plan_dir);
  const std::string hash = plan_hash(plan_dir);
  const std::size_t tiles = tile_count();
  std::error_code ec;
  detail::require_syntheses_file(plan_dir, job);
  if (!fs::is_regular_file(syntheses_path(plan_dir), ec)) return {plan_dir, hash, tiles, 0, 0};
  json list = detail::read_syntheses(plan_dir, job);
  if (list.value("plan", "") != hash) {
    if (list.value("completed", "") == hash) return {plan_dir, hash, tiles, 0, 0};
    fail("{}: belongs to plan {}, plan.json is {}; plan again ({})",
         syntheses_path(plan_dir).string(), list.value("plan", ""), hash,
         detail::plan_again(plan_dir));
  }
  const PipelineConfig config = detail::with_exemplar_defaults(detail::job_config(job));
  WorldPlan plan = load_plan(plan_dir);
  Warnings warnings;
  detail::SynthesisCache store(fs::path(list.at("store").get<std::string>()), warnings);
  detail::PatternOptions options;
  options.backend = job_backend(job);
  options.cache = &store;
  options.scope = Scope::cached;
  detail::PatternRun run = synthesize_from_store(config, plan, options, warnings, list, plan_dir);
  const json& features = list.at("features");
  if (run.patterns.size() != features.size())
    fail("{}: {} syntheses, the plan has {}", syntheses_path(plan_dir).string(), features.size(),
         run.patterns.size());
  double seconds = 0.0;  // the tasks' own, summed (on any number of workers)
  for (std::size_t i = 0; i < features.size(); ++i) {
    detail::FeaturePattern& p = run.patterns[i];
    const json& entry = features[i];
    const std::string key = entry.at("key").get<std::string>();
    if (p.key.hex() != key) key_changed(plan_dir, config, p, i);
    // As the plan found the cache; a task's synthesis reports what it did.
    p.cache = {entry.at("cache").at("reused").get<bool>(),
               entry.at("cache").at("why").get<std::string>(), key};
    if (!entry.at("task").get<bool>()) continue;
    const fs::path report = results_dir(plan_dir) / (key + ".cbor");
    if (!fs::is_regular_file(report, ec))
      fail("{}: not synthesized: no {} (terraweave synth-feature {} --feature {})", p.name,
           report.string(), plan_dir.string(), i);
    const std::string bytes = read_file_bytes(report);
    try {
      detail::decode(json::from_cbor(bytes), p.report, report.string());
    } catch (const json::exception& e) {
      fail("{}: not a synthesis report ({})", report.string(), e.what());
    }
    seconds += p.report.avoidance_seconds + p.report.synthesis_seconds + p.report.render_seconds;
  }
  // The syntheses into the patterns' entry; the methods after it (the areas, which avoid the
  // curve patterns) plan here, after every synthesis, as plan_world orders them.
  Warnings synthesis_warnings;
  detail::PatternsPlan* patterns = detail::patterns_plan(plan);
  if (!patterns) fail("plan: no patterns entry to complete");
  patterns->run = std::make_shared<detail::PatternRun>(std::move(run));
  plan.report.stages.push_back({"synthesis", seconds});
  for (const StageTiming& t :
       detail::plan_after(config, plan, detail::pattern_method(), synthesis_warnings))
    plan.report.stages.push_back(t);
  if ((strict || config.strict) && !synthesis_warnings.list().empty())
    fail("strict: {} (the synthesis); nothing completed",
         to_string(synthesis_warnings.list().front()));
  // Appended as plan_world's Warnings would keep them: each once.
  std::vector<Warning>& kept = plan.report.warnings;
  for (const Warning& w : synthesis_warnings.list())
    if (std::none_of(kept.begin(), kept.end(), [&](const Warning& k) {
          return k.code == w.code && k.subject == w.subject && k.fid == w.fid &&
                 k.message == w.message;
        }))
      kept.push_back(w);
  index_plan(plan);
  // The complete plan's objects first (beside the incomplete plan's, which stays whole), then
  // the journal: from its rename on, the completion is decided, and resume_completion replaces
  // the four files and deletes what the incomplete plan alone used.
  const detail::StagedPlan staged = detail::stage_plan(plan, plan_dir);
  job["plan"] = staged.hash;
  job["syntheses_complete"] = true;
  list["completed"] = staged.hash;
  const json journal = {{"format", kCompletingFormat},
                        {"version", kPlanVersion},
                        {"from", hash},
                        {"to", staged.hash},
                        {"warnings", plan.report.warnings.size()},
                        {"files",
                         {{"tasks.json", staged.tasks_json},
                          {"plan.json", staged.plan_json},
                          {"job.json", job.dump(1) + "\n"},
                          {"syntheses.json", list.dump(1) + "\n"}}}};
  write_file_atomic(journal_path(plan_dir), journal.dump() + "\n");
  detail::resume_completion(plan_dir);
  logger().info("plan {}: {} syntheses in, now plan {}", hash, features.size(), staged.hash);
  return {plan_dir, staged.hash, tiles, plan.report.warnings.size(), 0};
}

}  // namespace tw
