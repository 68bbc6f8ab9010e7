#include "pipeline/methods/patterns/pattern_method.hpp"

#include <algorithm>
#include <map>
#include <span>
#include <utility>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "core/output_folder.hpp"
#include "pipeline/detail/plan_binary.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_report_parts.hpp"
#include "pipeline/detail/plan_synthesis.hpp"
#include "pipeline/detail/tile_cache.hpp"
#include "pipeline/methods/patterns/pattern_config.hpp"
#include "pipeline/methods/patterns/pattern_inputs.hpp"
#include "pipeline/methods/patterns/pattern_report.hpp"
#include "pipeline/methods/patterns/pattern_tasks.hpp"
#include "pipeline/methods/patterns/synthesis_cache.hpp"
#include "raster/footprint.hpp"
#include "raster/sparse_raster.hpp"
#include "synth/pattern_canvas.hpp"
#include "synth/placements_io.hpp"
#include "synth/render.hpp"
#include "terrain/pattern_layers.hpp"
#include "terrain/splat.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;

// The codec's field lists of its own types (detail/plan_codec.hpp).
#define TW_FIELDS TW_DEFINE_PLAN_FIELDS
#define F TW_FIELD
TW_FIELDS(CostTexels, F(width) F(height) F(rgba) F(binary_alpha))
TW_FIELDS(Exemplar, F(width) F(height) F(channel_names) F(texels) F(cost) F(path))
TW_FIELDS(PatternTarget, F(exemplar_channel) F(to_height) F(material) F(is_alpha))
TW_FIELDS(Placement,
          F(ux) F(uy) F(exemplar) F(empty) F(origin) F(along) F(across) F(scale) F(stitch))
TW_FIELDS(MixLayout, F(x0) F(width) F(height) F(gap))
TW_FIELDS(FeatureSynthesisReport,
          F(exemplar) F(seed) F(backend) F(mean_valid_positions) F(omega) F(mean_seam_cost)
              F(mean_seam_cost_stitched) F(violations) F(empty_pieces) F(canvas_width)
                  F(canvas_height) F(avoidance_seconds) F(synthesis_seconds) F(render_seconds)
                      F(placements) F(objective) F(min_coverage) F(min_coverage_from_exemplar)
                          F(coverage_ratio) F(mean_coverage) F(natural_coverage)
                              F(parametric_seam_cost) F(width_m) F(delta_m) F(width_from)
                                  F(delta_from) F(mix_exemplars) F(pieces_per_exemplar)
                                      F(exemplar_switches) F(switch_cost))
TW_FIELDS(PatternFeatureReport, F(synthesis) F(cache))
TW_FIELDS(GrownSynthesisReport, F(dressed) F(no_room))
TW_FIELDS(PatternsReport, F(features) F(grown) F(violations))
#undef F
#undef TW_FIELDS

