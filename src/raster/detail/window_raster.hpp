#pragma once
// Small helpers for window-sized outputs.
#include <cstdint>
#include <vector>

#include "core/grid.hpp"
#include "raster/polygon.hpp"

namespace tw::detail {

// Allocates `out` for the window when empty; throws tw::Error when it has another size.
void prepare_window_raster(Raster<std::uint8_t>& out, const Window& window, const char* who);
// Throws tw::Error when the window is negative-sized.
void check_window(const Window& window, const char* who);

// Pixel-space rings of world polygons, scaled by `scale` (supersampling), with their shape index.
struct PixelRing {
  std::vector<Vec2> points;
  std::uint32_t shape;
};
// Polygons whose bounding box misses `window` (in scaled pixels) are left out: they cannot touch
// it, and on a tile of a large world most polygons are elsewhere.
std::vector<PixelRing> polygons_to_pixels(const std::vector<Polygon>& polygons,
                                          const GridSpec& grid, double scale, const Window& window);

}  // namespace tw::detail
