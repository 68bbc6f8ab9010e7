#pragma once
// A uniform bin grid over the pixel windows of many items (features, ribbons, patterns): which
// of them meet a window, without a pass over all of them. Plain data, built once per world.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/grid.hpp"

namespace tw {

struct WindowIndex {
  int bin_size = 256;  // pixels per bin side
  int bins_x = 0, bins_y = 0;
  std::vector<Window> windows;        // one per item (empty: meets nothing)
  std::vector<std::int64_t> offsets;  // CSR: bin b holds items[offsets[b] .. offsets[b + 1])
  std::vector<std::uint32_t> items;
};

// Bins `windows` (pixel windows of `grid`, clamped to it) into bins of `bin_size` pixels.
WindowIndex index_windows(const GridSpec& grid, std::vector<Window> windows, int bin_size = 256);

// The items whose window meets `window`, in ascending order.
std::vector<std::size_t> items_meeting(const WindowIndex& index, const Window& window);

}  // namespace tw