namespace {

std::vector<ChannelMapping> mappings_of(const FeatureClassConfig& c, const Exemplar& exemplar) {
  const SynthesisConfig& synthesis = *method_options<SynthesisConfig>(c, kPatternsMethodName);
  if (!synthesis.channels.empty()) return synthesis.channels;
  std::vector<ChannelMapping> mappings = {{"A", "splat." + c.name + "_pattern"}};
  if (exemplar.channel_index("height") >= 0) mappings.push_back({"height", "height"});
  return mappings;
}

// The patterns as the renderer needs them, and their splat materials in order of first use
// (the order an untiled render adds them in). Throws tw::Error naming the class and the channel
// when an exemplar lacks a mapped channel.
void plan_patterns(const PipelineConfig& config, PatternRun run, WorldPlan& plan,
                   PatternsPlan& out) {
  const auto material_index = [&](const std::string& target) {
    const std::string material = target.substr(6);  // after "splat."
    auto it = std::find(plan.splat_materials.begin(), plan.splat_materials.end(), material);
    if (it == plan.splat_materials.end()) {
      plan.splat_materials.push_back(material);
      it = plan.splat_materials.end() - 1;
    }
    return std::size_t(it - plan.splat_materials.begin());
  };
  out.patterns.clear();
  for (FeaturePattern& p : run.patterns) {
    const FeatureClassConfig& c = config.features[p.class_index];
    const Exemplar& exemplar = run.exemplars[p.exemplar_index];
    if (!p.synthesized) {  // outside the region: its bands still come in the same order
      if (p.on_ground && ribbon_window(p.ribbon, plan.grid).width > 0)
        for (const ChannelMapping& m : mappings_of(c, exemplar))
          if (m.target != "height") material_index(m.target);
      continue;
    }
    PlannedPattern& planned = out.patterns.emplace_back();
    planned.class_index = p.class_index;
    planned.feature_index = p.feature_index;
    planned.exemplar_index = p.exemplar_index;
    planned.on_ground = p.on_ground;
    // The render reaches kCanvasHalo cells beyond the pieces (synth/pattern_canvas.hpp).
    const Window on_grid = p.on_ground ? ribbon_window(p.ribbon, plan.grid) : Window{};
    planned.window = on_grid.width > 0 ? grow_window(on_grid, kCanvasHalo, plan.grid) : Window{};
    planned.ribbon = std::move(p.ribbon);
    planned.synthesis = std::move(p.synthesis);
    const SynthesisConfig& synthesis = *method_options<SynthesisConfig>(c, kPatternsMethodName);
    planned.stitch = synthesis.stitch;
    planned.feather = synthesis.feather;
    planned.height_detail = float(synthesis.height_detail);
    if (planned.window.width == 0) continue;  // off the grid: no band is added
    for (const ChannelMapping& m : mappings_of(c, exemplar)) {
      PatternTarget& target = planned.targets.emplace_back();
      target.exemplar_channel = exemplar.channel_index(m.channel);
      if (target.exemplar_channel < 0) {
        fail("features.{}.synthesis.channels.{}: exemplar {} has no channel '{}' (it has {})",
             c.name, m.channel, exemplar.path, m.channel, fmt::join(exemplar.channel_names, ", "));
      }
      target.to_height = m.target == "height";
      target.is_alpha = m.channel == "A";
      if (target.to_height) continue;
      target.material = material_index(m.target);
    }
  }
  out.exemplars = std::move(run.exemplars);
  out.unread = std::move(run.unread);
}

// The synthesis ribbon's width and delta in the feature's report, and where they came from.
void record_geometry(const SynthesisConfig& s, const FeatureReport& feature,
                     FeatureSynthesisReport& r) {
  r.width_m = s.width.value_or(feature.width_m);
  r.width_from = s.width_of_feature ? "feature" : s.width_from_exemplar ? "exemplar" : "config";
  r.delta_m = s.delta.value_or(0.0);
  r.delta_from = s.delta_from_exemplar ? "exemplar" : "config";
}

// A pattern without its synthesis, which goes to its own placements file.
template <class Io>
void pattern_fields(Io& io, PlannedPattern& p) {
  io("class_index", p.class_index);
  io("feature_index", p.feature_index);
  io("exemplar_index", p.exemplar_index);
  io("on_ground", p.on_ground);
  io("ribbon", p.ribbon);
  io("window", p.window);
  io("stitch", p.stitch);
  io("feather", p.feather);
  io("height_detail", p.height_detail);
  io("targets", p.targets);
}

// What a placements file holds of a synthesis (synth/placements_io), the fields a plan keeps.
template <class Io>
void placements_file_fields(Io& io, Synthesis& s) {
  io("column", s.column);
  io("closed", s.closed);
  io("backend", s.backend);
  io("total_cost", s.total_cost);
  io("mean_seam_cost", s.mean_seam_cost);
  io("mean_seam_cost_stitched", s.mean_seam_cost_stitched);
  io("valid_counts", s.valid_counts);
  io("mix", s.mix);
  io("pieces_per_exemplar", s.pieces_per_exemplar);
  io("exemplar_switches", s.exemplar_switches);
  io("placements", s.placements);
}

class PatternMethod final : public SynthesisMethod {
 public:
  std::string name() const override { return kPatternsMethodName; }
  std::string stage_name() const override { return "synthesis"; }
  MethodStage stage() const override { return MethodStage::placements; }
  bool serves(const PipelineConfig& config, const PlanOptions& options) const override {
    return options.synthesize && !synthesis_order(config).empty();
  }
  std::unique_ptr<MethodPayload> empty_payload() const override {
    return std::make_unique<PatternsPlan>();
  }
  void resolve_defaults(PipelineConfig& config) const override {
    resolve_exemplar_defaults(config);
  }
  // Its pieces are the ribbons' (one pattern piece per ribbon piece, `synthesis.delta`), on a
  // ribbon of `synthesis.width` where it has its own.
  RibbonNeeds ribbon_needs(const FeatureClassConfig& c) const override {
    const SynthesisConfig* synthesis = method_options<SynthesisConfig>(c, kPatternsMethodName);
    if (!synthesis) return {};
    if (!synthesis->delta)
      fail("features.{}.synthesis: delta not resolved (with_method_defaults)", c.name);
    return {synthesis->delta, synthesis->width, false};
  }
  bool check_input(const InputFile& input, InputCheck& check) const override {
    return check_exemplar_input(input, check);
  }

