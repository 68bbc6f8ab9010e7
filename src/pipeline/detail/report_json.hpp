#pragma once
// report.json: what a run read, made and wrote, with the versions that made it.
#include <nlohmann/json.hpp>

#include "pipeline/config.hpp"
#include "pipeline/run.hpp"
#include "pipeline/run_layers.hpp"

namespace tw::detail {

nlohmann::json report_to_json(const RunReport& report, const PipelineConfig& config);

}  // namespace tw::detail
