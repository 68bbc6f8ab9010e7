// Default quality (issue #11): every exemplar of samples/exemplars along the built-in S-curve,
// hairpin and circle with default parameters (width, δ and coverage floor from the exemplar,
// the pattern objective): no failed run, mean window coverage >= 0.8 of the exemplar's natural
// coverage, seams (as rendered, stitched) cheaper than parametric texture mapping's on the same
// ribbon.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <memory>

#include "synth/baseline.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/exemplar_stats.hpp"
#include "synth/shapes.hpp"
#include "synth/synthesize.hpp"
#include "synth_fixtures.hpp"
#include "test_support.hpp"

namespace tw {
namespace {

// Built-in curves at the ribbon's scale: the S-curve's arcs have radius 1 width, the circle's 2,
// the hairpin's legs lie 1.2 widths apart (closer, the legs would overlap whole).
double shape_length(const std::string& shape, double width) {
  return shape == "hairpin" ? 10.0 * width : 4.0 * width;
}

using Case = std::tuple<std::string, std::string>;  // exemplar file name, shape

std::vector<std::string> exemplar_files() {
  std::vector<std::string> names;
  for (const auto& entry :
       std::filesystem::directory_iterator(test::source_dir() / "samples/exemplars"))
    if (entry.path().extension() == ".png") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// The tests read the first kColumns columns of each exemplar so that 36 syntheses take seconds on
// 2 cores; bench_quality measures the whole exemplars (docs/synthesis.md, "Default quality").
constexpr int kColumns = 112;

Exemplar first_columns(const Exemplar& e, int columns) {
  if (e.width <= columns) return e;
  const std::size_t n = e.channel_names.size();
  std::vector<float> texels;
  for (int y = 0; y < e.height; ++y)
    texels.insert(texels.end(), e.texels.begin() + (std::size_t(y) * e.width) * n,
                  e.texels.begin() + (std::size_t(y) * e.width + columns) * n);
  return make_exemplar(columns, e.height, e.channel_names, std::move(texels), e.path,
                       !e.cost.binary_alpha);
}

struct Outcome {
  std::string error;  // empty: the run succeeded
  Synthesis synthesis, baseline;
};

// One synthesis per case (cached: gtest_filter may run several cases in one process).
const Outcome& outcome(const Case& c) {
  static std::map<Case, std::unique_ptr<Outcome>> cache;
  auto& slot = cache[c];
  if (slot) return *slot;
  slot = std::make_unique<Outcome>();
  const auto& [file, shape] = c;
  try {
    const Exemplar exemplar = first_columns(
        load_exemplar((test::source_dir() / "samples/exemplars" / file).string()), kColumns);
    const ExemplarStats stats = exemplar_stats(exemplar);
    constexpr double kScale = 1.0;
    const double width = suggested_width(stats, kScale);
    const Ribbon ribbon = make_ribbon(make_shape(shape, shape_length(shape, width)),
                                      {width, suggested_delta(stats, kScale)});
    const GridSpec canvas = test::canvas_around(ribbon, 1.0, 4.0);
    SynthParams params;  // defaults: pattern objective, floor from the exemplar
    params.scale = kScale;
    auto cpu = detail::make_cpu_backend();
    slot->synthesis = detail::synthesize_on(*cpu, exemplar, ribbon, canvas, nullptr, params);
    slot->baseline = parametric_baseline(exemplar, ribbon, kScale);
    std::printf(
        "%s %s: coverage ratio %.3f, seam %.1f (stitched %.1f), parametric %.1f, %zu pieces\n",
        file.c_str(), shape.c_str(), slot->synthesis.coverage_ratio, slot->synthesis.mean_seam_cost,
        slot->synthesis.mean_seam_cost_stitched, slot->baseline.mean_seam_cost,
        ribbon.pieces.size());
  } catch (const std::exception& e) {
    slot->error = e.what();
  }
  return *slot;
}

class DefaultQuality : public testing::TestWithParam<Case> {};

// The three properties of a case in one test: ctest runs every test in its own process, so
// separate tests would each repeat the synthesis.
TEST_P(DefaultQuality, RunsCoversAndSeamsBelowParametric) {
  const Outcome& o = outcome(GetParam());
  ASSERT_EQ(o.error, "") << "property 1: the run fails";
  EXPECT_GT(o.synthesis.natural_coverage, 0.0);
  EXPECT_GE(o.synthesis.coverage_ratio, 0.8)
      << "property 2: mean window coverage below 0.8 of the natural coverage";
  // The seams as rendered: after stitching (Section 3.2) against the baseline's (it has none).
  EXPECT_LT(o.synthesis.mean_seam_cost_stitched, o.baseline.mean_seam_cost)
      << "property 3: seams cost more than parametric texture mapping's";
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  std::string name = std::get<0>(info.param) + "_" + std::get<1>(info.param);
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

// Every exemplar of samples/exemplars x the three built-in curves.
INSTANTIATE_TEST_SUITE_P(Samples, DefaultQuality,
                         testing::Combine(testing::ValuesIn(exemplar_files()),
                                          testing::Values("s-curve", "hairpin", "circle")),
                         case_name);

}  // namespace
}  // namespace tw
