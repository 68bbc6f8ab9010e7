// Whole DPs on both backends: for a set of curves (straight, arc, S-curve, closed circle,
// hairpin with fold-over) the OpenCL backend must find the same optimal cost and the same
// placements, bit for bit, as the CPU reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ribbon/ribbon.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/dp.hpp"
#include "synth/detail/foldover.hpp"
#include "synth/detail/footprint.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "test_opencl_fixtures.hpp"

namespace tw::test {
namespace {

constexpr double kWidth = 6.0;  // b, metres
constexpr double kDelta = 1.5;  // metres
constexpr double kScale = 5.0;  // texels per metre: C = 30

void arc(std::vector<Vec2>& points, Vec2 centre, double radius, double from, double to, int steps) {
  for (int i = 0; i <= steps; ++i) {
    const double a = from + (to - from) * i / steps;
    points.push_back({centre.x + radius * std::cos(a), centre.y + radius * std::sin(a)});
  }
}

Curve straight() {
  Curve c;
  for (int i = 0; i <= 40; ++i) c.points.push_back({double(i), 0.0});
  return c;
}

Curve circular_arc() {
  Curve c;
  arc(c.points, {0, 0}, 20.0, 0.0, 100.0 * std::numbers::pi / 180.0, 60);
  return c;
}

Curve s_curve() {
  Curve c;
  const double pi = std::numbers::pi;
  arc(c.points, {0, 0}, 12.0, -pi / 2, 0.0, 30);
  std::vector<Vec2> second;
  arc(second, {24, 0}, 12.0, pi, pi / 2, 30);
  c.points.insert(c.points.end(), second.begin() + 1, second.end());
  return c;
}

Curve closed_circle() {
  Curve c;
  arc(c.points, {0, 0}, 6.0, 0.0, 2 * std::numbers::pi, 40);
  c.points.pop_back();  // no repeat of the first point on a closed curve
  c.closed = true;
  return c;
}

// A U-turn of radius 2 m with a 6 m ribbon: the inner side folds over itself.
Curve hairpin() {
  Curve c;
  for (int i = 0; i <= 15; ++i) c.points.push_back({double(i), 0.0});
  arc(c.points, {15, 2}, 2.0, -std::numbers::pi / 2 + 0.2, std::numbers::pi / 2, 12);
  for (int i = 15; i >= 0; --i) c.points.push_back({double(i), 4.0});
  return c;
}

GridSpec canvas_around(const Curve& curve) {
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  for (const Vec2& p : curve.points) {
    min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
  }
  const double margin = 10.0, pixel = 0.5;
  GridSpec grid;
  grid.origin_x = min_x - margin;
  grid.origin_y = max_y + margin;
  grid.pixel_width = grid.pixel_height = pixel;
  grid.width = int(std::ceil((max_x - min_x + 2 * margin) / pixel));
  grid.height = int(std::ceil((max_y - min_y + 2 * margin) / pixel));
  return grid;
}

detail::DpInput dp_input(const Curve& curve, const detail::CostTexels& texels) {
  const Ribbon ribbon = make_ribbon(curve, {kWidth, kDelta});
  const GridSpec canvas = canvas_around(curve);
  const SparseRaster<std::uint8_t> avoid = detail::combined_avoidance(ribbon, canvas, nullptr);
  detail::DpInput input;
  input.texels = &texels;
  const int column = detail::column_count(kWidth, kScale);
  input.space = {texels.width, texels.height, column};
  for (const Piece& piece : ribbon.pieces)
    input.pieces.push_back(detail::make_piece_footprint(piece, kScale, column, canvas, &avoid));
  input.closed = ribbon.closed;
  input.allow_empty = true;  // fold-over pieces may have no valid position on either backend
  return input;
}

class OpenCLFullDp : public testing::TestWithParam<int> {};

TEST_P(OpenCLFullDp, SameOptimumAndPlacementsAsCpu) {
  TW_REQUIRE_OPENCL(context);
  const Curve curves[] = {straight(), circular_arc(), s_curve(), closed_circle(), hairpin()};
  const Curve& curve = curves[GetParam()];
  // The closed circle may need the exact cycle mode (one DP per start): a narrower exemplar
  // keeps it fast.
  const detail::CostTexels texels = chain_texels(curve.closed ? 40 : 100, 32, 17);
  const detail::DpInput input = dp_input(curve, texels);
  ASSERT_GE(input.pieces.size(), 10u);

  auto cpu = detail::make_cpu_backend();
  auto opencl = detail::make_opencl_backend(*context);
  const detail::DpResult expected = detail::run_dp(*cpu, input);
  const detail::DpResult actual = detail::run_dp(*opencl, input);

  EXPECT_EQ(actual.valid_counts, expected.valid_counts);
  EXPECT_EQ(actual.total_cost, expected.total_cost);
  EXPECT_EQ(actual.positions, expected.positions);
  EXPECT_EQ(actual.approximate_cycle_cost, expected.approximate_cycle_cost);
  EXPECT_EQ(actual.exact_dp_passes, expected.exact_dp_passes);
  // The pieces are mostly filled, and the reported optimum is the cost of the placements.
  const auto empty = std::count(actual.positions.begin(), actual.positions.end(), -1);
  EXPECT_LT(empty, std::ptrdiff_t(actual.positions.size() / 4));
  if (empty == 0) {
    EXPECT_EQ(actual.total_cost, detail::sequence_cost(texels, input.space, input.pieces,
                                                       actual.positions, input.closed));
  }
  if (!input.closed) return;
  // The exact cycle search: its remaining-cost bounds run the row update with the edges
  // swapped, on each backend.
  detail::DpInput exact = input;
  exact.exact_cycle = true;
  const detail::DpResult cpu_exact = detail::run_dp(*cpu, exact);
  const detail::DpResult opencl_exact = detail::run_dp(*opencl, exact);
  EXPECT_EQ(opencl_exact.total_cost, cpu_exact.total_cost);
  EXPECT_EQ(opencl_exact.positions, cpu_exact.positions);
  EXPECT_EQ(opencl_exact.exact_dp_passes, cpu_exact.exact_dp_passes);
  EXPECT_GT(cpu_exact.exact_dp_passes, 1);
  std::printf("exact cycle %lld in %d passes, approximation %lld\n",
              (long long)cpu_exact.total_cost, cpu_exact.exact_dp_passes,
              (long long)expected.approximate_cycle_cost);
}

std::string curve_name(const testing::TestParamInfo<int>& info) {
  static const char* const names[] = {"Straight", "Arc", "SCurve", "ClosedCircle",
                                      "HairpinFoldOver"};
  return names[info.param];
}

INSTANTIATE_TEST_SUITE_P(Curves, OpenCLFullDp, testing::Range(0, 5), curve_name);

}  // namespace
}  // namespace tw::test
