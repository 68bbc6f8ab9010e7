// The registry of synthesis methods (pipeline/synthesis_method.hpp): a method is added here,
// and nowhere else in the pipeline.
#include "pipeline/synthesis_method.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "pipeline/methods/areas/area_method.hpp"
#include "pipeline/methods/grown/grown_method.hpp"
#include "pipeline/methods/network/network_method.hpp"
#include "pipeline/methods/patterns/pattern_method.hpp"

namespace tw {

nlohmann::json SynthesisMethod::encode_report(const MethodPayload& /*part*/,
                                              detail::PlanObjects& /*objects*/) const {
  fail("method '{}' has a part of the run's report but no codec for it", name());
}

std::unique_ptr<MethodPayload> SynthesisMethod::decode_report(
    const nlohmann::json& /*value*/, detail::PlanObjects& /*objects*/) const {
  fail("method '{}' has a part of the run's report but no codec for it", name());
}

nlohmann::json SynthesisMethod::take_report_timings(MethodPayload& /*part*/) const {
  return nullptr;
}

nlohmann::json SynthesisMethod::plan_tasks(const WorldPlan& /*plan*/,
                                           MethodTasks& /*tasks*/) const {
  return nlohmann::json::array();
}

MethodTaskRun SynthesisMethod::run_task(const WorldPlan& /*plan*/, MethodTasks& /*tasks*/,
                                        const nlohmann::json& /*list*/, std::size_t index) const {
  fail("method '{}' makes no synthesis tasks (task {})", name(), index);
}

double SynthesisMethod::complete_tasks(
    WorldPlan& /*plan*/, MethodPlan& /*entry*/, MethodTasks& /*tasks*/,
    const nlohmann::json& /*list*/,
    const std::function<MethodTaskResult(std::size_t)>& /*result*/) const {
  fail("method '{}' makes no synthesis tasks to complete", name());
}

const std::vector<const SynthesisMethod*>& builtin_synthesis_methods() {
  static const std::vector<const SynthesisMethod*> methods = {
      &detail::grown_method(), &detail::network_method(), &detail::pattern_method(),
      &detail::area_method()};
  return methods;
}

namespace detail {

const std::vector<MethodKeys>& builtin_method_keys() {
  static const std::vector<MethodKeys> keys = {pattern_keys(), grown_keys(), network_keys(),
                                               area_keys()};
  return keys;
}

const std::vector<MethodReader>& builtin_method_readers() {
  static const std::vector<MethodReader> readers = {network_reader(), grown_reader(),
                                                    pattern_reader(), area_reader()};
  return readers;
}

}  // namespace detail

const std::vector<const SynthesisMethod*>& methods_or_builtin(
    const std::vector<const SynthesisMethod*>& methods) {
  return methods.empty() ? builtin_synthesis_methods() : methods;
}

PipelineConfig with_method_defaults(PipelineConfig config,
                                    const std::vector<const SynthesisMethod*>& methods) {
  for (const SynthesisMethod* method : methods_or_builtin(methods))
    method->resolve_defaults(config);
  return config;
}

RibbonNeeds class_ribbon_needs(const FeatureClassConfig& c,
                               const std::vector<const SynthesisMethod*>& methods) {
  RibbonNeeds needs;
  for (const SynthesisMethod* method : methods_or_builtin(methods)) {
    const RibbonNeeds its = method->ribbon_needs(c);
    if (its.piece_length) needs.piece_length = its.piece_length;
    if (its.synthesis_width) needs.synthesis_width = its.synthesis_width;
    needs.counts_short_lines = needs.counts_short_lines || its.counts_short_lines;
  }
  return needs;
}

bool lines_made_by_a_method(const FeatureClassConfig& c,
                            const std::vector<const SynthesisMethod*>& methods) {
  const std::vector<const SynthesisMethod*>& all = methods_or_builtin(methods);
  return std::any_of(all.begin(), all.end(),
                     [&](const SynthesisMethod* method) { return method->makes_lines_of(c); });
}

std::string method_name(const MethodPlan& entry) {
  return entry.method ? entry.method->name() : std::string();
}

void fail_payload_type(const MethodPlan& entry) {
  fail("plan: the entry of method '{}' holds another method's payload", method_name(entry));
}

const MethodPlan* find_method_plan(const WorldPlan& plan, const std::string& name) {
  for (const MethodPlan& entry : plan.methods)
    if (method_name(entry) == name) return &entry;
  return nullptr;
}

MethodPlan* find_method_plan(WorldPlan& plan, const std::string& name) {
  for (MethodPlan& entry : plan.methods)
    if (method_name(entry) == name) return &entry;
  return nullptr;
}

}  // namespace tw
