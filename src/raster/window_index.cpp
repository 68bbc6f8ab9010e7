#include "raster/window_index.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "raster/footprint.hpp"

namespace tw {

namespace {

// The bins [bx0, bx1) x [by0, by1) a window (clamped to the binned area) falls in.
struct BinRange {
  int bx0 = 0, by0 = 0, bx1 = 0, by1 = 0;
};

BinRange bins_of(const WindowIndex& index, const Window& w) {
  if (w.width <= 0 || w.height <= 0) return {};
  const auto bin = [&](int pixel, int count) {
    return std::clamp(pixel / index.bin_size, 0, count);
  };
  return {bin(std::max(0, w.col0), index.bins_x), bin(std::max(0, w.row0), index.bins_y),
          bin(std::max(0, w.col_end() - 1), index.bins_x - 1) + 1,
          bin(std::max(0, w.row_end() - 1), index.bins_y - 1) + 1};
}

}  // namespace

WindowIndex index_windows(const GridSpec& grid, std::vector<Window> windows, int bin_size) {
  if (bin_size <= 0) fail("index_windows: bin size must be > 0, got {}", bin_size);
  WindowIndex index;
  index.bin_size = bin_size;
  index.bins_x = std::max(1, (grid.width + bin_size - 1) / bin_size);
  index.bins_y = std::max(1, (grid.height + bin_size - 1) / bin_size);
  for (Window& w : windows) w = intersect(w, Window::whole(grid));
  index.windows = std::move(windows);
  const std::size_t bins = std::size_t(index.bins_x) * index.bins_y;
  std::vector<std::int64_t> counts(bins + 1, 0);
  for (const Window& w : index.windows) {
    const BinRange r = bins_of(index, w);
    for (int by = r.by0; by < r.by1; ++by)
      for (int bx = r.bx0; bx < r.bx1; ++bx) ++counts[std::size_t(by) * index.bins_x + bx + 1];
  }
  for (std::size_t b = 0; b < bins; ++b) counts[b + 1] += counts[b];
  index.offsets = counts;
  index.items.resize(std::size_t(counts.back()));
  for (std::size_t i = 0; i < index.windows.size(); ++i) {
    const BinRange r = bins_of(index, index.windows[i]);
    for (int by = r.by0; by < r.by1; ++by)
      for (int bx = r.bx0; bx < r.bx1; ++bx)
        index.items[std::size_t(counts[std::size_t(by) * index.bins_x + bx]++)] = std::uint32_t(i);
  }
  return index;
}

std::vector<std::size_t> items_meeting(const WindowIndex& index, const Window& window) {
  std::vector<std::size_t> found;
  const BinRange r = bins_of(index, window);
  for (int by = r.by0; by < r.by1; ++by)
    for (int bx = r.bx0; bx < r.bx1; ++bx) {
      const std::size_t b = std::size_t(by) * index.bins_x + bx;
      for (std::int64_t k = index.offsets[b]; k < index.offsets[b + 1]; ++k) {
        const std::size_t item = index.items[std::size_t(k)];
        if (intersect(index.windows[item], window).width > 0) found.push_back(item);
      }
    }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

}  // namespace tw
