#include "pipeline/methods/network/network_method.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_report_parts.hpp"
#include "pipeline/methods/network/network_classes.hpp"
#include "pipeline/methods/network/network_report.hpp"

namespace tw::detail {

using nlohmann::json;

// The codec's field lists of its own types (detail/plan_codec.hpp).
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD
TW_FIELDS(NetworkClassReport,
          F(exemplar) F(method) F(chosen) F(lead) F(lead_bearing_deg) F(exemplar_edges) F(lines)
              F(kept) F(placed) F(snapped) F(t_junctions) F(boundary_ends) F(pruned)
                  F(rejected_crossing) F(rejected_region) F(rejected_forbidden))
TW_FIELDS(NetworkReport, F(classes))
#undef F
#undef TW_FIELDS

namespace {

struct NetworkPlan : MethodPayloadOf<NetworkPlan> {};

class NetworkMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return kNetworkMethodName; }
  MethodStage stage() const override { return MethodStage::lines; }
  bool serves(const PipelineConfig& config, const PlanOptions& /*options*/) const override {
    return std::any_of(config.features.begin(), config.features.end(),
                       [&](const FeatureClassConfig& c) { return makes_lines_of(c); });
  }
  bool makes_lines_of(const FeatureClassConfig& c) const override {
    return has_method_options(c, kNetworkMethodName);
  }
  std::string class_source(const FeatureClassConfig& c) const override {
    return method_options<NetworkClassConfig>(c, kNetworkMethodName)->exemplar;
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<NetworkPlan>();
  }

  // After the grown classes, off everything before them; once, in the plan, so that every tile
  // and worker sees the same lines.
  void plan(MethodContext& context, MethodPlan& /*entry*/) const override {
    NetworkReport& report = method_report<NetworkReport>(context.plan.report, name());
    report = NetworkReport{};
    report.classes.resize(context.config.features.size());
    grow_network_classes(context.config.features, context.source, context.heightfield,
                         *context.existing, context.reserved, context.lines, report.classes,
                         context.warnings);
  }

  // Per network class its `network`.
  void report_json(const RunReport& report, const PipelineConfig& /*config*/,
                   json& out) const override {
    const NetworkReport* part = method_report<NetworkReport>(report);
    for (std::size_t i = 0; part && i < part->classes.size(); ++i) {
      if (!part->classes[i]) continue;
      const NetworkClassReport& n = *part->classes[i];
      out["classes"][i]["network"] = {{"exemplar", n.exemplar},
                                      {"method", n.method},
                                      {"chosen", n.chosen},
                                      {"exemplar_edges", n.exemplar_edges},
                                      {"lines", n.lines},
                                      {"kept", n.kept},
                                      {"placed", n.placed},
                                      {"snapped", n.snapped},
                                      {"t_junctions", n.t_junctions},
                                      {"boundary_ends", n.boundary_ends},
                                      {"pruned", n.pruned},
                                      {"rejected",
                                       {{"crossing", n.rejected_crossing},
                                        {"region", n.rejected_region},
                                        {"forbidden", n.rejected_forbidden}}}};
      if (!n.lead.empty()) {
        out["classes"][i]["network"]["lead"] = n.lead;
        out["classes"][i]["network"]["lead_bearing_deg"] = n.lead_bearing_deg;
      }
    }
  }

  json encode_report(const MethodPayload& part, PlanObjects& objects) const override {
    return detail::put_report_part<NetworkReport>(part, objects);
  }
  std::unique_ptr<MethodPayload> decode_report(const json& value,
                                               PlanObjects& objects) const override {
    return detail::get_report_part<NetworkReport>(value, objects, "network");
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
