#include "pipeline/detail/patterns.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>

#include "core/error.hpp"
#include "core/grid_limits.hpp"
#include "core/log.hpp"
#include "raster/foldover.hpp"
#include "raster/rasterize.hpp"
#include "synth/detail/backend_factory.hpp"
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

// Copies the 1s of `source` (on its canvas) onto `target` (on `target_grid`); both canvases lie
// on the same world lattice, so the offset between them is a whole number of cells.
void add_on_lattice(const Raster<std::uint8_t>& source, const GridSpec& source_grid,
                    Raster<std::uint8_t>& target, const GridSpec& target_grid) {
  const int dc =
      int(std::lround((source_grid.origin_x - target_grid.origin_x) / target_grid.pixel_width));
  const int dr =
      int(std::lround((target_grid.origin_y - source_grid.origin_y) / target_grid.pixel_height));
  const int row0 = std::max(0, -dr), row1 = std::min(source.height, target.height - dr);
  const int col0 = std::max(0, -dc), col1 = std::min(source.width, target.width - dc);
  for (int row = row0; row < row1; ++row) {
    for (int col = col0; col < col1; ++col) {
      if (source.at(col, row)) target.at(col + dc, row + dr) = 1;
    }
  }
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

// Renders the pattern on its canvas tile by tile (memory bounded by a tile, whatever the
// feature's length), skipping tiles far from every piece; counts opaque pixels on forbidden
// ones with the synthesizer's criterion and marks every covered pixel in `opaque`.
std::int64_t check_and_mark_opaque(const Exemplar& exemplar, const Ribbon& ribbon,
                                   const Synthesis& synthesis, const GridSpec& canvas,
                                   const Raster<std::uint8_t>& forbidden, bool stitch,
                                   Raster<std::uint8_t>& opaque) {
  constexpr int kTile = 512;
  const int tiles_x = (canvas.width + kTile - 1) / kTile;
  const int tiles_y = (canvas.height + kTile - 1) / kTile;
  std::vector<std::uint8_t> touched(std::size_t(tiles_x) * tiles_y, 0);
  for (const Piece& piece : ribbon.pieces) {
    Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
    for (const Vec2 c : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right}) {
      const Vec2 p = canvas.world_to_pixel(c);
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
    }
    const int tx0 = std::clamp(int(std::floor(lo.x - 1)) / kTile, 0, tiles_x - 1);
    const int tx1 = std::clamp(int(std::floor(hi.x + 1)) / kTile, 0, tiles_x - 1);
    const int ty0 = std::clamp(int(std::floor(lo.y - 1)) / kTile, 0, tiles_y - 1);
    const int ty1 = std::clamp(int(std::floor(hi.y + 1)) / kTile, 0, tiles_y - 1);
    for (int ty = ty0; ty <= ty1; ++ty) {
      for (int tx = tx0; tx <= tx1; ++tx) touched[std::size_t(ty) * tiles_x + tx] = 1;
    }
  }
  std::int64_t violations = 0;
  for (int ty = 0; ty < tiles_y; ++ty) {
    for (int tx = 0; tx < tiles_x; ++tx) {
      if (!touched[std::size_t(ty) * tiles_x + tx]) continue;
      const Window window{tx * kTile, ty * kTile, std::min(kTile, canvas.width - tx * kTile),
                          std::min(kTile, canvas.height - ty * kTile)};
      const RenderedPattern rendered =
          render_pattern(exemplar, ribbon, synthesis, canvas, window, stitch);
      for (int row = 0; row < window.height; ++row) {
        for (int col = 0; col < window.width; ++col) {
          if (rendered.coverage.at(col, row) > 0.0f) {
            opaque.at(window.col0 + col, window.row0 + row) = 1;
          }
        }
      }
      violations += count_avoidance_violations(rendered, forbidden);
    }
  }
  return violations;
}

