#include "pipeline/detail/grown_method.hpp"

#include <algorithm>

#include "pipeline/detail/grown_classes.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"

namespace tw::detail {

using nlohmann::json;

namespace {

class GrownMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return "grown"; }
  std::string stage_name() const override { return "grow"; }
  MethodStage stage() const override { return MethodStage::lines; }
  bool serves(const PipelineConfig& config, const PlanOptions& /*options*/) const override {
    return std::any_of(config.features.begin(), config.features.end(),
                       [](const FeatureClassConfig& c) { return bool(c.grow); });
  }
  bool makes_lines_of(const FeatureClassConfig& c) const override { return bool(c.grow); }
  std::string class_source(const FeatureClassConfig& c) const override {
    return c.source.string() + ":" + c.layer;
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<GrownPlan>();
  }

  // Grown lines avoid the lines read and the existing features; everything after treats them
  // as the class's features.
  void plan(MethodContext& context, MethodPlan& entry) const override {
    RunReport& report = context.plan.report;
    payload_as<GrownPlan>(entry).classes =
        grow_classes(context.config, context.source, context.heightfield, *context.existing,
                     context.lines, report.classes, context.warnings);
    for (const FeatureClassReport& c : report.classes)
      if (c.grow)
        report.grown_crossings +=
            c.grow->crossings.grown + c.grow->crossings.feature + c.grow->crossings.forbidden;
  }

  json encode(const MethodPlan& entry, PlanObjects& objects) const override {
    return objects.put_cbor(detail::encode(payload_as<GrownPlan>(entry).classes));
  }

  void decode(const json& value, PlanObjects& objects, MethodPlan& entry) const override {
    detail::decode(objects.get_cbor(value, "methods.grown"), payload_as<GrownPlan>(entry).classes,
                   "plan " + (objects.dir() / "plan.json").string() + ": methods.grown");
  }
};

}  // namespace

const SynthesisMethod& grown_method() {
  static const GrownMethod method;
  return method;
}

const GrownPlan* grown_plan(const WorldPlan& plan) {
  const MethodPlan* entry = find_method_plan(plan, "grown");
  return entry ? &payload_as<GrownPlan>(*entry) : nullptr;
}

}  // namespace tw::detail
