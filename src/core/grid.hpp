#pragma once
// The world grid: a north-up raster in a metric CRS. Pixel (col, row) covers
// [col, col+1) x [row, row+1) in pixel coordinates; its centre is (col + 0.5, row + 0.5).
#include <array>
#include <cstdint>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

struct GridSpec {
  int width = 0;
  int height = 0;
  double origin_x = 0.0;      // world x of the left edge of column 0
  double origin_y = 0.0;      // world y of the top edge of row 0
  double pixel_width = 1.0;   // metres, > 0
  double pixel_height = 1.0;  // metres, > 0 (rows go south)

  constexpr Vec2 pixel_to_world(Vec2 p) const {
    return {origin_x + p.x * pixel_width, origin_y - p.y * pixel_height};
  }
  constexpr Vec2 world_to_pixel(Vec2 w) const {
    return {(w.x - origin_x) / pixel_width, (origin_y - w.y) / pixel_height};
  }
  constexpr Vec2 pixel_centre_world(int col, int row) const {
    return pixel_to_world({col + 0.5, row + 0.5});
  }
  // GDAL's geotransform of this grid.
  constexpr std::array<double, 6> geotransform() const {
    return {origin_x, pixel_width, 0.0, origin_y, 0.0, -pixel_height};
  }
  constexpr std::int64_t cell_count() const { return std::int64_t(width) * height; }
  friend constexpr bool operator==(const GridSpec&, const GridSpec&) = default;
};

// A rectangle of pixels of a grid: a tile, or a tile plus its halo (like OpenImageIO's ROI).
struct Window {
  int col0 = 0;
  int row0 = 0;
  int width = 0;
  int height = 0;

  constexpr int col_end() const { return col0 + width; }
  constexpr int row_end() const { return row0 + height; }
  constexpr bool contains(int col, int row) const {
    return col >= col0 && col < col_end() && row >= row0 && row < row_end();
  }
  static constexpr Window whole(const GridSpec& g) { return {0, 0, g.width, g.height}; }
  friend constexpr bool operator==(const Window&, const Window&) = default;
};

// Row-major pixels of one band over a window of a grid (the whole grid by default).
template <class T>
struct Raster {
  int width = 0;
  int height = 0;
  std::vector<T> pixels;

  Raster() = default;
  Raster(int w, int h, T fill = T{}) : width(w), height(h), pixels(std::size_t(w) * h, fill) {}

  T& at(int col, int row) { return pixels[std::size_t(row) * width + col]; }
  const T& at(int col, int row) const { return pixels[std::size_t(row) * width + col]; }
  bool inside(int col, int row) const {
    return col >= 0 && row >= 0 && col < width && row < height;
  }
};

}  // namespace tw