  void plan(MethodContext& context, MethodPlan& entry) const override {
    const PipelineConfig& config = context.config;
    const WorldPlan& plan = context.plan;
    SynthesisCache cache(context.options.cache_dir ? context.options.cache_dir : config.cache_dir,
                         context.warnings);
    PatternOptions pattern_options;
    pattern_options.backend = context.options.backend;
    pattern_options.cache = &cache;
    if (config.region) {  // the patterns whose render reaches the region, and what they avoid
      const GridSpec output = window_grid(plan.grid, plan.output_window);
      const double reach = (kCanvasHalo + 2) * std::max(output.pixel_width, output.pixel_height);
      pattern_options.wanted = [output, reach](const GridSpec& canvas) {
        return canvas.origin_x - reach < output.origin_x + output.width * output.pixel_width &&
               output.origin_x < canvas.origin_x + canvas.width * canvas.pixel_width + reach &&
               canvas.origin_y - canvas.height * canvas.pixel_height - reach < output.origin_y &&
               output.origin_y - output.height * output.pixel_height < canvas.origin_y + reach;
      };
    }
    payload_as<PatternsPlan>(entry).run = std::make_shared<PatternRun>(synthesize_patterns(
        config, context.lines, *context.ribbons, *context.existing, pattern_options));
  }

  // The areas' shapes avoid the patterns' opaque coverage on the ground.
  void keep_out(const MethodPlan& entry, const GridSpec& lattice,
                SparseRaster<std::uint8_t>& forbidden) const override {
    const PatternsPlan& patterns = payload_as<PatternsPlan>(entry);
    if (!patterns.run) return;
    for (const FeaturePattern& p : patterns.run->patterns)
      if (p.on_ground) add_on_lattice(p.opaque, p.canvas, forbidden, lattice);
  }

  bool makes_tasks() const override { return true; }
  nlohmann::json plan_tasks(const WorldPlan& plan, MethodTasks& tasks) const override {
    return plan_pattern_tasks(plan, tasks);
  }
  MethodTaskRun run_task(const WorldPlan& plan, MethodTasks& tasks, const nlohmann::json& list,
                         std::size_t index) const override {
    return run_pattern_task(plan, tasks, list, index);
  }
  double complete_tasks(WorldPlan& plan, MethodPlan& entry, MethodTasks& tasks,
                        const nlohmann::json& list,
                        const std::function<MethodTaskResult(std::size_t)>& result) const override {
    return complete_pattern_tasks(plan, payload_as<PatternsPlan>(entry), tasks, list, result);
  }

  void collect(MethodContext& context, MethodPlan& entry) const override {
    PatternsPlan& patterns = payload_as<PatternsPlan>(entry);
    if (!patterns.run) return;
    add_patterns(context.config, std::move(*patterns.run), context.plan, context.warnings);
    patterns.run.reset();
  }

  std::vector<Window> windows(const WorldPlan& /*plan*/, const MethodPlan& entry) const override {
    std::vector<Window> out;
    for (const PlannedPattern& p : payload_as<PatternsPlan>(entry).patterns)
      out.push_back(p.window);
    return out;
  }

