#include "geo/resample.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "geo/detail/cell_sampling.hpp"

namespace tw {
namespace {

// Cells of a raster covering `window` of a grid, addressed in the grid's indices; NaN off the
// grid (cells of the grid outside the window are never asked for: the window covers them).
struct WindowCells {
  const Raster<float>& pixels;
  Window window;
  int grid_width, grid_height;
  float operator()(int col, int row) const {
    if (col < 0 || row < 0 || col >= grid_width || row >= grid_height)
      return std::numeric_limits<float>::quiet_NaN();
    return pixels.at(col - window.col0, row - window.row0);
  }
};

WindowCells whole_cells(const Raster<float>& height) {
  return {height, {0, 0, height.width, height.height}, height.width, height.height};
}

// The raster's own size, whatever the grid says (the sampling rules of a raster).
GridSpec sized_like(const GridSpec& grid, const Raster<float>& height) {
  GridSpec g = grid;
  g.width = height.width;
  g.height = height.height;
  return g;
}

}  // namespace

double sample_height_bilinear(const Raster<float>& height, const GridSpec& grid, Vec2 world) {
  return detail::bilinear_at(whole_cells(height), sized_like(grid, height), world);
}

double sample_height_cubic(const Raster<float>& height, const GridSpec& grid, Vec2 world) {
  return detail::cubic_at(whole_cells(height), sized_like(grid, height), world);
}

Raster<float> resample_heights(const Raster<float>& height, const GridSpec& from,
                               const GridSpec& to, Resampling resampling) {
  return resample_heights_window(height, Window::whole(sized_like(from, height)),
                                 sized_like(from, height), to, Window::whole(to), resampling);
}

Window resample_source_window(const GridSpec& from, const GridSpec& to, const Window& window) {
  // Every sample point lies within the target cells; bilinear reads one cell either side of
  // it, cubic two, the centre check the cell under it: a margin of 3 covers all (and rounding).
  const Vec2 a = from.world_to_pixel(to.pixel_to_world({double(window.col0), double(window.row0)}));
  const Vec2 b =
      from.world_to_pixel(to.pixel_to_world({double(window.col_end()), double(window.row_end())}));
  const auto clamp_to = [](double v, int n) { return int(std::clamp(v, 0.0, double(n))); };
  const int c0 = clamp_to(std::floor(std::min(a.x, b.x)) - 3, from.width);
  const int c1 = clamp_to(std::ceil(std::max(a.x, b.x)) + 3, from.width);
  const int r0 = clamp_to(std::floor(std::min(a.y, b.y)) - 3, from.height);
  const int r1 = clamp_to(std::ceil(std::max(a.y, b.y)) + 3, from.height);
  return {c0, r0, c1 - c0, r1 - r0};
}

Raster<float> resample_heights_window(const Raster<float>& source, const Window& source_window,
                                      const GridSpec& from, const GridSpec& to,
                                      const Window& window, Resampling resampling) {
  if (source.width != source_window.width || source.height != source_window.height)
    fail("resample: source raster is {} x {}, its window {} x {}", source.width, source.height,
         source_window.width, source_window.height);
  // A target cell larger than the source cells averages the interpolant over k x k points (the
  // source cell centres when the lattices align), so downsampling does not alias.
  const int kx = detail::samples_per_side(to.pixel_width / from.pixel_width);
  const int ky = detail::samples_per_side(to.pixel_height / from.pixel_height);
  const WindowCells cells{source, source_window, from.width, from.height};
  Raster<float> out(window.width, window.height);
  // Rows are independent and indexed in the whole grid: any window and split give the same bits.
  tbb::parallel_for(0, window.height, [&](int r) {
    for (int c = 0; c < window.width; ++c)
      out.at(c, r) = detail::resampled_cell(cells, from, to, window.col0 + c, window.row0 + r, kx,
                                            ky, resampling);
  });
  return out;
}

}  // namespace tw