// A closed curve starting at its first piece whose corners all lie on free canvas cells: the
// synthesizer's closed mode needs piece 0 to have a valid position, and a ring often starts
// where it meets another road (a junction disc). Unchanged when no piece is clear.
Curve start_in_the_clear(const Curve& curve, const Ribbon& ribbon, const GridSpec& canvas,
                         const Raster<std::uint8_t>& forbidden) {
  auto free_at = [&](Vec2 world) {
    const Vec2 p = canvas.world_to_pixel(world);
    const int col = int(std::floor(p.x)), row = int(std::floor(p.y));
    return !forbidden.inside(col, row) || !forbidden.at(col, row);
  };
  for (std::size_t k = 0; k < ribbon.pieces.size(); ++k) {
    const Piece& piece = ribbon.pieces[k];
    const Vec2 centre =
        0.25 * (piece.top_left + piece.bottom_left + piece.bottom_right + piece.top_right);
    if (!(free_at(piece.top_left) && free_at(piece.bottom_left) && free_at(piece.bottom_right) &&
          free_at(piece.top_right) && free_at(centre))) {
      continue;
    }
    if (k == 0) return curve;
    const std::vector<double> cumulative = cumulative_lengths(curve);
    const double start = double(k) * ribbon.delta;
    Curve rotated;
    rotated.closed = true;
    rotated.points.push_back(point_at(curve, cumulative, start));
    const std::size_t n = curve.points.size();
    std::size_t first = 0;
    while (first < n && cumulative[first] <= start) ++first;
    for (std::size_t i = 0; i < n; ++i) rotated.points.push_back(curve.points[(first + i) % n]);
    return without_duplicates(rotated);
  }
  return curve;
}

}  // namespace

std::uint64_t feature_seed(std::uint64_t run_seed, std::uint64_t class_seed, std::int64_t fid) {
  std::uint64_t h = splitmix64(run_seed);
  h = splitmix64(h ^ class_seed);
  h = splitmix64(h ^ std::uint64_t(fid));
  return h == 0 ? 1 : h;
}

GridSpec synthesis_canvas(const Ribbon& ribbon, double resolution, double halo_m,
                          const std::string& label) {
  Vec2 lo{1e300, 1e300}, hi{-1e300, -1e300};
  for (const Piece& piece : ribbon.pieces) {
    for (const Vec2 c : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right}) {
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
    }
  }
  const double x0 = std::floor((lo.x - halo_m) / resolution) * resolution;
  const double y1 = std::ceil((hi.y + halo_m) / resolution) * resolution;
  GridSpec grid;
  grid.pixel_width = grid.pixel_height = resolution;
  grid.origin_x = x0;
  grid.origin_y = y1;
  const double columns = std::ceil((hi.x + halo_m - x0) / resolution);
  const double rows = std::ceil((y1 - (lo.y - halo_m)) / resolution);
  require_grid_size(columns, rows,
                    fmt::format("{}: a synthesis canvas of {} m cells", label, resolution));
  grid.width = int(columns);
  grid.height = int(rows);
  return grid;
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

  Backends backends;
  const double cell = config.synthesis_resolution;
  for (const ClassPlan& plan : plans) {
    const FeatureClassConfig& feature_class = config.features[plan.class_index];
    const SynthesisConfig& synthesis = *feature_class.synthesis;
    for (std::size_t f = 0; f < lines[plan.class_index].size(); ++f) {
      const LineFeature& line = lines[plan.class_index][f];
      if (ribbons.ribbons[plan.class_index][f].pieces.empty()) continue;
      const std::string label = pattern_label(feature_class, line.fid);
      FeaturePattern pattern;
      const Curve curve{line.points, line.closed};
      const double width = synthesis.width.value_or(line.width);
      pattern.ribbon = synthesis.width ? make_ribbon(curve, {width, synthesis.delta, 0.0})
                                       : ribbons.ribbons[plan.class_index][f];
      pattern.class_index = plan.class_index;
      pattern.feature_index = f;
      FeatureSynthesisReport& report = pattern.report;
      report.seed = feature_seed(config.seed, synthesis.seed, line.fid);

      // Avoidance on the feature's canvas: a halo of a cell beyond the pieces.
      auto started = std::chrono::steady_clock::now();
      pattern.canvas = synthesis_canvas(pattern.ribbon, cell, cell, label);
      const GridSpec& canvas = pattern.canvas;
      const Window whole = Window::whole(canvas);
      Raster<std::uint8_t> forbidden(canvas.width, canvas.height, 0);
      burn_polygons(existing.polygons, canvas, whole, forbidden, 1);
      burn_buffered_lines(existing.lines, existing.line_widths, canvas, whole, forbidden, 1);
      burn_polygons(ribbons.synthesis_junction_discs, canvas, whole, forbidden, 1);
      for (const FeaturePattern& earlier : run.patterns) {
        if (overlaps(earlier.canvas, canvas)) {
          add_on_lattice(earlier.opaque, earlier.canvas, forbidden, canvas);
        }
      }
      if (curve.closed) {
        pattern.ribbon = make_ribbon(start_in_the_clear(curve, pattern.ribbon, canvas, forbidden),
                                     {width, synthesis.delta, 0.0});
      }
      const Ribbon& ribbon = pattern.ribbon;
      const Raster<std::uint8_t> folds = foldover_mask(ribbon, canvas, whole);
      for (std::size_t i = 0; i < folds.pixels.size(); ++i) forbidden.pixels[i] |= folds.pixels[i];
      report.avoidance_seconds = seconds_since(started);

      // Synthesis: by seed one exemplar, or every exemplar and the lowest Omega / N.
      started = std::chrono::steady_clock::now();
      SynthParams params;
      params.scale = synthesis.scale;
      params.seed = report.seed;
      params.stitch = synthesis.stitch;
      params.backend = plan.backend;
      params.allow_empty_pieces = synthesis.empty_pieces;
      params.min_coverage = synthesis.min_coverage;
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
      pattern.opaque = Raster<std::uint8_t>(canvas.width, canvas.height, 0);
      report.violations = check_and_mark_opaque(exemplar, ribbon, result, canvas, forbidden,
                                                synthesis.stitch, pattern.opaque);
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
      report.empty_pieces = int(empty);
      report.canvas_width = canvas.width;
      report.canvas_height = canvas.height;
      logger().info(
          "{}: {} pieces, {:.0f} valid positions per piece, Omega {}, {:.2f} per seam ({:.2f} "
          "stitched), {} empty, {} violations, canvas {}x{}, {:.2f} s",
          label, ribbon.pieces.size(), report.mean_valid_positions, report.omega,
          report.mean_seam_cost, report.mean_seam_cost_stitched, empty, report.violations,
          canvas.width, canvas.height,
          report.avoidance_seconds + report.synthesis_seconds + report.render_seconds);
      run.patterns.push_back(std::move(pattern));
    }
  }
  return run;
}

