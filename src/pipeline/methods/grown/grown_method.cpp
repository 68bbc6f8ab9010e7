#include "pipeline/methods/grown/grown_method.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/output_folder.hpp"
#include "ornament/element.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/plan_binary.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/grow_region.hpp"
#include "pipeline/methods/grown/grown_classes.hpp"

namespace tw::detail {

using nlohmann::json;

// The codec's field lists of its own types (detail/plan_codec.hpp).
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD
TW_FIELDS(GrownLine, F(ornament) F(element) F(name) F(material) F(points) F(heights))
TW_FIELDS(GrownClass, F(class_index) F(kind) F(height_m) F(lines))
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
    return c.source.string() + ":" + c.layer;
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<GrownPlan>();
  }
  // Its element sets (`grow.element`), read whole.
  bool check_input(const InputFile& input, InputCheck& /*check*/) const override {
    if (input.kind != InputFile::Kind::ornament) return false;
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
    RunReport& report = context.plan.report;
    payload_as<GrownPlan>(entry).classes =
        grow_classes(context.config.features, context.source, context.heightfield,
                     *context.existing, context.lines, report.classes, context.warnings);
    for (const FeatureClassReport& c : report.classes)
      if (c.grow)
        report.grown_crossings +=
            c.grow->crossings.grown + c.grow->crossings.feature + c.grow->crossings.forbidden;
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
    for (std::size_t i = 0; i < report.classes.size(); ++i) {
      const FeatureClassReport& c = report.classes[i];
      json& entry = out["classes"][i];
      if (c.grow) {
        const GrowthReport& g = *c.grow;
        entry["grown_kind"] = g.kind;  // `kind` stays the terrain profile's
        entry["grow"] = {{"element", g.element},
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
                         {"layer", "ornaments.gpkg:" + c.name}};
        if (g.synthesis)
          entry["grow"]["synthesis"] = {{"dressed", g.synthesis->dressed},
                                        {"no_room", g.synthesis->no_room}};
      }
    }
    out["grown_crossings"] = report.grown_crossings;
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
