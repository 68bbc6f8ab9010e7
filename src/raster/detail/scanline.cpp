#include "raster/detail/scanline.hpp"

namespace tw::detail {

RowBuckets bucket_edges(const std::vector<ScanEdge>& edges, int row_begin, int row_end,
                        int block_rows) {
  RowBuckets buckets;
  buckets.row_begin = row_begin;
  buckets.block_rows = block_rows;
  const int blocks = (row_end - row_begin + block_rows - 1) / block_rows;
  std::vector<std::uint32_t> counts(std::size_t(blocks) + 1, 0);
  auto block_range = [&](const ScanEdge& e, int& b0, int& b1) {
    const int r0 = std::max(e.row_begin, row_begin);
    const int r1 = std::min(e.row_end, row_end);
    if (r0 >= r1) {
      b0 = b1 = 0;
      return;
    }
    b0 = (r0 - row_begin) / block_rows;
    b1 = (r1 - 1 - row_begin) / block_rows + 1;
  };
  for (const ScanEdge& e : edges) {
    int b0, b1;
    block_range(e, b0, b1);
    for (int b = b0; b < b1; ++b) ++counts[b + 1];
  }
  for (int b = 0; b < blocks; ++b) counts[b + 1] += counts[b];
  buckets.offsets = counts;
  buckets.edge_ids.resize(counts.back());
  for (std::uint32_t i = 0; i < edges.size(); ++i) {
    int b0, b1;
    block_range(edges[i], b0, b1);
    for (int b = b0; b < b1; ++b) buckets.edge_ids[counts[b]++] = i;
  }
  return buckets;
}

}  // namespace tw::detail
