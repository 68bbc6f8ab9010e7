// The resident row pipeline of the OpenCL backend (synth/detail/opencl_dp_row.cpp): every
// work-group split and pruning on or off give the bytes of the definition (every pair, every
// sample), and rows run through dp_row (columns kept on the device, the next row extracted
// ahead, the cost row reused) give the CPU backend's costs and argmins, also when the caller
// changes the cost row between rows or announces a different next row.
#include <gtest/gtest.h>

#include <memory>

#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "test_opencl_fixtures.hpp"

namespace tw::test {
namespace {

using detail::ColumnSet;
using detail::CostTexels;
using detail::PieceFootprint;
using detail::PositionSpace;

struct Row {
  std::vector<std::int64_t> cost;
  std::vector<std::int32_t> argmin;
};

// Valid positions of a chain exemplar for a slanted piece, and the edges of a row over them.
struct ChainRow {
  CostTexels texels = chain_texels(67, 24, 5);
  PositionSpace space{67, 24, 24};
  PieceFootprint piece = slanted_piece(24, 5, 200);
  std::vector<std::int32_t> indices;
  ColumnSet right, left;
  ChainRow() {
    auto cpu = detail::make_cpu_backend();
    std::vector<std::uint8_t> flags;
    cpu->find_valid_positions(texels, space, piece, flags);
    cpu->compact_valid_positions(flags, indices);
    cpu->extract_right_columns(texels, space, piece, indices, right);
    cpu->extract_left_columns(texels, space, indices, left);
  }
};

TEST(OpenCLRowKernel, EveryWorkGroupSplitAndPruningOffGiveTheDefinition) {
  TW_REQUIRE_OPENCL(context);
  const ChainRow chain;
  ASSERT_GT(chain.indices.size(), 200u);
  std::mt19937 rng(3);
  std::vector<std::int64_t> previous(chain.indices.size());
  for (auto& p : previous) p = uniform(rng, 0, 30000);
  Row naive;
  detail::update_table_row_naive(previous, chain.right, chain.left, naive.cost, naive.argmin);
  // Few distinct group sizes: PoCL compiles the kernel once per local size.
  const detail::OpenCLRowOptions splits[] = {{1, 1, true}, {16, 4, true},  {7, 3, true},
                                             {7, 9, true}, {16, 4, false}, {1, 1, false}};
  for (const auto& options : splits) {
    SCOPED_TRACE(testing::Message() << "group " << options.group_size << " per item "
                                    << options.per_item << " prune " << options.prune);
    detail::OpenCLBackend backend(*context, options);
    Row row;
    backend.update_table_row(previous, chain.right, chain.left, row.cost, row.argmin);
    EXPECT_EQ(row.cost, naive.cost);
    EXPECT_EQ(row.argmin, naive.argmin);
  }
}

TEST(OpenCLRowKernel, TheDefaultSplitIsTheDevicesAndGivesTheDefinition) {
  TW_REQUIRE_OPENCL(context);
  const ChainRow chain;
  std::vector<std::int64_t> previous(chain.indices.size(), 0);
  Row naive, row;
  detail::update_table_row_naive(previous, chain.right, chain.left, naive.cost, naive.argmin);
  detail::OpenCLBackend backend(*context, {});
  const bool gpu = context->device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU;
  EXPECT_EQ(backend.row_options().per_item, gpu ? 1 : 4);
  EXPECT_EQ(backend.row_options().group_size, 16);
  backend.update_table_row(previous, chain.right, chain.left, row.cost, row.argmin);
  EXPECT_EQ(row.cost, naive.cost);
  EXPECT_EQ(row.argmin, naive.argmin);
}

TEST(OpenCLRowKernel, ManyTiesAndContinuousAlphaUnderEverySplit) {
  TW_REQUIRE_OPENCL(context);
  std::mt19937 rng(9);
  for (bool binary : {true, false}) {
    const int column = 9, previous_count = 150, current_count = 61;
    ColumnSet right{column, {}, binary}, left{column, {}, binary};
    // Four colours, alphas on both sides of 128: many equal totals, several mask groups.
    const std::uint32_t colours[] = {pack_rgba(9, 9, 9, 255), pack_rgba(9, 9, 9, 0),
                                     pack_rgba(200, 10, 10, 140), pack_rgba(200, 10, 10, 90)};
    for (int i = 0; i < previous_count * column; ++i)
      right.samples.push_back(colours[uniform(rng, 0, 3)]);
    for (int i = 0; i < current_count * column; ++i)
      left.samples.push_back(colours[uniform(rng, 0, 3)]);
    std::vector<std::int64_t> previous(previous_count);
    for (auto& p : previous) p = uniform(rng, 0, 2) * 1000;
    Row naive;
    detail::update_table_row_naive(previous, right, left, naive.cost, naive.argmin);
    for (const detail::OpenCLRowOptions& options :
         {detail::OpenCLRowOptions{16, 4, true}, {7, 2, true}, {1, 1, false}}) {
      SCOPED_TRACE(testing::Message() << "binary " << binary << " group " << options.group_size);
      detail::OpenCLBackend backend(*context, options);
      Row row;
      backend.update_table_row(previous, right, left, row.cost, row.argmin);
      EXPECT_EQ(row.cost, naive.cost);
      EXPECT_EQ(row.argmin, naive.argmin);
    }
  }
}

// Three rows through dp_row, the way the DP driver calls it, against the CPU backend.
TEST(OpenCLDpRow, ResidentRowsEqualCpuRowsWhateverTheCallerDoesBetweenRows) {
  TW_REQUIRE_OPENCL(context);
  const ChainRow chain;
  std::mt19937 rng(4);
  // Row sets: the chain's valid positions and subsets of them.
  std::vector<std::vector<std::int32_t>> sets(5);
  for (std::size_t i = 0; i < chain.indices.size(); ++i) {
    sets[0].push_back(chain.indices[i]);
    if (i % 2 == 0) sets[1].push_back(chain.indices[i]);
    if (i % 3 != 1) sets[2].push_back(chain.indices[i]);
    if (i % 5 != 0) sets[3].push_back(chain.indices[i]);
    if (i % 4 != 0) sets[4].push_back(chain.indices[i]);
  }
  const PieceFootprint other = slanted_piece(24, 6, -150);
  const PieceFootprint* pieces[] = {&chain.piece, &other, &chain.piece, &other};
  for (int scenario = 0; scenario < 3; ++scenario) {
    SCOPED_TRACE(testing::Message() << "scenario " << scenario);
    auto cpu = detail::make_cpu_backend();
    detail::OpenCLBackend opencl(*context);
    std::vector<std::int64_t> cpu_cost(sets[0].size(), 0), cl_cost = cpu_cost;
    for (int r = 1; r < 4; ++r) {
      const detail::RowEdges row{pieces[r - 1], &sets[r - 1], &sets[r]};
      // Scenario 1 announces a wrong next row (the row that comes is extracted then).
      const detail::RowEdges next{pieces[r], &sets[r], scenario == 1 ? &sets[0] : &sets[r + 1]};
      const detail::RowEdges* announced = r < 3 ? &next : nullptr;
      Row a, b;
      detail::RowTimes times;
      cpu->dp_row(chain.texels, chain.space, row, announced, cpu_cost, a.cost, a.argmin, times);
      opencl.dp_row(chain.texels, chain.space, row, announced, cl_cost, b.cost, b.argmin, times);
      EXPECT_EQ(b.cost, a.cost) << "row " << r;
      EXPECT_EQ(b.argmin, a.argmin) << "row " << r;
      cpu_cost = a.cost;
      cl_cost = b.cost;
      // Scenario 2 adds a per-position term on the host, as a unary cost would.
      if (scenario == 2)
        for (std::size_t j = 0; j < cpu_cost.size(); ++j) {
          const int extra = uniform(rng, 0, 5000);
          cpu_cost[j] += extra;
          cl_cost[j] += extra;
        }
    }
  }
}

}  // namespace
}  // namespace tw::test
