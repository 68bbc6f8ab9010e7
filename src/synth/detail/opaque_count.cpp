#include "synth/detail/opaque_count.hpp"

#include <algorithm>

#include "synth/detail/cost.hpp"

namespace tw::detail {

std::vector<TexelRun> row_runs(const std::vector<TexelOffset>& offsets) {
  std::vector<TexelRun> runs;
  for (const TexelOffset& o : offsets) {
    if (!runs.empty() && runs.back().fixed == o.dy && runs.back().last + 1 == o.dx)
      runs.back().last = o.dx;
    else
      runs.push_back({o.dy, o.dx, o.dx});
  }
  return runs;
}

std::vector<TexelRun> column_runs(const std::vector<TexelOffset>& offsets) {
  std::vector<TexelOffset> sorted = offsets;
  std::stable_sort(sorted.begin(), sorted.end(), [](const TexelOffset& a, const TexelOffset& b) {
    return a.dx != b.dx ? a.dx < b.dx : a.dy < b.dy;
  });
  std::vector<TexelRun> runs;
  for (const TexelOffset& o : sorted) {
    if (!runs.empty() && runs.back().fixed == o.dx && runs.back().last + 1 == o.dy)
      runs.back().last = o.dy;
    else
      runs.push_back({o.dx, o.dy, o.dy});
  }
  return runs;
}

OpaqueCounter::OpaqueCounter(const CostTexels& t) : width_(t.width), height_(t.height) {
  by_row_.assign(std::size_t(height_) * (width_ + 1), 0);
  by_column_.assign(std::size_t(width_) * (height_ + 1), 0);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const int opaque = is_opaque(t.rgba[std::size_t(y) * width_ + x]) ? 1 : 0;
      by_row_[std::size_t(y) * (width_ + 1) + x + 1] =
          by_row_[std::size_t(y) * (width_ + 1) + x] + opaque;
      by_column_[std::size_t(x) * (height_ + 1) + y + 1] =
          by_column_[std::size_t(x) * (height_ + 1) + y] + opaque;
    }
}

void OpaqueCounter::set_interior(const std::vector<TexelOffset>& interior) {
  std::vector<TexelRun> rows = row_runs(interior), columns = column_runs(interior);
  columns_ = columns.size() < rows.size();
  runs_ = columns_ ? std::move(columns) : std::move(rows);
}

std::int32_t OpaqueCounter::row_run(int y, int x0, int x1) const {
  if (y < 0 || y >= height_) return 0;
  x0 = std::max(x0, 0), x1 = std::min(x1, width_ - 1);
  if (x0 > x1) return 0;
  const std::int32_t* line = by_row_.data() + std::size_t(y) * (width_ + 1);
  return line[x1 + 1] - line[x0];
}

std::int32_t OpaqueCounter::column_run(int x, int y0, int y1) const {
  if (x < 0 || x >= width_) return 0;
  y0 = std::max(y0, 0), y1 = std::min(y1, height_ - 1);
  if (y0 > y1) return 0;
  const std::int32_t* line = by_column_.data() + std::size_t(x) * (height_ + 1);
  return line[y1 + 1] - line[y0];
}

std::int32_t OpaqueCounter::count(int ux, int uy) const {
  std::int32_t count = 0;
  if (columns_)
    for (const TexelRun& r : runs_) count += column_run(ux + r.fixed, uy + r.first, uy + r.last);
  else
    for (const TexelRun& r : runs_) count += row_run(uy + r.fixed, ux + r.first, ux + r.last);
  return count;
}

}  // namespace tw::detail
