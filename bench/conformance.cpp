// Conformance on a coarse real river over a real DEM (issue #8): the WDBII Moselle centreline
// over Luxembourg's 30" DEM (pipelines/luxembourg.yaml, samples/README.md). Prints, for the
// river cells the terrain stage lowers, the largest and median lowering and the deepest
// centreline cut: as before conformance (the line as drawn, no bound on the carve), with the
// max_carve bound only (the old default of 5 x depth and today's 2 x depth), and with the line
// conformed within a corridor as well; and the share of the river's length whose bed lies more
// than 2 x depth below the valley floor around it (issue #21 item 6, terrain/trench.hpp).
// Usage: bench_conformance [--resolution METRES] [corridor metres ...] (default 1000 2000
// 4000; resolution: the pipeline's 50). Never fails on time.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/conformance.hpp"
#include "pipeline/detail/ingest.hpp"
#include "pipeline/detail/stage_options.hpp"
#include "pipeline/detail/stages.hpp"
#include "terrain/height_ops.hpp"
#include "terrain/trench.hpp"

namespace {

using namespace tw;

struct Lowering {
  double largest = 0.0, median = 0.0, deepest_cut = 0.0;
  std::size_t cells = 0;
  double moved_max = 0.0, moved_mean = 0.0, seconds = 0.0;
  // Issue #21 item 6: the share of the river's length whose bed lies more than 2 x depth below
  // the valley floor around it (the lowest terrain within its bed and banks), and the deepest.
  double trench_share = 0.0, deepest_trench = 0.0;
  std::size_t warnings = 0;
};

// One terrain stage over the river class only, the way run_pipeline does it.
Lowering measure(PipelineConfig config, std::optional<double> max_carve, double corridor) {
  const auto t0 = std::chrono::steady_clock::now();
  std::erase_if(config.features, [](const auto& c) { return c.kind != FeatureKind::river; });
  for (auto& c : config.features) {
    c.river.max_carve = max_carve;
    c.conform_corridor = corridor;
  }
  Warnings warnings;
  const Heightfield heightfield =
      detail::load_heightfield(detail::heightfield_input(config), warnings);
  std::vector<std::vector<LineFeature>> lines;
  for (const auto& c : config.features)
    lines.push_back(detail::load_feature_class(c, heightfield, warnings));
  const detail::TerrainOptions terrain = detail::terrain_options(config);
  const auto moves =
      detail::conform_lines(terrain, *in_memory_heightfield(heightfield), lines, warnings);
  const auto features = detail::terrain_features(terrain, lines);
  const TerrainPlan plan =
      plan_terrain(heightfield.height, heightfield.grid, features, detail::terrain_params(terrain));
  Raster<float> after = heightfield.height;
  apply_terrain(after, heightfield.grid, Window::whole(heightfield.grid), plan);

  Lowering out;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> lowered;
  for (std::size_t i = 0; i < after.pixels.size(); ++i) {
    const double d = double(heightfield.height.pixels[i]) - after.pixels[i];
    if (d > 0.01) lowered.push_back(d);  // a centimetre: the cells the river carves
  }
  std::sort(lowered.begin(), lowered.end());
  out.cells = lowered.size();
  if (!lowered.empty()) {
    out.largest = lowered.back();
    out.median = lowered[lowered.size() / 2];
  }
  for (const auto& e : plan.earthwork) out.deepest_cut = std::max(out.deepest_cut, e.max_cut);
  double length = 0.0, deeper = 0.0;
  for (const TerrainFeature& f : plan.features) {
    if (f.kind != FeatureKind::river) continue;
    const TrenchProfile t =
        trench_below_valley_floor(heightfield.height, after, heightfield.grid, f.centerline,
                                  0.5 * f.width + f.river.bank_width, 2.0 * f.river.depth);
    length += t.length;
    deeper += t.deeper_length;
    out.deepest_trench = std::max(out.deepest_trench, t.deepest);
  }
  out.trench_share = length > 0.0 ? deeper / length : 0.0;
  for (const auto& m : moves)
    for (const auto& f : m) {
      out.moved_max = std::max(out.moved_max, f.max_m);
      out.moved_mean = std::max(out.moved_mean, f.mean_m);
    }
  out.warnings = warnings.size();
  return out;
}

void print(const char* label, const Lowering& l) {
  std::printf("%-34s %9.1f %9.1f %9.1f %7zu %9.0f %9.0f %7.1f%% %8.1f %6zu %7.3f\n", label,
              l.largest, l.median, l.deepest_cut, l.cells, l.moved_max, l.moved_mean,
              100.0 * l.trench_share, l.deepest_trench, l.warnings, l.seconds);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> corridors;
  std::vector<Override> overrides;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--resolution" && i + 1 < argc) {
      overrides.push_back({"resolution", argv[++i]});
    } else {
      corridors.push_back(std::atof(argv[i]));
    }
  }
  if (corridors.empty()) corridors = {1000.0, 2000.0, 4000.0};
  const PipelineConfig config =
      load_pipeline(std::string(TERRAWEAVE_SOURCE_DIR) + "/pipelines/luxembourg.yaml", overrides);
  const double depth = config.features.front().river.depth;
  std::printf("Moselle (WDBII) over Luxembourg 30\" DEM, %g m output cells, depth %g m\n",
              config.resolution.value_or(0.0), depth);
  std::printf("%-34s %9s %9s %9s %7s %9s %9s %8s %8s %6s %7s\n", "", "largest", "median", "bed cut",
              "cells", "moved max", "max mean", ">2depth", "trench", "warns", "s");
  print("as drawn, unbounded (before)", measure(config, 1e12, 0.0));
  print("as drawn, max_carve 5 x depth (old)", measure(config, 5.0 * depth, 0.0));
  print("as drawn, max_carve default", measure(config, std::nullopt, 0.0));
  for (const double c : corridors) {
    char label[64];
    std::snprintf(label, sizeof label, "conformed %g m, unbounded", c);
    print(label, measure(config, 1e12, c));
    std::snprintf(label, sizeof label, "conformed %g m, max_carve default", c);
    print(label, measure(config, std::nullopt, c));
  }
  return 0;
}
