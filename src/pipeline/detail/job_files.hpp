#pragma once
// The files of a plan folder that more than one job step reads (pipeline/job.hpp,
// pipeline/synthesis_job.hpp): job.json and the folders named by the plan's hash.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "core/warnings.hpp"
#include "pipeline/config.hpp"
#include "pipeline/plan.hpp"

namespace tw::detail {

inline constexpr const char* kJobFormat = "terraweave.job";

// job.json, checked to belong to the plan in plan.json. Throws tw::Error naming the folder.
nlohmann::json read_job(const std::filesystem::path& plan_dir);

// The pipeline as it was planned (its file unchanged, the same overrides, from the same folder).
PipelineConfig job_config(const nlohmann::json& job);

// job.json's `cache` (plan --cache, or the pipeline's cache key), absolute; none without one.
std::optional<std::filesystem::path> job_cache(const nlohmann::json& job);

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