  bool renders() const override { return true; }

  // Each pattern is rendered on the blocks of the lattice its ribbon meets (kBlock pixels on
  // the world grid, as an untiled render), cut to the window.
  void render(const WorldPlan& plan, const MethodPlan& entry, const Window& window,
              Raster<float>& height, SplatLayers& splat) const override {
    const PatternsPlan& patterns = payload_as<PatternsPlan>(entry);
    constexpr int kBlock = 256;
    const SparseRaster<std::uint8_t> layout(plan.grid.width, plan.grid.height, 0, kBlock);
    for (const std::size_t p : items_meeting(entry.index, window)) {
      const PlannedPattern& pattern = patterns.patterns[p];
      if (!pattern.on_ground || pattern.targets.empty()) continue;
      const Exemplar& exemplar = patterns.texels(pattern.exemplar_index);
      for (const TileIndex t : ribbon_tiles(pattern.ribbon, plan.grid, kBlock, kCanvasHalo)) {
        const Window part = intersect(layout.tile_window(t), window);
        if (part.width == 0) continue;
        const RenderedPattern rendered =
            render_pattern(exemplar, pattern.ribbon, pattern.synthesis, plan.grid, part,
                           pattern.stitch, pattern.feather);
        std::vector<PatternLayerTarget> targets;
        for (const PatternTarget& target : pattern.targets) {
          targets.push_back({&rendered.channels[std::size_t(target.exemplar_channel)],
                             target.to_height, target.material, target.is_alpha});
        }
        add_pattern_to_layers(window, height, splat, part, rendered.coverage, targets,
                              pattern.height_detail);
      }
    }
  }

  std::vector<ContentHash> item_hashes(const WorldPlan& /*plan*/,
                                       const MethodPlan& entry) const override {
    const PatternsPlan& patterns = payload_as<PatternsPlan>(entry);
    std::vector<ContentHash> out;
    std::map<std::size_t, ContentHash> exemplars;
    for (const PlannedPattern& p : patterns.patterns) {
      auto it = exemplars.find(p.exemplar_index);
      if (it == exemplars.end()) {
        const Exemplar& exemplar = patterns.exemplars[p.exemplar_index];
        const fs::path path = exemplar.path;
        const fs::path height = exemplar_height_path(path);
        std::error_code ec;
        Hasher e;
        if (fs::is_regular_file(path, ec)) {
          e.file(path).file(height);
        } else {  // a mix's atlas (synth/exemplar_mix.hpp) names no one file: its texels
          e.text(exemplar.path).i64(exemplar.width).i64(exemplar.height);
          for (const std::string& name : exemplar.channel_names) e.text(name);
          e.bytes(std::as_bytes(std::span(exemplar.texels)));
        }
        it = exemplars.emplace(p.exemplar_index, e.digest()).first;
      }
      Hasher h;
      h.hash(it->second).text(placements_to_json(p.synthesis, "")).hash(ribbon_hash(p.ribbon));
      h.boolean(p.on_ground).boolean(p.stitch).real(p.feather).real(p.height_detail);
      hash_window(h, p.window);
      h.u64(p.targets.size());
      for (const PatternTarget& t : p.targets)
        h.i64(t.exemplar_channel).boolean(t.to_height).u64(t.material).boolean(t.is_alpha);
      out.push_back(h.digest());
    }
    return out;
  }

  std::string outputs_stage(const WorldPlan& /*plan*/, const MethodPlan& /*entry*/) const override {
    return "placements";
  }

