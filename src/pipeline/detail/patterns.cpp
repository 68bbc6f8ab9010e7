#include "pipeline/detail/patterns.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/progress.hpp"
#include "pipeline/detail/synthesis_cache.hpp"
#include "raster/avoidance.hpp"
#include "raster/foldover.hpp"
#include "synth/baseline.hpp"
#include "synth/detail/backend_factory.hpp"
#include "synth/pattern_canvas.hpp"
#include "synth/render.hpp"

namespace tw::detail {

namespace fs = std::filesystem;

namespace {

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool overlaps(const GridSpec& a, const GridSpec& b) {
  const double ax1 = a.origin_x + a.width * a.pixel_width;
  const double bx1 = b.origin_x + b.width * b.pixel_width;
  const double ay0 = a.origin_y - a.height * a.pixel_height;
  const double by0 = b.origin_y - b.height * b.pixel_height;
  return a.origin_x < bx1 && b.origin_x < ax1 && ay0 < b.origin_y && by0 < a.origin_y;
}

// One backend per kind, made on first use (an OpenCL context is costly to create).
class Backends {
 public:
  Backend& get(BackendKind kind) {
    auto& slot = backends_[kind];
    if (!slot) slot = make_backend(kind, nullptr);
    return *slot;
  }

 private:
  std::map<BackendKind, std::unique_ptr<Backend>> backends_;
};

struct ClassPlan {
  std::size_t class_index = 0;
  std::vector<std::size_t> exemplars;  // indices into PatternRun::exemplars
  BackendKind backend = BackendKind::automatic;
};

std::string pattern_label(const FeatureClassConfig& c, std::int64_t fid) {
  return fmt::format("features.{}: FID {}", c.name, fid);
}

}  // namespace

std::uint64_t feature_seed(std::uint64_t run_seed, std::uint64_t class_seed, std::int64_t fid) {
  std::uint64_t h = splitmix64(run_seed);
  h = splitmix64(h ^ class_seed);
  h = splitmix64(h ^ std::uint64_t(fid));
  return h == 0 ? 1 : h;
}

Exemplar load_exemplar_with_height(const fs::path& path, bool continuous_alpha) {
  ExemplarOptions options;
  options.continuous_alpha = continuous_alpha;
  const fs::path height = path.parent_path() / (path.stem().string() + "_height.tif");
  if (fs::exists(height)) options.height_path = height.string();
  return load_exemplar(path.string(), options);
}

PatternRun synthesize_patterns(const PipelineConfig& config,
                               const std::vector<std::vector<LineFeature>>& lines,
                               const FeatureRibbons& ribbons, const ExistingFeatures& existing,
                               const PatternOptions& options) {
  PatternRun run;
  std::vector<ClassPlan> plans;
  for (const std::string& name : config.synthesis_order) {
    const auto it = std::find_if(config.features.begin(), config.features.end(),
                                 [&](const FeatureClassConfig& c) { return c.name == name; });
    if (it == config.features.end() || !it->synthesis) {
      fail("synthesis_order: '{}' is not a feature class with synthesis", name);
    }
    ClassPlan& plan = plans.emplace_back();
    plan.class_index = std::size_t(it - config.features.begin());
    for (const fs::path& path : it->synthesis->exemplars) {
      plan.exemplars.push_back(run.exemplars.size());
      run.exemplars.push_back(load_exemplar_with_height(path, it->synthesis->continuous_alpha));
    }
    const std::string backend = options.backend.value_or(
        it->synthesis->backend.empty() ? config.backend : it->synthesis->backend);
    plan.backend = parse_backend_kind(backend);
  }

  // What every pattern avoids besides its own fold-overs and the patterns before it.
  AvoidanceInputs fixed;
  fixed.polygons = existing.polygons;
  fixed.lines = existing.lines;
  fixed.line_widths = existing.line_widths;
  fixed.junction_discs = ribbons.synthesis_junction_discs;
  fixed.include_foldovers = false;

  Backends backends;
  std::int64_t total = 0;
  for (const ClassPlan& plan : plans)
    for (const Ribbon& r : ribbons.ribbons[plan.class_index]) total += r.pieces.empty() ? 0 : 1;
  Progress progress("synthesis", total, "feature");
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
  for (const ClassPlan& plan : plans) {
    const FeatureClassConfig& feature_class = config.features[plan.class_index];
    const SynthesisConfig& synthesis = *feature_class.synthesis;
    for (std::size_t f = 0; f < lines[plan.class_index].size(); ++f) {
      const LineFeature& line = lines[plan.class_index][f];
      if (ribbons.ribbons[plan.class_index][f].pieces.empty()) continue;
      const std::string label = pattern_label(feature_class, line.fid);
      logger().info("synthesis: feature {} of {}: {}", ++feature_number, feature_count, label);
      FeaturePattern pattern;
      const Curve curve{line.points, line.closed};
      const double width = synthesis.width.value_or(line.width);
      pattern.ribbon = synthesis.width ? make_ribbon(curve, {width, *synthesis.delta, 0.0})
                                       : ribbons.ribbons[plan.class_index][f];
      pattern.class_index = plan.class_index;
      pattern.feature_index = f;
      pattern.on_ground = line.structure == Structure::ground;
      FeatureSynthesisReport& report = pattern.report;
      report.seed = feature_seed(config.seed, synthesis.seed, line.fid);

      // Avoidance on the feature's canvas (a halo of a cell beyond the pieces), on the tiles
      // the synthesis reads.
      auto started = std::chrono::steady_clock::now();
      pattern.canvas = synthesis_canvas(pattern.ribbon, cell, cell, label);
      const GridSpec& canvas = pattern.canvas;
      pattern.name = fmt::format("{}_{}", feature_class.name, line.fid);
      if (const int part = parts[pattern.name]++; part > 0)
        pattern.name += fmt::format("_{}", part);
      const SynthesisKey key =
          cache.key(config, feature_class, line, report.seed, canvas, fixed, earlier_keys);
      pattern.key = key.combined();
      earlier_keys.push_back({canvas, pattern.key});
      if (std::optional<CachedSynthesis> cached = cache.find(
              "features." + feature_class.name, line.fid, pattern.name, key, pattern.cache)) {
        if (cached->start)
          pattern.ribbon = make_ribbon(*cached->start, {width, *synthesis.delta, 0.0});
        pattern.synthesis = std::move(cached->synthesis);
        pattern.exemplar_index = plan.exemplars.at(cached->exemplar_slot);
        pattern.opaque = std::move(cached->opaque);
        pattern.report = std::move(cached->report);
        logger().info("{}: reused from the cache ({})", label, pattern.cache.key);
        run.patterns.push_back(std::move(pattern));
        continue;
      }
      auto forbidden_on = [&](const std::vector<TileIndex>& tiles) {
        SparseRaster<std::uint8_t> forbidden(canvas.width, canvas.height, 0, options.canvas_tile);
        add_tiles(forbidden, tiles);
        burn_avoidance(fixed, canvas, forbidden);
        for (const FeaturePattern& earlier : run.patterns) {
          if (overlaps(earlier.canvas, canvas)) {
            add_on_lattice(earlier.opaque, earlier.canvas, forbidden, canvas);
          }
        }
        return forbidden;
      };
      std::vector<TileIndex> tiles = canvas_tiles(pattern.ribbon, canvas, options.canvas_tile);
      SparseRaster<std::uint8_t> forbidden = forbidden_on(tiles);
      std::optional<Curve> start;
      if (curve.closed) {
        start = start_in_the_clear(curve, pattern.ribbon, canvas, forbidden);
        pattern.ribbon = make_ribbon(*start, {width, *synthesis.delta, 0.0});
        // The rotated ribbon's pieces differ: it may read a tile more.
        std::vector<TileIndex> more = canvas_tiles(pattern.ribbon, canvas, options.canvas_tile);
        more.erase(std::remove_if(more.begin(), more.end(),
                                  [&](TileIndex t) { return forbidden.has_tile(t); }),
                   more.end());
        if (!more.empty()) {
          tiles.insert(tiles.end(), more.begin(), more.end());
          forbidden = forbidden_on(tiles);
        }
      }
      const Ribbon& ribbon = pattern.ribbon;
      add_foldovers(ribbon, canvas, forbidden);
      report.avoidance_seconds = seconds_since(started);

      // Synthesis: by seed one exemplar, or every exemplar and the lowest Omega / N.
      started = std::chrono::steady_clock::now();
      SynthParams params;
      params.scale = synthesis.scale;
      params.seed = report.seed;
      params.stitch = synthesis.stitch;
      params.backend = plan.backend;
      params.allow_empty_pieces = synthesis.empty_pieces;
      params.min_coverage = synthesis.min_coverage.value_or(-1.0);  // < 0: from the exemplar
      params.objective = synthesis.objective;
      params.coverage_weight = synthesis.coverage_weight;
      params.feature_label = label;
      std::vector<std::size_t> candidates = plan.exemplars;
      if (synthesis.choice == ExemplarChoice::by_seed) {
        candidates = {plan.exemplars[report.seed % plan.exemplars.size()]};
      }
      bool have = false;
      for (const std::size_t e : candidates) {
        Synthesis result = synthesize_on(backends.get(plan.backend), run.exemplars[e], ribbon,
                                         canvas, &forbidden, params);
        if (!have || result.mean_seam_cost < pattern.synthesis.mean_seam_cost) {
          pattern.synthesis = std::move(result);
          pattern.exemplar_index = e;
          have = true;
        }
      }
      const Exemplar& exemplar = run.exemplars[pattern.exemplar_index];
      const Synthesis& result = pattern.synthesis;
      const auto empty = std::count_if(result.placements.begin(), result.placements.end(),
                                       [](const Placement& p) { return p.empty; });
      if (std::size_t(empty) == result.placements.size()) {
        const Piece& first = ribbon.pieces.front();
        fail(
            "{}: no room for the pattern: none of the {} pieces has a valid position in {} "
            "(piece 0 at ({:.2f}, {:.2f}); the avoidance map blocks them all)",
            label, ribbon.pieces.size(), exemplar.path, first.top_left.x, first.top_left.y);
      }
      report.synthesis_seconds = seconds_since(started);

      // The check: opaque pattern pixels on forbidden canvas pixels, by the synthesizer's own
      // criterion; then the opaque coverage that later features avoid.
      started = std::chrono::steady_clock::now();
      PatternCheck check =
          check_pattern(exemplar, ribbon, result, canvas, forbidden, synthesis.stitch);
      pattern.opaque = std::move(check.opaque);
      report.violations = check.violations;
      if (report.violations != 0) {
        fail("{}: the pattern puts {} opaque pixels on forbidden ones (a synthesis bug)", label,
             report.violations);
      }
      report.render_seconds = seconds_since(started);

      double valid = 0.0;
      for (const int v : result.valid_counts) valid += v;
      report.mean_valid_positions =
          result.valid_counts.empty() ? 0.0 : valid / double(result.valid_counts.size());
      report.exemplar = exemplar.path;
      report.backend = result.backend;
      report.omega = result.total_cost;
      report.mean_seam_cost = result.mean_seam_cost;
      report.mean_seam_cost_stitched = result.mean_seam_cost_stitched;
      report.objective = result.objective;
      report.min_coverage = result.min_coverage;
      report.min_coverage_from_exemplar = result.min_coverage_from_exemplar;
      report.coverage_ratio = result.coverage_ratio;
      report.mean_coverage = result.mean_coverage;
      report.natural_coverage = result.natural_coverage;
      report.parametric_seam_cost =
          parametric_baseline(exemplar, ribbon, synthesis.scale).mean_seam_cost;
      report.empty_pieces = int(empty);
      report.canvas_width = canvas.width;
      report.canvas_height = canvas.height;
      logger().info(
          "{}: {} pieces, {:.0f} valid positions per piece, Omega {}, {:.2f} per seam ({:.2f} "
          "stitched), {} empty, {} violations, canvas {}x{} ({} tiles, {:.1f} MB), {:.2f} s",
          label, ribbon.pieces.size(), report.mean_valid_positions, report.omega,
          report.mean_seam_cost, report.mean_seam_cost_stitched, empty, report.violations,
          canvas.width, canvas.height, forbidden.tile_count(),
          double(forbidden.allocated_bytes()) / 1e6,
          report.avoidance_seconds + report.synthesis_seconds + report.render_seconds);
      const std::size_t slot = std::size_t(
          std::find(plan.exemplars.begin(), plan.exemplars.end(), pattern.exemplar_index) -
          plan.exemplars.begin());
      cache.store(pattern.name, key, pattern.synthesis, slot, start ? &*start : nullptr,
                  pattern.opaque, report);
      run.patterns.push_back(std::move(pattern));
      progress.advance();
    }
  }
  return run;
}

}  // namespace tw::detail
