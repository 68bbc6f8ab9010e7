#include "pipeline/detail/network_method.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "pipeline/detail/network_classes.hpp"

namespace tw::detail {

using nlohmann::json;

namespace {

struct NetworkPlan : MethodPayloadOf<NetworkPlan> {};

class NetworkMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return "network"; }
  MethodStage stage() const override { return MethodStage::lines; }
  bool serves(const PipelineConfig& config, const PlanOptions& /*options*/) const override {
    return std::any_of(config.features.begin(), config.features.end(),
                       [](const FeatureClassConfig& c) { return bool(c.network); });
  }
  bool makes_lines_of(const FeatureClassConfig& c) const override { return bool(c.network); }
  std::string class_source(const FeatureClassConfig& c) const override {
    return c.network->exemplar;
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<NetworkPlan>();
  }

  // After the grown classes, off everything before them; once, in the plan, so that every tile
  // and worker sees the same lines.
  void plan(MethodContext& context, MethodPlan& /*entry*/) const override {
    grow_network_classes(context.config, context.source, context.heightfield, *context.existing,
                         context.lines, context.plan.report.classes, context.warnings);
  }

  json encode(const MethodPlan& /*entry*/, PlanObjects& /*objects*/) const override {
    return nullptr;
  }
  void decode(const json& /*value*/, PlanObjects& /*objects*/,
              MethodPlan& /*entry*/) const override {}
};

}  // namespace

const SynthesisMethod& network_method() {
  static const NetworkMethod method;
  return method;
}

}  // namespace tw::detail