  // placements/<class>_<fid>.json (a multi-part FID adds _<part>), named in the feature's
  // report. The backend field is left out so that every backend writes the same bytes.
  void write_outputs(const WorldPlan& plan, const MethodPlan& entry,
                     MethodOutputs& outputs) const override {
    const PatternsPlan& patterns = payload_as<PatternsPlan>(entry);
    std::map<std::string, int> parts;
    for (const PlannedPattern& p : patterns.patterns) {
      std::string name = fmt::format("{}_{}", plan.class_names[p.class_index],
                                     plan.lines[p.class_index][p.feature_index].fid);
      if (const int part = parts[name]++; part > 0) name += fmt::format("_{}", part);
      const std::string file = "placements/" + name + ".json";
      Synthesis saved = p.synthesis;
      saved.backend.clear();
      save_placements(saved, patterns.exemplars[p.exemplar_index].path,
                      outputs.transaction.stage(outputs.dir / file).string());
      if (PatternsReport* report = method_report<PatternsReport>(outputs.report))
        if (auto& feature = report->features.at(p.class_index).at(p.feature_index))
          feature->synthesis.placements = file;
    }
  }

  // Per synthesized feature its `synthesis` and `cache`, its timings under
  // `timings.synthesis`, a grown class's `grow.synthesis`, and the violations over every
  // feature.
  void report_json(const RunReport& report, const PipelineConfig& /*config*/,
                   json& out) const override {
    const PatternsReport* part = method_report<PatternsReport>(report);
    json timings = json::array();
    for (std::size_t c = 0; c < report.classes.size(); ++c) {
      const FeatureClassReport& fc = report.classes[c];
      if (part && c < part->grown.size() && part->grown[c])
        out["classes"][c]["grow"]["synthesis"] = {{"dressed", part->grown[c]->dressed},
                                                  {"no_room", part->grown[c]->no_room}};
      for (std::size_t i = 0; i < fc.features.size(); ++i) {
        const PatternFeatureReport* f = part ? part->feature(c, i) : nullptr;
        if (!f) continue;
        json& feature = out["classes"][c]["features"][i];
        const FeatureSynthesisReport& s = f->synthesis;
        feature["synthesis"] = {
            {"exemplar", s.exemplar},
            {"seed", s.seed},
            {"backend", s.backend},
            {"mean_valid_positions", s.mean_valid_positions},
            {"omega", s.omega},
            {"mean_seam_cost", s.mean_seam_cost},
            {"mean_seam_cost_stitched", s.mean_seam_cost_stitched},
            {"objective", s.objective},
            {"min_coverage", s.min_coverage},
            {"min_coverage_from", s.min_coverage_from_exemplar ? "exemplar" : "pipeline"},
            {"coverage_ratio", s.coverage_ratio},
            {"mean_coverage", s.mean_coverage},
            {"natural_coverage", s.natural_coverage},
            {"parametric_seam_cost", s.parametric_seam_cost},
            {"width_m", s.width_m},
            {"width_from", s.width_from},
            {"delta_m", s.delta_m},
            {"delta_from", s.delta_from},
            {"empty_pieces", s.empty_pieces},
            {"violations", s.violations},
            {"canvas", {s.canvas_width, s.canvas_height}},
            {"placements", s.placements}};
        if (!s.mix_exemplars.empty()) {  // choose: mix
          feature["synthesis"]["mix"] = {{"exemplars", s.mix_exemplars},
                                         {"pieces_per_exemplar", s.pieces_per_exemplar},
                                         {"switches", s.exemplar_switches},
                                         {"switch_cost", s.switch_cost}};
        }
        feature["cache"] = {{"status", f->cache.reused ? "reused" : "rebuilt"},
                            {"why", f->cache.why},
                            {"key", f->cache.key}};
        timings.push_back({{"class", fc.name},
                           {"fid", report.classes[c].features[i].fid},
                           {"avoidance", s.avoidance_seconds},
                           {"synthesis", s.synthesis_seconds},
                           {"render", s.render_seconds}});
      }
    }
    out["timings"]["synthesis"] = std::move(timings);
    out["pattern_violations"] = part ? part->violations : 0;
  }

