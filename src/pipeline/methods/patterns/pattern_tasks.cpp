#include "pipeline/methods/patterns/pattern_tasks.hpp"

#include <algorithm>
#include <memory>
#include <system_error>
#include <vector>

#include "core/error.hpp"
#include "pipeline/detail/job_files.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/methods/patterns/synthesis_cache.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;
using Scope = PatternOptions::Scope;

namespace {

PatternRun synthesize(const PipelineConfig& config, const WorldPlan& plan,
                      const PatternOptions& options) {
  return synthesize_patterns(config, plan.lines, synthesis_ribbons(plan), existing_features(plan),
                             options);
}

// A synthesis whose key is not the plan's: what it reads changed after planning. An exemplar is
// named by its file (the most common case: an exemplar image edited or replaced).
[[noreturn]] void key_changed(const fs::path& plan_dir, const PipelineConfig& config,
                              const FeaturePattern& pattern, std::size_t index) {
  const FeatureClassConfig& c = config.features.at(pattern.class_index);
  std::string changed;
  for (const fs::path& path : method_options<SynthesisConfig>(c, kPatternsMethodName)->exemplars) {
    std::error_code ec;
    const auto written = fs::last_write_time(path, ec);
    const auto planned = fs::last_write_time(plan_dir / "plan.json", ec);
    if (!ec && written > planned) changed += (changed.empty() ? "" : ", ") + path.string();
  }
  const std::string what_to_do = "plan again (" + plan_again(plan_dir) + ")";
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
PatternRun synthesize_from_store(const WorldPlan& plan, const PatternOptions& options,
                                 const MethodTasks& tasks, const json& list) {
  try {
    return synthesize(tasks.config, plan, options);
  } catch (const Error&) {
    for (const Warning& w : tasks.warnings.list()) {
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
          w.subject, w.fid.value_or(-1), message, tasks.plan_dir.string(), index);
    }
    throw;
  }
}

}  // namespace

json plan_pattern_tasks(const WorldPlan& plan, MethodTasks& tasks) {
  SynthesisCache statuses(tasks.store, tasks.warnings);
  PatternOptions options;
  options.backend = tasks.backend;
  options.cache = &statuses;
  options.scope = Scope::keys;
  const PatternRun run = synthesize(tasks.config, plan, options);
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
                        {"class", tasks.config.features[p.class_index].name},
                        {"fid", plan.lines[p.class_index][p.feature_index].fid},
                        {"key", p.key.hex()},
                        {"cache", {{"reused", p.cache.reused}, {"why", p.cache.why}}},
                        {"after", p.after},
                        {"task", task},
                        {"wave", task ? json(wave) : json()}});
  }
  return features;
}

MethodTaskRun run_pattern_task(const WorldPlan& plan, MethodTasks& tasks, const json& list,
                               std::size_t index) {
  const json& entry = list.at("features").at(index);
  SynthesisCache store(tasks.store, tasks.warnings);
  PatternOptions options;
  options.backend = tasks.backend;
  options.cache = &store;
  options.scope = Scope::one;
  options.feature = index;
  options.after = entry.at("after").get<std::vector<std::size_t>>();
  options.planned = {entry.at("cache").at("reused").get<bool>(),
                     entry.at("cache").at("why").get<std::string>(),
                     entry.at("key").get<std::string>()};
  PatternRun run = synthesize_from_store(plan, options, tasks, list);
  if (run.patterns.empty())
    fail("{}: feature {} ({}) is not in the plan's features any more; plan again ({})",
         syntheses_path(tasks.plan_dir).string(), index, entry.at("name").get<std::string>(),
         plan_again(tasks.plan_dir));
  if (run.patterns.back().key.hex() != entry.at("key").get<std::string>())
    key_changed(tasks.plan_dir, tasks.config, run.patterns.back(), index);
  // The report, and the cache status when the finer check reused a stored synthesis (the
  // plan's status stands otherwise).
  const FeaturePattern& pattern = run.patterns.back();
  json result = {{"report", encode(pattern.report)}};
  MethodTaskRun task;
  if (pattern.cache.reused) {
    result["cache"] = {{"reused", true}, {"why", pattern.cache.why}};
    task.reused_why = pattern.cache.why;
  }
  const std::vector<std::uint8_t> bytes = json::to_cbor(result);
  task.result.assign(bytes.begin(), bytes.end());
  return task;
}

double complete_pattern_tasks(const WorldPlan& plan, PatternsPlan& entry, MethodTasks& tasks,
                              const json& list,
                              const std::function<MethodTaskResult(std::size_t)>& result) {
  SynthesisCache store(tasks.store, tasks.warnings);
  PatternOptions options;
  options.backend = tasks.backend;
  options.cache = &store;
  options.scope = Scope::cached;
  PatternRun run = synthesize_from_store(plan, options, tasks, list);
  const json& features = list.at("features");
  if (run.patterns.size() != features.size())
    fail("{}: {} syntheses, the plan has {}", syntheses_path(tasks.plan_dir).string(),
         features.size(), run.patterns.size());
  double seconds = 0.0;  // the tasks' own, summed (on any number of workers)
  for (std::size_t i = 0; i < features.size(); ++i) {
    FeaturePattern& p = run.patterns[i];
    const json& feature = features[i];
    const std::string key = feature.at("key").get<std::string>();
    if (p.key.hex() != key) key_changed(tasks.plan_dir, tasks.config, p, i);
    // As the plan found the cache; a task's synthesis reports what it did.
    p.cache = {feature.at("cache").at("reused").get<bool>(),
               feature.at("cache").at("why").get<std::string>(), key};
    if (!feature.at("task").get<bool>()) continue;
    const MethodTaskResult stored = result(i);
    try {
      const json task = json::from_cbor(stored.bytes);
      decode(task.at("report"), p.report, stored.file);
      if (task.contains("cache"))  // reused by the finer check
        p.cache = {task.at("cache").at("reused").get<bool>(),
                   task.at("cache").at("why").get<std::string>(), key};
    } catch (const json::exception& e) {
      fail("{}: not a synthesis report ({})", stored.file, e.what());
    }
    seconds += p.report.avoidance_seconds + p.report.synthesis_seconds + p.report.render_seconds;
  }
  entry.run = std::make_shared<PatternRun>(std::move(run));
  return seconds;
}

}  // namespace tw::detail
