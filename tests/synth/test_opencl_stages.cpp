// Every OpenCL kernel against its CPU twin, stage by stage, on random inputs and edge cases:
// both backends must agree bit for bit (DESIGN.md, "Exactness and determinism").
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <memory>

#include "core/error.hpp"
#include "synth/detail/backend_factory.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "test_opencl_fixtures.hpp"
#include "test_support.hpp"

namespace tw::test {
namespace {

using detail::ColumnSet;
using detail::CostTexels;
using detail::PieceFootprint;
using detail::PositionSpace;

struct Backends {
  std::unique_ptr<detail::Backend> cpu = detail::make_cpu_backend();
  std::unique_ptr<detail::Backend> opencl;
};

#define TW_BACKENDS(backends)         \
  TW_REQUIRE_OPENCL(opencl_context_); \
  Backends backends;                  \
  backends.opencl = detail::make_opencl_backend(*opencl_context_)

void expect_same_valid_positions(Backends& b, const CostTexels& texels, const PositionSpace& space,
                                 const PieceFootprint& piece) {
  std::vector<std::uint8_t> cpu_flags, cl_flags;
  b.cpu->find_valid_positions(texels, space, piece, cpu_flags);
  b.opencl->find_valid_positions(texels, space, piece, cl_flags);
  ASSERT_EQ(cpu_flags.size(), std::size_t(space.count()));
  EXPECT_EQ(cl_flags, cpu_flags);
}

TEST(OpenCLFindValidPositions, MatchesCpuOnRandomInputs) {
  TW_BACKENDS(b);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    const int width = uniform(rng, 1, 70), height = uniform(rng, 1, 40);
    const int column = uniform(rng, 1, 60);  // C larger than H on some seeds
    CostTexels texels = random_texels(rng, width, height, uniform(rng, 5, 60));
    SCOPED_TRACE(testing::Message()
                 << "seed " << seed << " W " << width << " H " << height << " C " << column);
    expect_same_valid_positions(b, texels, {width, height, column}, random_piece(rng, column));
  }
}

TEST(OpenCLFindValidPositions, MatchesCpuWithAMinimumOpaqueCount) {
  TW_BACKENDS(b);
  for (unsigned seed = 11; seed <= 18; ++seed) {
    std::mt19937 rng(seed);
    const int width = uniform(rng, 8, 90), height = uniform(rng, 4, 40);
    const int column = uniform(rng, 2, 40);
    CostTexels texels = random_texels(rng, width, height, uniform(rng, 20, 90));
    PieceFootprint piece = random_piece(rng, column);
    piece.min_opaque = uniform(rng, 2, 30);
    SCOPED_TRACE(testing::Message() << "seed " << seed << " min_opaque " << piece.min_opaque);
    expect_same_valid_positions(b, texels, {width, height, column}, piece);
  }
}

TEST(OpenCLFindValidPositions, MatchesCpuOnChainWithSlantedPiece) {
  TW_BACKENDS(b);
  CostTexels texels = chain_texels(120, 40, 3);
  for (int column : {12, 40, 55}) {
    PieceFootprint piece = slanted_piece(column, 4, 200);
    std::vector<std::uint8_t> flags;
    b.opencl->find_valid_positions(texels, {120, 40, column}, piece, flags);
    const auto valid = std::count(flags.begin(), flags.end(), 1);
    // Positions above the exemplar (uy < 0) can be valid: the piece then reaches into it.
    EXPECT_GT(valid, 0) << "C " << column;
    expect_same_valid_positions(b, texels, {120, 40, column}, piece);
  }
}

TEST(OpenCLFindValidPositions, TransparentExemplarHasNoValidPosition) {
  TW_BACKENDS(b);
  CostTexels texels{30, 20, std::vector<std::uint32_t>(600, pack_rgba(200, 10, 10, 127)), true};
  std::vector<std::uint8_t> flags;
  b.opencl->find_valid_positions(texels, {30, 20, 8}, slanted_piece(8, 3, 0), flags);
  EXPECT_EQ(std::count(flags.begin(), flags.end(), 1), 0);
  expect_same_valid_positions(b, texels, {30, 20, 8}, slanted_piece(8, 3, 0));
}

TEST(OpenCLFindValidPositions, SingleOpaqueTexelWithOneTexelPiece) {
  TW_BACKENDS(b);
  CostTexels texels{9, 7, std::vector<std::uint32_t>(63, 0), true};
  texels.rgba[4 * 9 + 5] = pack_rgba(1, 2, 3, 128);
  PieceFootprint piece;
  piece.column = 3;
  piece.right_fx = piece.right_fy = {0, 0, 0};
  piece.interior = {{0, 0}};
  std::vector<std::uint8_t> flags;
  b.opencl->find_valid_positions(texels, {9, 7, 3}, piece, flags);
  ASSERT_EQ(std::count(flags.begin(), flags.end(), 1), 1);
  // index = (uy + C) * W + ux with (ux, uy) = (5, 4)
  EXPECT_EQ(flags[(4 + 3) * 9 + 5], 1);
  expect_same_valid_positions(b, texels, {9, 7, 3}, piece);
}

TEST(OpenCLCompactValidPositions, MatchesCpuForManySizesAndDensities) {
  TW_BACKENDS(b);
  std::mt19937 rng(11);
  // Sizes around the work-group size (256), not multiples of it, and above 2^16.
  for (std::size_t size : {0u, 1u, 2u, 255u, 256u, 257u, 1000u, 65535u, 65537u, 70001u, 300000u}) {
    for (int percent : {0, 1, 20, 100}) {
      std::vector<std::uint8_t> flags(size);
      for (auto& f : flags) f = uniform(rng, 0, 99) < percent;
      std::vector<std::int32_t> cpu_indices, cl_indices;
      b.cpu->compact_valid_positions(flags, cpu_indices);
      b.opencl->compact_valid_positions(flags, cl_indices);
      ASSERT_EQ(cl_indices, cpu_indices) << "size " << size << " density " << percent;
      ASSERT_EQ(cl_indices.size(), std::size_t(std::count(flags.begin(), flags.end(), 1)));
      EXPECT_TRUE(std::is_sorted(cl_indices.begin(), cl_indices.end()));
    }
  }
}

TEST(OpenCLCompactValidPositions, SingleSetFlagAtEachEnd) {
  TW_BACKENDS(b);
  for (std::size_t at : {std::size_t(0), std::size_t(131071)}) {
    std::vector<std::uint8_t> flags(131072, 0);
    flags[at] = 1;
    std::vector<std::int32_t> indices;
    b.opencl->compact_valid_positions(flags, indices);
    EXPECT_EQ(indices, std::vector<std::int32_t>{std::int32_t(at)});
  }
}

std::vector<std::int32_t> random_indices(std::mt19937& rng, const PositionSpace& space, int count) {
  std::vector<std::int32_t> indices;
  for (int i = 0; i < count; ++i) indices.push_back(uniform(rng, 0, int(space.count()) - 1));
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

TEST(OpenCLExtractColumns, RightAndLeftMatchCpu) {
  TW_BACKENDS(b);
  for (unsigned seed = 21; seed <= 26; ++seed) {
    std::mt19937 rng(seed);
    const int width = uniform(rng, 2, 90), height = uniform(rng, 1, 50);
    const int column = uniform(rng, 1, 70);
    const PositionSpace space{width, height, column};
    CostTexels texels = random_texels(rng, width, height, 50);
    PieceFootprint piece = random_piece(rng, column);
    // Includes positions above the exemplar (the first C rows of the position space).
    std::vector<std::int32_t> indices = random_indices(rng, space, uniform(rng, 1, 700));
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    ColumnSet cpu_right, cl_right, cpu_left, cl_left;
    b.cpu->extract_right_columns(texels, space, piece, indices, cpu_right);
    b.opencl->extract_right_columns(texels, space, piece, indices, cl_right);
    EXPECT_EQ(cl_right.column, column);
    EXPECT_EQ(cl_right.samples, cpu_right.samples);
    b.cpu->extract_left_columns(texels, space, indices, cpu_left);
    b.opencl->extract_left_columns(texels, space, indices, cl_left);
    EXPECT_EQ(cl_left.samples, cpu_left.samples);
  }
}

TEST(OpenCLExtractColumns, LeftColumnAboveExemplarIsTransparentThenTexels) {
  TW_BACKENDS(b);
  std::mt19937 rng(5);
  CostTexels texels = random_texels(rng, 4, 3, 100);
  const PositionSpace space{4, 3, 5};
  ColumnSet left;
  // (ux, uy) = (2, -2): rows -2, -1 are outside, rows 0..2 are column 2 of the exemplar.
  b.opencl->extract_left_columns(texels, space, {(-2 + 5) * 4 + 2}, left);
  EXPECT_EQ(left.samples,
            (std::vector<std::uint32_t>{0, 0, texels.rgba[2], texels.rgba[6], texels.rgba[10]}));
}

TEST(OpenCLExtractColumns, RightSampleOnTexelCentreIsThatTexel) {
  TW_BACKENDS(b);
  std::mt19937 rng(6);
  CostTexels texels = random_texels(rng, 6, 6, 100);
  PieceFootprint piece;
  piece.column = 2;
  piece.right_fx = {3 * 256 + 128, 256 + 128 + 64};  // a texel centre, then a quarter off
  piece.right_fy = {128, 2 * 256 + 128};
  ColumnSet right;
  b.opencl->extract_right_columns(texels, {6, 6, 2}, piece, {(1 + 2) * 6 + 1}, right);
  ASSERT_EQ(right.samples.size(), 2u);
  EXPECT_EQ(right.samples[0], texels.rgba[1 * 6 + 4]);
  ColumnSet cpu_right;
  b.cpu->extract_right_columns(texels, {6, 6, 2}, piece, {(1 + 2) * 6 + 1}, cpu_right);
  EXPECT_EQ(right.samples, cpu_right.samples);
}

struct RowResult {
  std::vector<std::int64_t> cost;
  std::vector<std::int32_t> argmin;
};

RowResult run_row(detail::Backend& backend, const std::vector<std::int64_t>& previous,
                  const ColumnSet& right, const ColumnSet& left) {
  RowResult result;
  backend.update_table_row(previous, right, left, result.cost, result.argmin);
  return result;
}

void expect_same_row(Backends& b, const std::vector<std::int64_t>& previous, const ColumnSet& right,
                     const ColumnSet& left) {
  RowResult cpu = run_row(*b.cpu, previous, right, left);
  RowResult cl = run_row(*b.opencl, previous, right, left);
  EXPECT_EQ(cl.cost, cpu.cost);
  EXPECT_EQ(cl.argmin, cpu.argmin);
  // Both prune; the unpruned definition (every pair, every sample) must agree with them.
  RowResult naive;
  detail::update_table_row_naive(previous, right, left, naive.cost, naive.argmin);
  EXPECT_EQ(cl.cost, naive.cost);
  EXPECT_EQ(cl.argmin, naive.argmin);
}

ColumnSet palette_columns(std::mt19937& rng, int count, int column, int palette) {
  std::vector<std::uint32_t> colours;
  for (int i = 0; i < palette; ++i)
    colours.push_back(pack_rgba(uniform(rng, 0, 255), uniform(rng, 0, 255), uniform(rng, 0, 255),
                                uniform(rng, 0, 1) * 255));
  ColumnSet set{column, {}};
  for (int i = 0; i < count * column; ++i)
    set.samples.push_back(colours[uniform(rng, 0, palette - 1)]);
  return set;
}

TEST(OpenCLUpdateTableRow, MatchesCpuOnRandomColumns) {
  TW_BACKENDS(b);
  for (unsigned seed = 31; seed <= 36; ++seed) {
    std::mt19937 rng(seed);
    const int column = uniform(rng, 1, 90);
    const int previous_count = uniform(rng, 1, 300), current_count = uniform(rng, 1, 300);
    std::vector<std::int64_t> previous(previous_count);
    for (auto& p : previous) p = uniform(rng, 0, 2'000'000);
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    expect_same_row(b, previous, palette_columns(rng, previous_count, column, 200),
                    palette_columns(rng, current_count, column, 200));
  }
}

TEST(OpenCLUpdateTableRow, ContinuousAlphaMatchesCpu) {
  TW_BACKENDS(b);
  for (unsigned seed = 61; seed <= 64; ++seed) {
    std::mt19937 rng(seed);
    const int width = uniform(rng, 20, 60), height = uniform(rng, 10, 30);
    const int column = uniform(rng, 4, 40);
    const PositionSpace space{width, height, column};
    CostTexels texels = random_texels(rng, width, height, 50);
    texels.binary_alpha = false;
    std::vector<std::int32_t> indices = random_indices(rng, space, 300);
    ColumnSet right, left, cpu_left;
    b.opencl->extract_right_columns(texels, space, random_piece(rng, column), indices, right);
    b.opencl->extract_left_columns(texels, space, indices, left);
    b.cpu->extract_left_columns(texels, space, indices, cpu_left);
    EXPECT_FALSE(right.binary_alpha);
    EXPECT_FALSE(left.binary_alpha);
    EXPECT_EQ(left.samples, cpu_left.samples);
    std::vector<std::int64_t> previous(indices.size());
    for (auto& p : previous) p = uniform(rng, 0, 300000);
    SCOPED_TRACE(testing::Message() << "seed " << seed);
    expect_same_row(b, previous, right, left);
  }
}

TEST(OpenCLUpdateTableRow, TiesGoToTheLowestPreviousIndex) {
  TW_BACKENDS(b);
  std::mt19937 rng(41);
  // Two colours and costs in {0, 1}: nearly every entry has many equal candidates.
  const int column = 5;
  std::vector<std::int64_t> previous(77);
  for (auto& p : previous) p = uniform(rng, 0, 1);
  ColumnSet right = palette_columns(rng, 77, column, 2);
  ColumnSet left = palette_columns(rng, 45, column, 2);
  expect_same_row(b, previous, right, left);
  // Identical columns everywhere and equal costs: the minimum is reached by v = 0 for all j.
  ColumnSet same{column, std::vector<std::uint32_t>(77 * column, pack_rgba(9, 9, 9, 255))};
  ColumnSet same_left{column, std::vector<std::uint32_t>(3 * column, pack_rgba(9, 9, 9, 255))};
  RowResult cl = run_row(*b.opencl, std::vector<std::int64_t>(77, 5), same, same_left);
  EXPECT_EQ(cl.argmin, (std::vector<std::int32_t>{0, 0, 0}));
  EXPECT_EQ(cl.cost, (std::vector<std::int64_t>{5, 5, 5}));
}

TEST(OpenCLUpdateTableRow, OnePreviousPositionAndEmptySides) {
  TW_BACKENDS(b);
  std::mt19937 rng(51);
  const int column = 7;
  ColumnSet right = palette_columns(rng, 1, column, 10);
  ColumnSet left = palette_columns(rng, 33, column, 10);
  expect_same_row(b, {123}, right, left);
  RowResult cl = run_row(*b.opencl, {123}, right, left);
  EXPECT_EQ(cl.argmin, std::vector<std::int32_t>(33, 0));

  // No current position: an empty row. No previous position: nothing reaches any entry.
  expect_same_row(b, {123}, right, ColumnSet{column, {}});
  EXPECT_TRUE(run_row(*b.opencl, {123}, right, ColumnSet{column, {}}).cost.empty());
  expect_same_row(b, {}, ColumnSet{column, {}}, left);
}

TEST(OpenCLUpdateTableRow, MatchesCpuOnChainColumnsAcrossWorkGroupBoundaries) {
  TW_BACKENDS(b);
  CostTexels texels = chain_texels(96, 36, 7);
  const int column = 36;
  const PositionSpace space{96, 36, column};
  PieceFootprint piece = slanted_piece(column, 5, 300);
  std::vector<std::uint8_t> flags;
  std::vector<std::int32_t> indices;
  b.cpu->find_valid_positions(texels, space, piece, flags);
  b.cpu->compact_valid_positions(flags, indices);
  ASSERT_GT(indices.size(), 20u);
  if (indices.size() % 16 == 0) indices.pop_back();  // V not a multiple of the group size
  ColumnSet right, left;
  b.cpu->extract_right_columns(texels, space, piece, indices, right);
  b.cpu->extract_left_columns(texels, space, indices, left);
  std::mt19937 rng(8);
  std::vector<std::int64_t> previous(indices.size());
  for (auto& p : previous) p = uniform(rng, 0, 40000);
  expect_same_row(b, previous, right, left);
  expect_same_row(b, std::vector<std::int64_t>(indices.size(), 0), right, left);
}

TEST(OpenCLContext, UnknownDeviceAndMissingKernelNameTheCulprit) {
  TW_REQUIRE_OPENCL(context);
  EXPECT_FALSE(context->device_name().empty());
  try {
    OpenCLContext::create({"no-such-device-anywhere", ""});
    FAIL() << "expected tw::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("no-such-device-anywhere"), std::string::npos);
  }
  TempDir dir;
  OpenCLContext empty = OpenCLContext::create({"0", dir.path().string()});
  try {
    empty.program("row_update");
    FAIL() << "expected tw::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("row_update.cl"), std::string::npos) << error.what();
  }
}

TEST(OpenCLContext, SelectsDevicesByIndexOrNameSubstring) {
  TW_REQUIRE_OPENCL(context);
  const std::string name = context->device_name();
  EXPECT_EQ(OpenCLContext::create({"0", ""}).device_name(), name);
  // The last word of the label, in upper case: matching ignores case.
  std::string word = name.substr(name.find_last_of(' ') + 1);
  std::transform(word.begin(), word.end(), word.begin(), ::toupper);
  EXPECT_EQ(OpenCLContext::create({word, ""}).device_name(), name);
  try {
    OpenCLContext::create({"999", ""});
    FAIL() << "expected tw::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("999"), std::string::npos) << error.what();
  }
}

TEST(OpenCLContext, BuildFailureCarriesTheBuildLog) {
  TW_REQUIRE_OPENCL(context);
  TempDir dir;
  std::ofstream(dir / "broken.cl")
      << "kernel void broken(global int* x) { x[0] = undeclared_name; }\n";
  OpenCLContext with_broken = OpenCLContext::create({"0", dir.path().string()});
  try {
    with_broken.program("broken");
    FAIL() << "expected tw::Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("broken.cl"), std::string::npos) << message;
    EXPECT_NE(message.find("undeclared_name"), std::string::npos) << message;
  }
}

TEST(BackendFactory, ParsesKindsAndMakesBackends) {
  EXPECT_EQ(parse_backend_kind("cpu"), BackendKind::cpu);
  EXPECT_EQ(parse_backend_kind("opencl"), BackendKind::opencl);
  EXPECT_EQ(parse_backend_kind("auto"), BackendKind::automatic);
  try {
    parse_backend_kind("cuda");
    FAIL() << "expected tw::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("cuda"), std::string::npos);
  }
  TW_REQUIRE_OPENCL(context);
  EXPECT_NE(detail::make_backend(BackendKind::opencl, context)->name().find("opencl"),
            std::string::npos);
  // auto takes OpenCL on GPUs and accelerators, the (faster) CPU backend on CPU devices.
  const bool cpu_device = (context->device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) != 0;
  const std::string automatic =
      detail::make_backend(BackendKind::automatic, context)->name();
  EXPECT_EQ(automatic.find("opencl") == std::string::npos, cpu_device) << automatic;
  EXPECT_EQ(detail::make_backend(BackendKind::cpu, nullptr)->name(),
            detail::make_cpu_backend()->name());
}

}  // namespace
}  // namespace tw::test