  // Its report: the features' timings apart, per class, per feature ([avoidance, synthesis,
  // render] seconds; null: not synthesized).
  json encode_report(const MethodPayload& part, PlanObjects& objects) const override {
    return detail::put_report_part<PatternsReport>(part, objects);
  }
  std::unique_ptr<MethodPayload> decode_report(const json& value,
                                               PlanObjects& objects) const override {
    return detail::get_report_part<PatternsReport>(value, objects, "patterns");
  }
  json take_report_timings(MethodPayload& part) const override {
    json classes = json::array();
    for (auto& features : dynamic_cast<PatternsReport&>(part).features) {
      json list = json::array();
      for (auto& f : features) {
        json seconds;
        if (f) {
          FeatureSynthesisReport& s = f->synthesis;
          seconds = {std::exchange(s.avoidance_seconds, 0.0),
                     std::exchange(s.synthesis_seconds, 0.0), std::exchange(s.render_seconds, 0.0)};
        }
        list.push_back(std::move(seconds));
      }
      classes.push_back(std::move(list));
    }
    return classes;
  }
  void restore_report_timings(const json& timings, MethodPayload& part) const override {
    auto& features = dynamic_cast<PatternsReport&>(part).features;
    for (std::size_t c = 0; c < features.size() && c < timings.size(); ++c) {
      for (std::size_t i = 0; i < features[c].size() && i < timings[c].size(); ++i) {
        const json& seconds = timings[c][i];
        if (!features[c][i] || !seconds.is_array() || seconds.size() != 3) continue;
        FeatureSynthesisReport& s = features[c][i]->synthesis;
        s.avoidance_seconds = seconds[0].get<double>();
        s.synthesis_seconds = seconds[1].get<double>();
        s.render_seconds = seconds[2].get<double>();
      }
    }
  }

  // The exemplars (texels) as binary objects, with their source's hash when it is a file; each
  // pattern as a binary object holding its synthesis as its placements file does
  // (pattern_to_bytes). Bytes, not a JSON tree: decoding them was 6 % of a render-tile.
  json encode(const MethodPlan& entry, PlanObjects& objects) const override {
    const PatternsPlan& plan = payload_as<PatternsPlan>(entry);
    json exemplars = json::array();
    for (std::size_t i = 0; i < plan.exemplars.size(); ++i) {
      const Exemplar& e = plan.texels(i);
      json item = objects.put_binary(to_bytes(e));
      item["path"] = e.path;
      std::error_code ec;  // the source's hash, when it is a file (a generated exemplar is not)
      item["source_xxh3_128"] =
          fs::is_regular_file(e.path, ec) ? json(content_hash(read_file_bytes(e.path))) : json();
      exemplars.push_back(std::move(item));
    }
    json patterns = json::array();
    for (const PlannedPattern& p : plan.patterns)
      patterns.push_back(objects.put_binary(pattern_to_bytes(p)));
    return {{"exemplars", exemplars}, {"patterns", patterns}};
  }

  void decode(const json& value, PlanObjects& objects, MethodPlan& entry) const override {
    PatternsPlan& plan = payload_as<PatternsPlan>(entry);
    const std::string where = "plan " + (objects.dir() / "plan.json").string();
    const json& exemplars = value.at("exemplars");
    for (std::size_t i = 0; i < exemplars.size(); ++i) {
      const std::string key = fmt::format("methods.patterns.exemplars[{}]", i);
      from_bytes(objects.get_binary(exemplars[i], key).body(), plan.exemplars.emplace_back(),
                 where + ": " + key);
    }
    const json& patterns = value.at("patterns");
    for (std::size_t i = 0; i < patterns.size(); ++i) {
      const std::string key = fmt::format("methods.patterns.patterns[{}]", i);
      PlannedPattern& p = plan.patterns.emplace_back();
      pattern_from_bytes(objects.get_binary(patterns[i], key).body(), p, where + ": " + key);
      if (p.exemplar_index >= plan.exemplars.size())
        fail("{}: {}.exemplar_index {} of {} exemplars", where, key, p.exemplar_index,
             plan.exemplars.size());
    }
  }
};

}  // namespace

std::string pattern_to_bytes(const PlannedPattern& pattern) {
  // The synthesis as its placements file holds it (read back from that file's text, as plans
  // before version 10 stored it): the same values as a plan of then decoded.
  PlannedPattern p = pattern;
  p.synthesis = placements_from_json(placements_to_json(pattern.synthesis, ""), "(plan)");
  BinaryWriter writer;
  pattern_fields(writer, p);
  placements_file_fields(writer, p.synthesis);
  return std::move(writer.bytes);
}

