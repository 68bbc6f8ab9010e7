#pragma once
// report.json: what a run read, made and wrote, with the versions that made it.
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/config.hpp"
#include "pipeline/run.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {
class SynthesisMethod;
}

namespace tw::detail {

// The report as report.json holds it; each of `methods` (the plan's: methods_in(plan)) writes
// its own fields into it (SynthesisMethod::report_json).
nlohmann::json report_to_json(const RunReport& report, const PipelineConfig& config,
                              const std::vector<const SynthesisMethod*>& methods);

}  // namespace tw::detail
