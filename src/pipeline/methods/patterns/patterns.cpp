#include "pipeline/methods/patterns/patterns.hpp"

#include <algorithm>
#include <map>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "core/split_mix.hpp"
#include "pipeline/detail/piece_length.hpp"
#include "pipeline/methods/patterns/pattern_bindings.hpp"
#include "pipeline/methods/patterns/pattern_config.hpp"
#include "pipeline/methods/patterns/synthesis_cache.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/avoidance.hpp"
#include "synth/feature_synthesis.hpp"
#include "synth/pattern_canvas.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

struct ClassPlan {
  std::size_t class_index = 0;
  std::vector<std::size_t> exemplars;  // indices into PatternRun::exemplars
  BackendKind backend = BackendKind::automatic;
  // choose: mix: the atlas (its copy in PatternRun::exemplars at mix_index), and [rule][feature]
  // whether each bind rule's predicate selects the line.
  std::optional<MixedExemplar> mix;
  std::size_t mix_index = 0;
  std::vector<std::vector<std::uint8_t>> matches;
};

// The DP's parameters from a class's synthesis values.
SynthParams synth_params(const SynthesisConfig& synthesis, BackendKind backend, std::uint64_t seed,
                         const std::string& label) {
  SynthParams params;
  params.scale = synthesis.scale;
  params.seed = seed;
  params.stitch = synthesis.stitch;
  params.backend = backend;
  params.allow_empty_pieces = synthesis.empty_pieces;
  params.min_coverage = synthesis.min_coverage.value_or(-1.0);  // < 0: from the exemplar
  params.objective = synthesis.objective;
  params.coverage_weight = synthesis.coverage_weight;
  params.feature_label = label;
  params.switch_cost = synthesis.switch_cost;
  return params;
}

std::string pattern_label(const FeatureClassConfig& c, std::int64_t fid) {
  return fmt::format("features.{}: FID {}", c.name, fid);
}

// Which canvases (synthesis order) to synthesize: the wanted ones and, from the last back,
// every earlier one overlapping a canvas already kept (its opaque coverage is avoided there).
std::vector<bool> needed_canvases(const std::vector<GridSpec>& canvases,
                                  const std::function<bool(const GridSpec&)>& wanted) {
  std::vector<bool> needed(canvases.size(), true);
  if (!wanted) return needed;
  for (std::size_t i = 0; i < canvases.size(); ++i) needed[i] = wanted(canvases[i]);
  for (std::size_t i = canvases.size(); i-- > 0;) {
    if (!needed[i]) continue;
    for (std::size_t j = 0; j < i; ++j)
      needed[j] = needed[j] || canvases_overlap(canvases[j], canvases[i]);
  }
  return needed;
}

}  // namespace

Exemplar load_exemplar_with_height(const fs::path& path, bool continuous_alpha) {
  ExemplarOptions options;
  options.continuous_alpha = continuous_alpha;
  const fs::path height = exemplar_height_path(path);
  if (fs::exists(height)) options.height_path = height.string();
  return load_exemplar(path.string(), options);
}

const Exemplar& read_texels(std::deque<Exemplar>& exemplars, std::map<std::size_t, bool>& unread,
                            std::size_t index) {
  if (const auto it = unread.find(index); it != unread.end()) {
    exemplars[index] = load_exemplar_with_height(exemplars[index].path, it->second);
    unread.erase(it);
  }
  return exemplars[index];
}

