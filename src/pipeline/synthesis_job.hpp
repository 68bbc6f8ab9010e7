#pragma once
// Feature syntheses as tasks (docs/distributed.md, "Syntheses as tasks"). `terraweave plan
// --synthesis tasks` plans the world without synthesizing and writes the synthesis task list;
// `terraweave synth-feature PLAN --feature I` synthesizes one feature on any machine that shares
// the output folder; `terraweave complete-plan PLAN` puts every synthesis into the plan, which
// is then the plan `terraweave plan` writes without --synthesis tasks (the same tiles, the same
// bytes). A feature's synthesis avoids the coverage of the features synthesized before it whose
// canvases overlap its own, and of nothing else: those are its dependencies, a DAG.
//
// In the plan folder:
//   syntheses.json                 format terraweave.syntheses: `plan` (the hash of the plan
//                                  still without syntheses), `store`, and per feature in
//                                  synthesis order: index, name, class, fid, key, cache (status
//                                  and why, as run reports them), after (the features it depends
//                                  on), task (false: reused from the cache), wave (tasks: 0 for
//                                  those that depend on no task, else 1 + their deepest task's)
//   syntheses/                     the store of the syntheses (a synthesis cache folder,
//                                  docs/cache.md) when the plan has no cache; else the cache
//   synthesis-results/<key>.cbor   a synthesized feature's result (the method's: the patterns
//                                  write their report and, when the finer check reused a stored
//                                  synthesis, its cache status), written last by its task
#include <filesystem>
#include <string>

#include "pipeline/job.hpp"

namespace tw {

inline constexpr const char* kSynthesesFormat = "terraweave.syntheses";

struct SynthesisJobResult {
  int feature = 0;
  std::string name;          // <class>_<fid>[_<part>]
  bool synthesized = false;  // false: reused from the cache, when planned or by the task
  std::string why;           // why it was reused (the cache status's why), when it was
  double seconds = 0.0;
};

// Synthesizes feature `feature` (its index in syntheses.json) of the plan in `plan_dir` and
// stores it (an entry written to a temporary and renamed, then its report). The features it
// depends on must be stored already (tw::Error naming the first that is not). A rerun, on any
// machine, writes the same bytes. Test hook: TERRAWEAVE_TEST_PAUSE_AT=synth-feature.
SynthesisJobResult synthesize_job_feature(const std::filesystem::path& plan_dir, int feature);

// Completes a plan made with --synthesis tasks once every task has run: the plan's syntheses,
// report and pattern index, written as plan_job would (a new plan hash; job.json follows).
// A complete plan is left alone. Throws tw::Error naming the first feature not synthesized.
// `strict` (--strict) or the pipeline's `strict`: a warning of the synthesis fails it.
PlannedJob complete_job_plan(const std::filesystem::path& plan_dir, bool strict = false);

}  // namespace tw
