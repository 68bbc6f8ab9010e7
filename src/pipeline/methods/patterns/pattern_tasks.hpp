#pragma once
// The patterns' syntheses as tasks (SynthesisMethod::plan_tasks, run_task, complete_tasks;
// pipeline/synthesis_job.hpp): one task per feature with `synthesis`, keyed by what its
// synthesis reads, run against the synthesis store.
#include <cstddef>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "pipeline/methods/patterns/pattern_method.hpp"
#include "pipeline/plan.hpp"
#include "pipeline/synthesis_method.hpp"

namespace tw::detail {

// Every feature's name, key, cache status (against tasks.store), the features it depends on,
// whether it is a task (not reused from the store) and its wave. A corrupt cache entry is a
// warning.
nlohmann::json plan_pattern_tasks(const WorldPlan& plan, MethodTasks& tasks);

// Synthesizes feature `index` of `list` into the store, unless the finer check (docs/cache.md)
// finds a stored synthesis whose DP read the same; returns its result (CBOR: `report`, and
// `cache` when it reused one) and, then, why. Throws tw::Error when its key is not the planned one
// (naming what changed) or a store entry it reads is corrupt.
MethodTaskRun run_pattern_task(const WorldPlan& plan, MethodTasks& tasks,
                               const nlohmann::json& list, std::size_t index);

// Every feature's synthesis from the store, its cache status as planned (or as its task
// reused it) and a task's report from `result`, into `entry` (collected later, as plan_world's).
// Returns the tasks' seconds.
double complete_pattern_tasks(const WorldPlan& plan, PatternsPlan& entry, MethodTasks& tasks,
                              const nlohmann::json& list,
                              const std::function<MethodTaskResult(std::size_t)>& result);

}  // namespace tw::detail
