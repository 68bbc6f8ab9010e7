// synthesize_feature with ExemplarChoice::mix (issue #11 item 4): one DP over the atlas of the
// river-bed samples (cobbles bedded in the sand, and the sand: one band), its exactness against
// each exemplar alone,
// the switching cost's effect on the number of switches, bindings near a junction, and CPU =
// OpenCL on one mixed feature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "core/segment_distance.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/feature_synthesis.hpp"
#include "synth/pattern_canvas.hpp"
#include "synth/placements_io.hpp"
#include "synth/shapes.hpp"
#include "test_opencl_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

const Exemplar& sample(const std::string& name) {
  static std::map<std::string, Exemplar> loaded;
  auto it = loaded.find(name);
  if (it == loaded.end()) {
    const std::string path = (test::source_dir() / "samples/exemplars" / name).string();
    it = loaded.emplace(name, load_exemplar(path)).first;
  }
  return it->second;
}

struct RiverBed {
  const Exemplar& cobbles = sample("cobble_bed_260x80.png");
  const Exemplar& sand = sample("sand_band_260x80.png");
  std::vector<const Exemplar*> both{&cobbles, &sand};
  FeatureSynthesisOptions options;
  RiverBed() {
    options.params.scale = 4.0;
    options.params.seed = 0;  // the global optimum, comparable across runs
    options.params.objective = Objective::paper;
    options.params.min_coverage = 0.3;  // the same floor for the mix and each exemplar alone
    options.params.feature_label = "river";
    // The ribbon holds the bands (rows 16..63), as a pipeline's default width does: a ribbon
    // narrower than an exemplar's band leaves it no position whose top and bottom edges are
    // clear (the rock band's 11 m would leave the sand none).
    double width = 0.0;
    for (const Exemplar* e : both)
      width = std::max(width, suggested_width(exemplar_stats(*e), options.params.scale));
    options.ribbon = {width, 6.0, 0.0};
    options.choice = ExemplarChoice::mix;
  }
  FeatureSynthesisResult run(const Curve& curve, const std::vector<const Exemplar*>& exemplars,
                             const FeatureSynthesisOptions& o) const {
    SynthesisBackends backends;
    const Ribbon ribbon = make_ribbon(curve, o.ribbon);
    const GridSpec canvas = synthesis_canvas(ribbon, 1.0, 1.0, "river");
    return synthesize_feature(backends, exemplars, curve, ribbon, canvas, AvoidanceInputs{}, {}, o);
  }
};

// The atlas holds every position of each exemplar: the mix's optimum can only be lower.
TEST(MixFeature, UnboundMixOmegaIsAtMostEachSingleExemplars) {
  const RiverBed bed;
  const Curve curve = make_shape("s-curve", 30.0);
  const FeatureSynthesisResult mixed = bed.run(curve, bed.both, bed.options);
  EXPECT_EQ(mixed.report.violations, 0);
  ASSERT_TRUE(mixed.synthesis.mix.has_value());
  EXPECT_EQ(mixed.report.mix_exemplars,
            (std::vector<std::string>{bed.cobbles.path, bed.sand.path}));
  FeatureSynthesisOptions single = bed.options;
  single.choice = ExemplarChoice::by_seed;
  for (const Exemplar* e : bed.both) {
    const FeatureSynthesisResult alone = bed.run(curve, {e}, single);
    EXPECT_LE(mixed.synthesis.total_cost, alone.synthesis.total_cost) << e->path;
    std::printf("[ measure  ] %s alone: Omega %lld; mix: Omega %lld, pieces %d + %d, %d switches\n",
                e->path.c_str(), (long long)alone.synthesis.total_cost,
                (long long)mixed.synthesis.total_cost, mixed.report.pieces_per_exemplar[0],
                mixed.report.pieces_per_exemplar[1], mixed.report.exemplar_switches);
  }
}

// (c2 - c1)(s1 - s2) >= 0 for optima under costs c1 < c2: more cost, never more switches; a cost
// above any seam saving leaves one exemplar.
TEST(MixFeature, LargerSwitchCostMeansFewerSwitches) {
  const RiverBed bed;
  const Curve curve = make_shape("s-curve", 120.0);
  int previous = 1 << 30;
  std::vector<int> measured;
  for (const int cost : {0, 16, 100000}) {
    FeatureSynthesisOptions o = bed.options;
    o.params.switch_cost = cost;
    const FeatureSynthesisResult r = bed.run(curve, bed.both, o);
    const int switches = r.report.exemplar_switches;
    EXPECT_LE(switches, previous) << "switch_cost " << cost;
    EXPECT_EQ(r.report.switch_cost, cost);
    previous = switches;
    measured.push_back(switches);
    std::printf("[ measure  ] switch_cost %6d: %d switches, Omega %lld\n", cost, switches,
                (long long)r.synthesis.total_cost);
  }
  EXPECT_GT(measured.front(), 0);  // the free mix does switch on this curve
  EXPECT_EQ(measured.back(), 0);
}

