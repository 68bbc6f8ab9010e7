#pragma once
// The pixels a ribbon's pieces can touch on a grid: where rasterizing a ribbon needs to look.
#include <cmath>
#include <vector>

#include "core/grid.hpp"
#include "ribbon/ribbon.hpp"

namespace tw {

// The box of a ribbon piece's four corners (or of all pieces of a ribbon, or of any points):
// lo = (+inf, +inf) and hi = (-inf, -inf) when there is none; non-finite coordinates are
// skipped axis by axis.
struct PieceBox {
  Vec2 lo{INFINITY, INFINITY}, hi{-INFINITY, -INFINITY};
};

// Grows `box` to hold `p` (a non-finite coordinate never widens it).
void include(PieceBox& box, Vec2 p);
// The box of `points`; empty when there are none.
PieceBox points_box(const std::vector<Vec2>& points);
// `box` grown by `margin` on every side.
PieceBox grown(const PieceBox& box, double margin);
// The world-metre box of a window of `grid`.
PieceBox world_box(const Window& window, const GridSpec& grid);
// Whether two boxes share a point (touching edges count); an empty box meets nothing.
bool meets(const PieceBox& a, const PieceBox& b);

// In world metres.
PieceBox piece_box(const Piece& piece);
PieceBox ribbon_box(const Ribbon& ribbon);
// In `grid`'s continuous pixel coordinates (x = column, y = row; rows grow southwards).
PieceBox piece_pixel_box(const Piece& piece, const GridSpec& grid);

// The window of `grid` holding every piece corner, plus a pixel; empty when the ribbon has no
// pieces or lies outside the grid. Corners far off the grid clamp (no int overflow).
Window ribbon_window(const Ribbon& ribbon, const GridSpec& grid);

// The window of `grid` holding every point of `points` grown by `reach` metres, plus two
// pixels; empty when it lies outside the grid. Far-off points clamp (no int overflow).
Window points_window(const std::vector<Vec2>& points, double reach, const GridSpec& grid);

// The intersection of two windows (empty, {0, 0, 0, 0}, when they do not meet).
Window intersect(const Window& a, const Window& b);

// `window` grown by `pixels` on every side, clamped to the grid.
Window grow_window(const Window& window, int pixels, const GridSpec& grid);

}  // namespace tw
