#pragma once
// The files of a plan folder that more than one job step reads (pipeline/job.hpp,
// pipeline/synthesis_job.hpp): job.json and the folders named by the plan's hash.
#include <filesystem>
#include <optional>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "core/warnings.hpp"
#include "pipeline/config.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

inline constexpr const char* kJobFormat = "terraweave.job";

// job.json, checked to belong to the plan in plan.json. Throws tw::Error naming the folder, or
// saying that complete-plan was interrupted (completing.json) and must be run again.
nlohmann::json read_job(const std::filesystem::path& plan_dir);

// The command that makes this plan again, from job.json ("terraweave plan PIPELINE --out DIR
// ..."; the generic form when job.json cannot be read).
std::string plan_again(const std::filesystem::path& plan_dir);

// A plan's objects written into its folder, and the texts of its plan.json and tasks.json, not
// yet written (save_plan writes them; complete-plan first records them in its journal).
struct StagedPlan {
  std::string hash;
  std::string plan_json, tasks_json;
};
StagedPlan stage_plan(const WorldPlan& plan, const std::filesystem::path& dir);

// The names under objects/ that a plan.json names; deleting the others in `dir`/objects
// (earlier plans' objects, a killed writer's temporaries).
std::set<std::string> plan_objects(const nlohmann::json& plan_json);
void delete_unused_objects(const std::filesystem::path& dir, const std::set<std::string>& used);

// syntheses.json, the synthesis task list, in a plan folder.
std::filesystem::path syntheses_path(const std::filesystem::path& plan_dir);

// Checks syntheses.json's dependency graph: every `after` names a feature of the list
// synthesized before it (no unknown index, no self-dependency, no cycle). Throws tw::Error
// naming `file` and the feature.
void check_synthesis_graph(const nlohmann::json& features, const std::filesystem::path& file,
                           const std::string& what_to_do);

// The hash job.json records for syntheses.json: of its values but `plan` and `completed`, which
// plan and complete-plan add after it.
std::string syntheses_hash(nlohmann::json list);

// syntheses.json, checked: its format, its graph, and its bytes (without `plan` and `completed`)
// against the hash job.json recorded. Throws tw::Error naming it and what to do.
nlohmann::json read_syntheses(const std::filesystem::path& plan_dir, const nlohmann::json& job);

// complete-plan's journal (completing.json): once complete-plan has written the complete plan's
// objects, the texts of the four files it then replaces; a rerun after a kill writes them again
// and cleans up. Returns false when there is no journal.
bool resume_completion(const std::filesystem::path& plan_dir, std::string* plan = nullptr,
                       std::size_t* warnings = nullptr);

// The pipeline as it was planned (its file unchanged, the same overrides, from the same folder).
PipelineConfig job_config(const nlohmann::json& job);

// job.json's `cache` (plan --cache, or the pipeline's cache key), absolute; none without one.
std::optional<std::filesystem::path> job_cache(const nlohmann::json& job);

// Deletes what a killed writer left at the top of the plan folder: its temporaries
// (".<name>.tmp-<host>-<pid>...", core/file_io.hpp). Only for commands holding the output
// folder's lock (plan, complete-plan, finish): workers write there only under results-, tiles-,
// syntheses/ and synthesis-results/.
void delete_temporaries(const std::filesystem::path& plan_dir);

// Deletes what earlier plans' tile tasks left (their workers may still write there: harmless).
void delete_other_plans(const std::filesystem::path& plan_dir, const std::string& plan);

// The synthesis task list of a plan made without syntheses (pipeline/synthesis_job.hpp): every
// feature's name, key, cache status (against `cache`), the features it depends on, and whether
// it is a task (not reused from the cache). Writes nothing; a corrupt cache entry is a warning.
nlohmann::json plan_synthesis_tasks(const PipelineConfig& config, const WorldPlan& plan,
                                    const std::optional<std::string>& backend,
                                    const std::optional<std::filesystem::path>& cache,
                                    const std::filesystem::path& plan_dir, Warnings& warnings);

// Writes syntheses.json for the plan `plan` (none, or no feature with synthesis: deletes it, the
// plan is complete) and clears what an earlier plan's syntheses left. Returns the number of
// features in the list.
std::size_t write_synthesis_tasks(const std::filesystem::path& plan_dir,
                                  const std::optional<nlohmann::json>& syntheses,
                                  const std::string& plan);

// Throws tw::Error when syntheses.json is gone while the plan (job.json) still has syntheses to
// complete: a missing file is never read as "no syntheses".
void require_syntheses_file(const std::filesystem::path& plan_dir, const nlohmann::json& job);

// Throws tw::Error when the plan `plan` in `plan_dir` still waits for its syntheses.
void require_complete_plan(const std::filesystem::path& plan_dir, const std::string& plan);

}  // namespace tw::detail
