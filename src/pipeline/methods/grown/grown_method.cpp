#include "pipeline/methods/grown/grown_method.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "ornament/element.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/plan_codec.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_report_parts.hpp"
#include "pipeline/detail/stages.hpp"
#include "pipeline/grow_region.hpp"
#include "pipeline/methods/grown/grown_classes.hpp"
#include "pipeline/methods/grown/grown_config.hpp"
#include "pipeline/methods/grown/grown_report.hpp"
#include "ribbon/ribbon.hpp"

namespace tw::detail {

using nlohmann::json;

// The codec's field lists of its own types (detail/plan_codec.hpp).
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD
TW_FIELDS(GrownLine, F(ornament) F(element) F(name) F(material) F(points) F(heights))
TW_FIELDS(GrownClass, F(class_index) F(kind) F(height_m) F(lines))
TW_FIELDS(GrownCrossings, F(grown) F(feature) F(forbidden))
TW_FIELDS(GrowthReport,
          F(kind) F(element) F(ornaments) F(elements) F(lines) F(rejected_crossing)
              F(rejected_forbidden) F(rejected_untraceable) F(rejected_footprint) F(crossings)
                  F(coverage) F(coverage_radius_m) F(mesh_width) F(mesh_height) F(short_lines))
TW_FIELDS(GrownReport, F(classes) F(crossings))
#undef F
#undef TW_FIELDS

namespace {

class GrownMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return kGrownMethodName; }
  std::string stage_name() const override { return "grow"; }
  MethodStage stage() const override { return MethodStage::lines; }
  bool serves(const PipelineConfig& config, const PlanOptions& /*options*/) const override {
    return std::any_of(config.features.begin(), config.features.end(),
                       [&](const FeatureClassConfig& c) { return makes_lines_of(c); });
  }
  bool makes_lines_of(const FeatureClassConfig& c) const override {
    return has_method_options(c, kGrownMethodName);
  }
  // Its lines are many short ones between joints: those shorter than a piece are counted in
  // its report (grow.short_lines), not warned about one by one.
  RibbonNeeds ribbon_needs(const FeatureClassConfig& c) const override {
    return {std::nullopt, std::nullopt, makes_lines_of(c)};
  }
  std::string class_source(const FeatureClassConfig& c) const override {
    return method_options<GrowConfig>(c, kGrownMethodName)->element.string();
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<GrownPlan>();
  }
  // Its element sets (`grow.element`), read whole.
  bool check_input(const InputFile& input, InputCheck& /*check*/) const override {
    if (input.kind != InputFile::Kind::method || input.role != kElementSetRole) return false;
    try {
      read_element_set(input.path);
    } catch (const Error& e) {
      fail("{}: cannot be used as an element set: {}", input.named_at, e.what());
    }
    return true;
  }

  // Grown lines avoid the lines read and the existing features; everything after treats them
  // as the class's features.
  void plan(MethodContext& context, MethodPlan& entry) const override {
    GrownReport& report = method_report<GrownReport>(context.plan.report, name());
    report = GrownReport{};
    report.classes.resize(context.config.features.size());
    payload_as<GrownPlan>(entry).classes =
        grow_classes(context.config.features, context.source, context.heightfield,
                     *context.existing, context.lines, report.classes, context.warnings);
    for (const std::optional<GrowthReport>& c : report.classes)
      if (c) report.crossings += c->crossings.grown + c->crossings.feature + c->crossings.forbidden;
  }

  // Once the ribbons are cut: the grown lines shorter than one piece.
  void collect(MethodContext& context, MethodPlan& /*entry*/) const override {
    GrownReport* report = method_report<GrownReport>(context.plan.report);
    if (!report || !context.ribbons) return;
    for (std::size_t c = 0; c < report->classes.size(); ++c) {
      if (!report->classes[c]) continue;
      const auto& ribbons = context.ribbons->ribbons.at(c);
      report->classes[c]->short_lines = int(std::count_if(
          ribbons.begin(), ribbons.end(), [](const Ribbon& r) { return r.pieces.empty(); }));
    }
  }

  std::string outputs_stage(const WorldPlan& /*plan*/, const MethodPlan& entry) const override {
    return payload_as<GrownPlan>(entry).classes.empty() ? "" : "ornaments.gpkg";
  }

  // ornaments.gpkg: one layer per grown class, named by it; FIDs as the class's features'.
  void write_outputs(const WorldPlan& plan, const MethodPlan& entry,
                     MethodOutputs& outputs) const override {
    std::vector<OrnamentLayer> layers;
    for (const GrownClass& g : payload_as<GrownPlan>(entry).classes)
      layers.push_back({plan.class_names.at(g.class_index), g.kind, g.height_m, &g.lines, {}});
    write_ornament_geopackage(outputs.transaction.stage(outputs.dir / "ornaments.gpkg"),
                              plan.crs_wkt, layers);
  }

  // Per grown class its `grow` (and `grown_kind`), and the crossings over every class.
  void report_json(const RunReport& report, const PipelineConfig& /*config*/,
                   json& out) const override {
    const GrownReport* part = method_report<GrownReport>(report);
    for (std::size_t i = 0; part && i < part->classes.size(); ++i) {
      if (!part->classes[i]) continue;
      const GrowthReport& g = *part->classes[i];
      json& entry = out["classes"][i];
      entry["grown_kind"] = g.kind;  // `kind` stays the terrain profile's
      json& grow = entry["grow"];    // its `synthesis` is the patterns'
      grow.update({{"element", g.element},
                   {"ornaments", g.ornaments},
                   {"elements", g.elements},
                   {"lines", g.lines},
                   {"rejected",
                    {{"crossing", g.rejected_crossing},
                     {"forbidden", g.rejected_forbidden},
                     {"untraceable", g.rejected_untraceable},
                     {"footprint", g.rejected_footprint}}},
                   {"crossings",
                    {{"grown", g.crossings.grown},
                     {"feature", g.crossings.feature},
                     {"forbidden", g.crossings.forbidden}}},
                   {"coverage", g.coverage},
                   {"coverage_radius_m", g.coverage_radius_m},
                   {"mesh", {g.mesh_width, g.mesh_height}},
                   {"short_lines", g.short_lines},
                   {"layer", "ornaments.gpkg:" + report.classes.at(i).name}});
    }
    out["grown_crossings"] = part ? part->crossings : 0;
  }

  json encode_report(const MethodPayload& part, PlanObjects& objects) const override {
    return detail::put_report_part<GrownReport>(part, objects);
  }
  std::unique_ptr<MethodPayload> decode_report(const json& value,
                                               PlanObjects& objects) const override {
    return detail::get_report_part<GrownReport>(value, objects, "grown");
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
