#include "raster/footprint.hpp"

#include <algorithm>
#include <cmath>

namespace tw {

void include(PieceBox& box, Vec2 p) {
  // std::min(a, NaN) is a: a non-finite corner coordinate never widens the box.
  box.lo = {std::min(box.lo.x, p.x), std::min(box.lo.y, p.y)};
  box.hi = {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y)};
}

PieceBox points_box(const std::vector<Vec2>& points) {
  PieceBox box;
  for (const Vec2 p : points) include(box, p);
  return box;
}

PieceBox grown(const PieceBox& box, double margin) {
  return {{box.lo.x - margin, box.lo.y - margin}, {box.hi.x + margin, box.hi.y + margin}};
}

PieceBox world_box(const Window& window, const GridSpec& grid) {
  const Vec2 a = grid.pixel_to_world({double(window.col0), double(window.row_end())});
  const Vec2 b = grid.pixel_to_world({double(window.col_end()), double(window.row0)});
  return {a, b};
}

bool meets(const PieceBox& a, const PieceBox& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}

PieceBox piece_box(const Piece& piece) {
  PieceBox box;
  for (const Vec2 c : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right})
    include(box, c);
  return box;
}

PieceBox ribbon_box(const Ribbon& ribbon) {
  PieceBox box;
  for (const Piece& piece : ribbon.pieces) {
    const PieceBox b = piece_box(piece);
    include(box, b.lo);
    include(box, b.hi);
  }
  return box;
}

PieceBox piece_pixel_box(const Piece& piece, const GridSpec& grid) {
  PieceBox box;
  for (const Vec2 c : {piece.top_left, piece.bottom_left, piece.bottom_right, piece.top_right})
    include(box, grid.world_to_pixel(c));
  return box;
}

Window ribbon_window(const Ribbon& ribbon, const GridSpec& grid) {
  PieceBox box;
  for (const Piece& piece : ribbon.pieces) {
    const PieceBox b = piece_pixel_box(piece, grid);
    include(box, b.lo);
    include(box, b.hi);
  }
  const double min_col = box.lo.x, min_row = box.lo.y, max_col = box.hi.x, max_row = box.hi.y;
  // Clamped in double before the conversion: a corner far outside the grid (a huge width)
  // must not overflow int.
  const auto clamped = [](double pixel, int limit) {
    return int(std::clamp(pixel, 0.0, double(limit)));
  };
  if (!(min_col <= max_col && min_row <= max_row)) return {};  // no (finite) corner
  const int col0 = clamped(std::floor(min_col) - 1, grid.width);
  const int row0 = clamped(std::floor(min_row) - 1, grid.height);
  const int col1 = clamped(std::ceil(max_col) + 1, grid.width);
  const int row1 = clamped(std::ceil(max_row) + 1, grid.height);
  if (col1 <= col0 || row1 <= row0) return {};
  return {col0, row0, col1 - col0, row1 - row0};
}

Window points_window(const std::vector<Vec2>& points, double reach, const GridSpec& grid) {
  if (points.empty() || !(reach >= 0.0)) return {};
  double min_x = points[0].x, max_x = min_x, min_y = points[0].y, max_y = min_y;
  for (const Vec2 p : points) {
    min_x = std::min(min_x, p.x), max_x = std::max(max_x, p.x);
    min_y = std::min(min_y, p.y), max_y = std::max(max_y, p.y);
  }
  const Vec2 a = grid.world_to_pixel({min_x - reach, max_y + reach});
  const Vec2 b = grid.world_to_pixel({max_x + reach, min_y - reach});
  const auto clamped = [](double pixel, int limit) {
    return int(std::clamp(pixel, 0.0, double(limit)));
  };
  if (!(std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(b.x) && std::isfinite(b.y)))
    return Window::whole(grid);
  const int col0 = clamped(std::floor(a.x) - 2, grid.width);
  const int row0 = clamped(std::floor(a.y) - 2, grid.height);
  const int col1 = clamped(std::ceil(b.x) + 2, grid.width);
  const int row1 = clamped(std::ceil(b.y) + 2, grid.height);
  if (col1 <= col0 || row1 <= row0) return {};
  return {col0, row0, col1 - col0, row1 - row0};
}

Window intersect(const Window& a, const Window& b) {
  const int col0 = std::max(a.col0, b.col0), row0 = std::max(a.row0, b.row0);
  const int col1 = std::min(a.col_end(), b.col_end()), row1 = std::min(a.row_end(), b.row_end());
  if (col1 <= col0 || row1 <= row0) return {};
  return {col0, row0, col1 - col0, row1 - row0};
}

Window grow_window(const Window& window, int pixels, const GridSpec& grid) {
  pixels = std::clamp(pixels, 0, std::max(grid.width, grid.height));  // no int overflow
  return intersect({window.col0 - pixels, window.row0 - pixels, window.width + 2 * pixels,
                    window.height + 2 * pixels},
                   Window::whole(grid));
}

}  // namespace tw
