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
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/plan_io.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

using detail::syntheses_path;

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

}  // namespace

namespace detail {

fs::path syntheses_path(const fs::path& plan_dir) {
  return plan_dir / "syntheses.json";
}

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
  // The keys of the syntheses plan_world would run: with the methods' defaults (the exemplars'
  // width and delta where the pipeline gives none; the tasks read the pipeline so too).
  const PipelineConfig defaults = with_method_defaults(config);
  MethodTasks tasks{defaults, backend, cache, plan_dir, warnings};
  const json features = tasks_method(plan).plan_tasks(plan, tasks);
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
  if (!entry.at("task").get<bool>()) {  // reused from the cache by the plan
    result.why = entry.at("cache").at("why").get<std::string>();
    return result;
  }

  // With the methods' defaults (the exemplars' width and delta), as the plan read it.
  const PipelineConfig config = with_method_defaults(detail::job_config(job));
  const WorldPlan plan = load_plan(plan_dir);
  Warnings warnings;  // a store entry of a dependency that is corrupt: an error below
  MethodTasks tasks{config, job_backend(job), fs::path(list.at("store").get<std::string>()),
                    plan_dir, warnings};
  const MethodTaskRun run =
      detail::tasks_method(plan).run_task(plan, tasks, list, std::size_t(feature));
  // Last: a report names a stored synthesis.
  write_file_atomic(results_dir(plan_dir) / (entry.at("key").get<std::string>() + ".cbor"),
                    run.result);
  result.synthesized = !run.reused_why;
  result.why = run.reused_why.value_or("");
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
  const PipelineConfig config = with_method_defaults(detail::job_config(job));
  WorldPlan plan = load_plan(plan_dir);
  Warnings warnings;
  MethodTasks tasks{config, job_backend(job), fs::path(list.at("store").get<std::string>()),
                    plan_dir, warnings};
  const json& features = list.at("features");
  // A task's result, stored by synth-feature under its key.
  const auto result = [&](std::size_t i) {
    const fs::path file =
        results_dir(plan_dir) / (features[i].at("key").get<std::string>() + ".cbor");
    if (!fs::is_regular_file(file, ec))
      fail("{}: not synthesized: no {} (terraweave synth-feature {} --feature {})",
           features[i].at("name").get<std::string>(), file.string(), plan_dir.string(), i);
    return MethodTaskResult{file.string(), read_file_bytes(file)};
  };
  // The syntheses into their method's entry; the methods after it (the areas, which avoid the
  // curve patterns) plan here, after every synthesis, as plan_world orders them.
  const SynthesisMethod& method = detail::tasks_method(plan);
  MethodPlan* entry = find_method_plan(plan, method.name());
  const double seconds = method.complete_tasks(plan, *entry, tasks, list, result);
  Warnings synthesis_warnings;
  plan.report.stages.push_back({method.stage_name(), seconds});
  for (const StageTiming& t : detail::plan_after(config, plan, method, synthesis_warnings))
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