PatternRun synthesize_patterns(const PipelineConfig& config,
                               const std::vector<std::vector<LineFeature>>& lines,
                               const FeatureRibbons& ribbons, const ExistingFeatures& existing,
                               const PatternOptions& options) {
  PatternRun run;
  std::vector<ClassPlan> plans;
  for (const std::string& name : synthesis_order(config)) {
    const auto it = std::find_if(config.features.begin(), config.features.end(),
                                 [&](const FeatureClassConfig& c) { return c.name == name; });
    const SynthesisConfig* synthesis =
        it == config.features.end() ? nullptr
                                    : method_options<SynthesisConfig>(*it, kPatternsMethodName);
    if (!synthesis) fail("synthesis_order: '{}' is not a feature class with synthesis", name);
    ClassPlan& plan = plans.emplace_back();
    plan.class_index = std::size_t(it - config.features.begin());
    const bool mix = synthesis->choice == ExemplarChoice::mix;  // its atlas: texels now
    for (const fs::path& path : synthesis->exemplars) {
      plan.exemplars.push_back(run.exemplars.size());
      std::optional<Exemplar> known =
          options.cache && !mix ? options.cache->remembered(path) : std::nullopt;
      if (known) run.unread[run.exemplars.size()] = synthesis->continuous_alpha;
      run.exemplars.push_back(known ? std::move(*known)
                                    : load_exemplar_with_height(path, synthesis->continuous_alpha));
    }
    if (synthesis->choice == ExemplarChoice::mix) {
      plan.matches = binding_matches(*it, lines[plan.class_index]);
      // One atlas for the class: its gap holds the widest feature's pieces (synthesize checks).
      double width = 0.0;
      for (const LineFeature& line : lines[plan.class_index])
        width = std::max(width, synthesis->width.value_or(line.width));
      std::vector<const Exemplar*> exemplars;
      for (const std::size_t e : plan.exemplars) exemplars.push_back(&run.exemplars[e]);
      plan.mix =
          mix_exemplars(exemplars, mix_gap(synthesis->scale, class_piece_length(*it), width));
      plan.mix_index = run.exemplars.size();
      run.exemplars.push_back(plan.mix->atlas);
    }
    const std::string backend =
        options.backend.value_or(synthesis->backend.empty() ? config.backend : synthesis->backend);
    plan.backend = parse_backend_kind(backend);
  }

  // What every pattern avoids besides its own fold-overs and the patterns before it.
  AvoidanceInputs fixed;
  fixed.polygons = existing.polygons;
  fixed.lines = existing.lines;
  fixed.line_widths = existing.line_widths;
  fixed.junction_discs = ribbons.synthesis_junction_discs;
  fixed.include_foldovers = false;

  SynthesisBackends backends;
  Warnings no_warnings;  // a cache without a folder never warns
  SynthesisCache keys_only(std::nullopt, no_warnings);
  SynthesisCache& cache = options.cache ? *options.cache : keys_only;
  std::vector<EarlierSynthesis> earlier_keys;
  std::map<std::string, int> parts;  // a multi-part FID's pieces are <name>_1, <name>_2, ...
  const double cell = config.synthesis_resolution;
  // "feature i of N" in the log: the DP's progress lines (with their ETA) follow each.
  std::size_t feature_count = 0, feature_number = 0;
  for (const ClassPlan& plan : plans)
    for (const Ribbon& ribbon : ribbons.ribbons[plan.class_index])
      feature_count += ribbon.pieces.empty() ? 0 : 1;
  // The synthesis ribbon of a feature (synthesis.width, or the feature's own).
  const auto synthesis_ribbon = [&](const ClassPlan& plan, std::size_t f) {
    const SynthesisConfig& synthesis =
        *method_options<SynthesisConfig>(config.features[plan.class_index], kPatternsMethodName);
    const LineFeature& line = lines[plan.class_index][f];
    return synthesis.width ? make_ribbon(Curve{line.points, line.closed},
                                         {*synthesis.width, *synthesis.delta, 0.0})
                           : ribbons.ribbons[plan.class_index][f];
  };
  std::vector<bool> needed;
  if (options.wanted) {
    std::vector<GridSpec> canvases;
    for (const ClassPlan& plan : plans)
      for (std::size_t f = 0; f < lines[plan.class_index].size(); ++f)
        if (!ribbons.ribbons[plan.class_index][f].pieces.empty())
          canvases.push_back(synthesis_canvas(
              synthesis_ribbon(plan, f), cell, cell,
              pattern_label(config.features[plan.class_index], lines[plan.class_index][f].fid)));
    needed = needed_canvases(canvases, options.wanted);
    feature_count = std::size_t(std::count(needed.begin(), needed.end(), true));
  }
  Progress progress("synthesis", std::int64_t(feature_count), "feature");
  std::size_t feature_position = 0;  // among the features with pieces, synthesis order
  for (const ClassPlan& plan : plans) {
    const FeatureClassConfig& feature_class = config.features[plan.class_index];
    const SynthesisConfig& synthesis =
        *method_options<SynthesisConfig>(feature_class, kPatternsMethodName);
    for (std::size_t f = 0; f < lines[plan.class_index].size(); ++f) {
      const LineFeature& line = lines[plan.class_index][f];
      if (ribbons.ribbons[plan.class_index][f].pieces.empty()) continue;
      const bool wanted = needed.empty() || needed[feature_position++];
      const std::string label = pattern_label(feature_class, line.fid);
      if (wanted)
        logger().info("synthesis: feature {} of {}: {}", ++feature_number, feature_count, label);
      FeaturePattern pattern;
      const Curve curve{line.points, line.closed};
      const double width = synthesis.width.value_or(line.width);
      pattern.ribbon = synthesis_ribbon(plan, f);
      pattern.class_index = plan.class_index;
      pattern.feature_index = f;
      pattern.on_ground = line.structure == Structure::ground;
      FeatureSynthesisReport& report = pattern.report;
      report.seed = feature_seed(config.seed, synthesis.seed, line.fid);

      pattern.canvas = synthesis_canvas(pattern.ribbon, cell, cell, label);
      const GridSpec& canvas = pattern.canvas;
      pattern.name = fmt::format("{}_{}", feature_class.name, line.fid);
      if (const int part = parts[pattern.name]++; part > 0)
        pattern.name += fmt::format("_{}", part);
      if (!wanted) {  // overlaps no canvas synthesized here: nothing below reads it
        pattern.synthesized = false;
        run.patterns.push_back(std::move(pattern));
        continue;
      }
      // A mix's bindings: each rule's verdict on the line and the junctions it meets.
      std::vector<PieceBinding> bindings;
      std::vector<Vec2> junctions;
      if (plan.mix) {
        bindings = feature_bindings(synthesis, plan.matches, f);
        if (plan.class_index < ribbons.synthesis_junctions.size() &&
            f < ribbons.synthesis_junctions[plan.class_index].size())
          junctions = ribbons.synthesis_junctions[plan.class_index][f];
      }
      const SynthesisKey key =
          cache.key(config, feature_class, line, report.seed, canvas, fixed, earlier_keys, bindings,
                    junctions, plan.mix ? plan.mix->layout.gap : 0);
      pattern.key = key.combined();
      for (std::size_t e = 0; e < earlier_keys.size(); ++e)
        if (canvases_overlap(earlier_keys[e].canvas, canvas)) pattern.after.push_back(e);
      earlier_keys.push_back({canvas, pattern.key});
      const std::size_t index = earlier_keys.size() - 1;
      using Scope = PatternOptions::Scope;
      const bool one = options.scope == Scope::one;
      const bool the_one = one && index == options.feature;  // synthesized, never looked up
      if (one && index > options.feature) return run;
      if (one && !the_one &&
          std::find(options.after.begin(), options.after.end(), index) == options.after.end())
        continue;  // not on its canvas: skipped
      std::optional<CachedSynthesis> cached;
      if (!the_one)
        cached = cache.find("features." + feature_class.name, line.fid, pattern.name, key,
                            pattern.cache);
      else  // its key missed when planned: the finer check below goes by why
        pattern.cache = {options.planned.reused, options.planned.why, key.combined().hex()};
      if (!cached && (options.scope == Scope::cached || (one && !the_one))) {
        fail(
            "{}: its synthesis (feature {} of the plan, key {}) is not done yet (terraweave "
            "synth-feature PLAN --feature {})",
            label, index, pattern.cache.key, index);
      }
      if (options.scope == Scope::keys) {
        run.patterns.push_back(std::move(pattern));
        continue;
      }
      // A synthesis from the cache, as if synthesized here.
      const auto reuse = [&](CachedSynthesis& entry) {
        if (entry.start) pattern.ribbon = make_ribbon(*entry.start, {width, *synthesis.delta, 0.0});
        pattern.synthesis = std::move(entry.synthesis);
        pattern.exemplar_index = plan.mix ? plan.mix_index : plan.exemplars.at(entry.exemplar_slot);
        pattern.opaque = std::move(entry.opaque);
        pattern.report = std::move(entry.report);
        if (plan.mix) {
          // The cached report holds the list already: set, not appended to.
          pattern.report.mix_exemplars.clear();
          for (const fs::path& path : synthesis.exemplars)
            pattern.report.mix_exemplars.push_back(path.string());
          pattern.report.pieces_per_exemplar = pattern.synthesis.pieces_per_exemplar;
          pattern.report.exemplar_switches = pattern.synthesis.exemplar_switches;
          pattern.report.switch_cost = synthesis.switch_cost;
        }
        logger().info("{}: reused from the cache ({}: {})", label, pattern.cache.key,
                      pattern.cache.why);
        run.patterns.push_back(std::move(pattern));
      };
      if (cached) {
        reuse(*cached);
        continue;
      }
      FeatureSynthesisOptions feature_options;
      feature_options.params = synth_params(synthesis, plan.backend, report.seed, label);
      feature_options.choice = synthesis.choice;
      feature_options.ribbon = {width, *synthesis.delta, 0.0};
      feature_options.canvas_tile = options.canvas_tile;
      // A grown class is many short lines between joints (junction discs) and the patterns
      // of its own earlier lines: one without room is left bare and counted (grow.synthesis).
      // So is a network class's line between two junctions.
      feature_options.no_room_is_error = !lines_made_by_a_method(feature_class);
      if (plan.mix) {
        feature_options.mix = &*plan.mix;
        feature_options.bindings = std::move(bindings);
        feature_options.junctions = std::move(junctions);
      }
      std::vector<EarlierPattern> earlier;
      for (const FeaturePattern& p : run.patterns)
        if (p.synthesized) earlier.push_back({&p.canvas, &p.opaque});
      FeatureAvoidance avoidance =
          feature_avoidance(curve, pattern.ribbon, canvas, fixed, earlier, feature_options);
      // The finer check: a key that changed only in what the avoidance might be is reused when
      // the DP would read the same (docs/cache.md, "A feature's synthesis").
      const ContentHash input = synthesis_input_hash(avoidance, feature_options.junctions);
      if (SynthesisCache::finer_check_may_reuse(pattern.cache))
        cached = cache.find_by_input("features." + feature_class.name, line.fid, key, input,
                                     pattern.cache);
      if (cached) {  // kept under the new key too: the next run finds it by that alone
        cache.store(pattern.name, key, input, cached->synthesis, cached->exemplar_slot,
                    cached->start ? &*cached->start : nullptr, cached->opaque, cached->report);
        reuse(*cached);
        run.patterns.back().report.avoidance_seconds = avoidance.seconds;
        continue;
      }
      std::vector<const Exemplar*> exemplars;
      for (const std::size_t e : plan.exemplars)
        exemplars.push_back(&read_texels(run.exemplars, run.unread, e));
      FeatureSynthesisResult result =
          synthesize_feature(backends, exemplars, std::move(avoidance), canvas, feature_options);
      pattern.ribbon = std::move(result.ribbon);
      pattern.synthesis = std::move(result.synthesis);
      pattern.exemplar_index = plan.mix ? plan.mix_index : plan.exemplars[result.exemplar_slot];
      pattern.opaque = std::move(result.opaque);
      pattern.report = std::move(result.report);
      cache.store(pattern.name, key, input, pattern.synthesis, result.exemplar_slot,
                  result.start ? &*result.start : nullptr, pattern.opaque, pattern.report);
      run.patterns.push_back(std::move(pattern));
      progress.advance();
    }
  }
  return run;
}

}  // namespace tw::detail