void pattern_from_bytes(std::string_view bytes, PlannedPattern& p, const std::string& where) {
  BinaryReader reader(bytes, where);
  pattern_fields(reader, p);
  Synthesis& s = p.synthesis;
  placements_file_fields(reader, s);
  reader.finish();
  // What the placements reader checks of a mix, which the renderer relies on.
  if (s.mix) {
    const MixLayout& mix = *s.mix;
    if (mix.x0.empty() || mix.width.size() != mix.x0.size() || mix.height.size() != mix.x0.size())
      fail("{}: its mix needs one x0, width and height per exemplar", where);
    for (const Placement& placement : s.placements)
      if (placement.exemplar < 0 || placement.exemplar >= mix.count())
        fail("{}: placement exemplar {} is not one of the mix's {} exemplars", where,
             placement.exemplar, mix.count());
  }
}

void exemplar_from_bytes(std::string_view bytes, Exemplar& exemplar, const std::string& where) {
  from_bytes(bytes, exemplar, where);
}

std::string exemplar_to_bytes(const Exemplar& exemplar) {
  return to_bytes(exemplar);
}

const Exemplar& PatternsPlan::texels(std::size_t index) const {
  const std::lock_guard lock(*texels_mutex_);
  return read_texels(exemplars, unread, index);
}

const SynthesisMethod& pattern_method() {
  static const PatternMethod method;
  return method;
}

const PatternsPlan* patterns_plan(const WorldPlan& plan) {
  const MethodPlan* entry = find_method_plan(plan, "patterns");
  return entry ? &payload_as<PatternsPlan>(*entry) : nullptr;
}

PatternsPlan* patterns_plan(WorldPlan& plan) {
  MethodPlan* entry = find_method_plan(plan, "patterns");
  return entry ? &payload_as<PatternsPlan>(*entry) : nullptr;
}

void add_patterns(const PipelineConfig& config, PatternRun patterns, WorldPlan& plan,
                  Warnings& warnings) {
  PatternsReport& report = method_report<PatternsReport>(plan.report, "patterns");
  report = PatternsReport{};
  report.grown.resize(config.features.size());
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    report.features.emplace_back(plan.report.classes[c].features.size());
    if (has_method_options(config.features[c], kPatternsMethodName) &&
        has_method_options(config.features[c], kGrownMethodName))
      report.grown[c].emplace();
  }
  for (const FeaturePattern& p : patterns.patterns) {
    if (!p.synthesized) continue;  // left out by a region (PatternOptions::wanted)
    PatternFeatureReport& feature = report.features.at(p.class_index).at(p.feature_index).emplace();
    feature.synthesis = p.report;
    record_geometry(
        *method_options<SynthesisConfig>(config.features[p.class_index], kPatternsMethodName),
        plan.report.classes[p.class_index].features[p.feature_index], feature.synthesis);
    feature.cache = p.cache;
    report.violations += p.report.violations;
    if (auto& grown = report.grown[p.class_index]) {
      const bool bare = std::size_t(p.report.empty_pieces) == p.synthesis.placements.size();
      ++(bare ? grown->no_room : grown->dressed);
    }
  }
  // Bare lines are no error (short lines between joints), but a class none of whose lines
  // took its pattern is a setting that does not fit (too wide, too long pieces).
  for (std::size_t c = 0; c < config.features.size(); ++c) {
    const auto& grown = report.grown[c];
    if (!grown || grown->dressed > 0 || grown->no_room == 0) continue;
    warnings.add("grown_undressed", "features." + config.features[c].name, std::nullopt,
                 fmt::format("synthesis dressed 0 of {} grown lines: every piece had no room "
                             "(a narrower synthesis.width or a shorter delta may fit)",
                             grown->no_room));
  }
  PatternsPlan* entry = patterns_plan(plan);
  if (!entry) fail("plan: no patterns entry to add {} patterns to", patterns.patterns.size());
  plan_patterns(config, std::move(patterns), plan, *entry);
}

}  // namespace tw::detail