// Pieces whose centre segment passes within near_junction of a junction use the bound
// exemplar; the others only the exemplar no rule names.
TEST(MixFeature, PiecesNearAJunctionUseTheBoundExemplar) {
  RiverBed bed;
  const Curve curve{{{0.0, 0.0}, {90.0, 0.0}}, false};
  bed.options.bindings = {{1, true, 10.0}};
  bed.options.junctions = {{45.0, 0.0}};
  const FeatureSynthesisResult r = bed.run(curve, bed.both, bed.options);
  int near = 0;
  for (std::size_t i = 0; i < r.ribbon.pieces.size(); ++i) {
    const Piece& p = r.ribbon.pieces[i];
    const double d = distance_to_segment({45.0, 0.0}, lerp(p.top_left, p.bottom_left, 0.5),
                                         lerp(p.top_right, p.bottom_right, 0.5));
    const int expected = d <= 10.0 ? 1 : 0;
    near += expected;
    ASSERT_FALSE(r.synthesis.placements[i].empty) << "piece " << i;
    EXPECT_EQ(r.synthesis.placements[i].exemplar, expected) << "piece " << i << " at " << d;
  }
  EXPECT_GE(near, 3);
  EXPECT_EQ(r.report.pieces_per_exemplar,
            (std::vector<int>{int(r.ribbon.pieces.size()) - near, near}));
  EXPECT_EQ(r.report.exemplar_switches, 2);
}

// A mix bound wholly to one exemplar is that exemplar alone under the defaults (the pattern
// objective, the coverage floor derived from the exemplar): each position keeps its own
// exemplar's floor and pays the coverage term of its own band, so the placements (in its
// columns), Omega, the objective and the coverage measures equal those of the single run.
TEST(MixFeature, AMixBoundToOneExemplarIsThatExemplarAlone) {
  RiverBed bed;
  bed.options.params.objective = Objective::pattern;
  bed.options.params.min_coverage = -1.0;
  const Curve curve = make_shape("s-curve", 30.0);
  FeatureSynthesisOptions single = bed.options;
  single.choice = ExemplarChoice::by_seed;
  for (int e = 0; e < 2; ++e) {
    SCOPED_TRACE(bed.both[std::size_t(e)]->path);
    FeatureSynthesisOptions bound = bed.options;
    bound.bindings = {{e, true, 0.0}};  // every piece
    const FeatureSynthesisResult mixed = bed.run(curve, bed.both, bound);
    const FeatureSynthesisResult alone = bed.run(curve, {bed.both[std::size_t(e)]}, single);
    ASSERT_TRUE(mixed.mix.has_value());
    const int x0 = mixed.mix->layout.x0[std::size_t(e)];
    ASSERT_EQ(mixed.synthesis.placements.size(), alone.synthesis.placements.size());
    for (std::size_t i = 0; i < alone.synthesis.placements.size(); ++i) {
      const Placement& m = mixed.synthesis.placements[i];
      const Placement& a = alone.synthesis.placements[i];
      EXPECT_EQ(m.exemplar, e) << "piece " << i;
      EXPECT_EQ(m.ux - x0, a.ux) << "piece " << i;
      EXPECT_EQ(m.uy, a.uy) << "piece " << i;
    }
    EXPECT_EQ(mixed.synthesis.valid_counts, alone.synthesis.valid_counts);
    EXPECT_EQ(mixed.synthesis.total_cost, alone.synthesis.total_cost);
    EXPECT_EQ(mixed.synthesis.objective_cost, alone.synthesis.objective_cost);
    EXPECT_DOUBLE_EQ(mixed.synthesis.mean_coverage, alone.synthesis.mean_coverage);
    EXPECT_DOUBLE_EQ(mixed.synthesis.natural_coverage, alone.synthesis.natural_coverage);
    EXPECT_EQ(mixed.report.exemplar_switches, 0);
    std::printf("[ measure  ] bound to %s: floor %.3f alone, Omega %lld, objective %lld\n",
                bed.both[std::size_t(e)]->path.c_str(), alone.synthesis.min_coverage,
                (long long)alone.synthesis.total_cost, (long long)alone.synthesis.objective_cost);
  }
}

// One mixed feature with a binding and a switching cost: the same placements, bytes and costs
// on the CPU and OpenCL backends.
TEST(MixFeature, CpuAndOpenClAgreeOnAMixedFeature) {
  TW_REQUIRE_OPENCL(context);
  RiverBed bed;
  const Curve curve = make_shape("s-curve", 30.0);
  bed.options.params.switch_cost = 8;
  bed.options.params.stitch = true;
  bed.options.bindings = {{0, true, 6.0}};
  bed.options.junctions = {curve.points[curve.points.size() / 2]};
  bed.options.params.backend = BackendKind::cpu;
  const FeatureSynthesisResult cpu = bed.run(curve, bed.both, bed.options);
  bed.options.params.backend = BackendKind::opencl;
  const FeatureSynthesisResult cl = bed.run(curve, bed.both, bed.options);
  EXPECT_EQ(cl.synthesis.backend.rfind("opencl", 0), 0u) << cl.synthesis.backend;
  EXPECT_EQ(cpu.synthesis.total_cost, cl.synthesis.total_cost);
  EXPECT_EQ(cpu.synthesis.objective_cost, cl.synthesis.objective_cost);
  EXPECT_EQ(cpu.report.pieces_per_exemplar, cl.report.pieces_per_exemplar);
  EXPECT_EQ(cpu.report.exemplar_switches, cl.report.exemplar_switches);
  // The placements file but for the backend's name: the same bytes.
  Synthesis cpu_named = cpu.synthesis, cl_named = cl.synthesis;
  cpu_named.backend = cl_named.backend = "any";
  EXPECT_TRUE(placements_to_json(cpu_named, "mix") == placements_to_json(cl_named, "mix"))
      << "the placements differ between the backends";
  EXPECT_EQ(cpu.opaque.tile_count(), cl.opaque.tile_count());
}

}  // namespace
}  // namespace tw