namespace {

std::vector<ChannelMapping> mappings_of(const FeatureClassConfig& c, const Exemplar& exemplar) {
  if (!c.synthesis->channels.empty()) return c.synthesis->channels;
  std::vector<ChannelMapping> mappings = {{"A", "splat." + c.name + "_pattern"}};
  if (exemplar.channel_index("height") >= 0) mappings.push_back({"height", "height"});
  return mappings;
}

}  // namespace

void apply_patterns(const PatternRun& run, const PipelineConfig& config, const GridSpec& grid,
                    Raster<float>& height, SplatLayers& splat) {
  for (const FeaturePattern& pattern : run.patterns) {
    const FeatureClassConfig& c = config.features[pattern.class_index];
    const Ribbon& ribbon = pattern.ribbon;
    const Exemplar& exemplar = run.exemplars[pattern.exemplar_index];
    const Window window = ribbon_window(ribbon, grid);
    if (window.width == 0) continue;
    const RenderedPattern rendered =
        render_pattern(exemplar, ribbon, pattern.synthesis, grid, window, c.synthesis->stitch,
                       c.synthesis->feather);
    for (const ChannelMapping& m : mappings_of(c, exemplar)) {
      const int channel = exemplar.channel_index(m.channel);
      if (channel < 0) {
        fail("features.{}.synthesis.channels.{}: exemplar {} has no channel '{}' (it has {})",
             c.name, m.channel, exemplar.path, m.channel, fmt::join(exemplar.channel_names, ", "));
      }
      const Raster<float>& values = rendered.channels[channel];
      if (m.target == "height") {
        const float factor = float(c.synthesis->height_detail);
        for (int row = 0; row < window.height; ++row) {
          for (int col = 0; col < window.width; ++col) {
            const float coverage = rendered.coverage.at(col, row);
            float& h = height.at(window.col0 + col, window.row0 + row);
            if (coverage > 0.0f && !std::isnan(h)) h += factor * values.at(col, row) * coverage;
          }
        }
        continue;
      }
      const std::string material = m.target.substr(6);  // after "splat."
      auto it = std::find(splat.materials.begin(), splat.materials.end(), material);
      if (it == splat.materials.end()) {
        splat.materials.push_back(material);
        splat.weights.emplace_back(grid.width, grid.height, 0.0f);
        it = splat.materials.end() - 1;
      }
      const std::size_t target = std::size_t(it - splat.materials.begin());
      const bool is_alpha = m.channel == "A";
      for (int row = 0; row < window.height; ++row) {
        for (int col = 0; col < window.width; ++col) {
          const float coverage = rendered.coverage.at(col, row);
          if (!(coverage > 0.0f)) continue;
          const float share =
              std::clamp(is_alpha ? coverage : coverage * values.at(col, row), 0.0f, 1.0f);
          const int x = window.col0 + col, y = window.row0 + row;
          for (auto& band : splat.weights) band.at(x, y) *= 1.0f - share;
          splat.weights[target].at(x, y) += share;
        }
      }
    }
  }
}

}  // namespace tw::detail
