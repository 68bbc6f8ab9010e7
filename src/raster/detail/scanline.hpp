#pragma once
// The scanline engine shared by polygon fill, coverage and fold-over detection.
//
// Edges are in pixel coordinates of the (possibly supersampled) world grid, never of a window, so
// a pixel's result does not depend on which window asks for it. Row r samples the line
// y = r + 0.5; an edge crosses it when y0 <= r + 0.5 < y1 (half-open, so a vertex is counted
// once); a span between crossings xa < xb covers the columns c with floor(xa + 0.5) <= c <
// floor(xb + 0.5), i.e. pixel centres in (xa, xb] -- GDAL's rule in GDALdllImageFilledPolygon.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/vec2.hpp"

namespace tw::detail {

struct ScanEdge {
  double x_top = 0.0;  // x at y_top
  double y_top = 0.0;  // the smaller y
  double dx_dy = 0.0;  // slope
  int row_begin = 0;   // first row whose centre line the edge crosses
  int row_end = 0;     // one past the last
  std::uint32_t shape = 0;
};

// Rows r with y0 <= r + 0.5 < y1.
inline int first_row_at_or_below(double y) {
  return int(std::ceil(y - 0.5));
}

struct Crossing {
  std::uint32_t shape;
  double x;
  friend bool operator<(const Crossing& a, const Crossing& b) {
    return a.shape != b.shape ? a.shape < b.shape : a.x < b.x;
  }
};

// Edge indices bucketed by blocks of rows, so each parallel task sees only nearby edges.
struct RowBuckets {
  int row_begin = 0;
  int block_rows = 1;
  std::vector<std::uint32_t> offsets;  // per block, into `edge_ids`
  std::vector<std::uint32_t> edge_ids;
};
RowBuckets bucket_edges(const std::vector<ScanEdge>& edges, int row_begin, int row_end,
                        int block_rows);

// `edges` must list each shape's edges contiguously, shapes in ascending order (EdgeBuilder does).
// Calls span(row, shape, col_begin, col_end) for every even-odd span of every shape on rows
// [row_begin, row_end), clipped to [col_begin, col_end) and non-empty. Blocks of `block_rows`
// rows (block starts aligned to row_begin) run in parallel; within a block rows are visited in
// order by one thread, and within a row shapes in increasing order; row_done(row) follows the
// last span of each row of a block that has edges.
template <class SpanFn, class RowDoneFn>
void scan_spans(const std::vector<ScanEdge>& edges, int row_begin, int row_end, int col_begin,
                int col_end, int block_rows, SpanFn&& span, RowDoneFn&& row_done) {
  if (row_end <= row_begin || col_end <= col_begin || edges.empty()) return;
  const RowBuckets buckets = bucket_edges(edges, row_begin, row_end, block_rows);
  const int blocks = int(buckets.offsets.size()) - 1;
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks), [&](const tbb::blocked_range<int>& range) {
    // Crossings per row of the block, generated edge by edge: the work is proportional to the
    // number of crossings, not to edges x rows.
    std::vector<std::vector<Crossing>> row_crossings(static_cast<std::size_t>(block_rows));
    for (int b = range.begin(); b != range.end(); ++b) {
      const int r0 = row_begin + b * block_rows;
      const int r1 = std::min(row_end, r0 + block_rows);
      const auto* ids = buckets.edge_ids.data() + buckets.offsets[b];
      const auto count = buckets.offsets[b + 1] - buckets.offsets[b];
      if (count == 0) continue;
      for (std::uint32_t k = 0; k < count; ++k) {
        const ScanEdge& e = edges[ids[k]];
        const int first = std::max(r0, e.row_begin), last = std::min(r1, e.row_end);
        for (int row = first; row < last; ++row)
          row_crossings[std::size_t(row - r0)].push_back(
              {e.shape, e.x_top + (row + 0.5 - e.y_top) * e.dx_dy});
      }
      for (int row = r0; row < r1; ++row) {
        auto& crossings = row_crossings[std::size_t(row - r0)];
        // Bucket edge ids ascend and shapes' edges are contiguous, so crossings already come
        // grouped by ascending shape: only each (small) group needs sorting by x.
        for (auto group = crossings.begin(); group != crossings.end();) {
          auto group_end = group + 1;
          while (group_end != crossings.end() && group_end->shape == group->shape) ++group_end;
          std::sort(group, group_end);
          group = group_end;
        }
        for (std::size_t i = 0; i + 1 < crossings.size();) {
          if (crossings[i].shape != crossings[i + 1].shape) {  // odd count: numerical leftover
            ++i;
            continue;
          }
          const double ca = std::floor(crossings[i].x + 0.5);
          const double cb = std::floor(crossings[i + 1].x + 0.5);
          const int c0 = int(std::clamp(ca, double(col_begin), double(col_end)));
          const int c1 = int(std::clamp(cb, double(col_begin), double(col_end)));
          if (c0 < c1) span(row, crossings[i].shape, c0, c1);
          i += 2;
        }
        crossings.clear();
        row_done(row);
      }
    }
  });
}

}  // namespace tw::detail

namespace tw::detail {
template <class SpanFn>
void scan_spans(const std::vector<ScanEdge>& edges, int row_begin, int row_end, int col_begin,
                int col_end, int block_rows, SpanFn&& span) {
  scan_spans(edges, row_begin, row_end, col_begin, col_end, block_rows, span, [](int) {});
}
}  // namespace tw::detail
