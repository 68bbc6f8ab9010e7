#pragma once
// A ribbon: the band of width b around a curve, sliced into pieces of length delta
// (Zhou, Lasram & Lefebvre 2013, Section 1.3). Everything in world metres.
#include <cstdint>
#include <vector>

#include "ribbon/curve.hpp"

namespace tw {

// The quadrilateral (T(x_i), B(x_i), B(x_{i+1}), T(x_{i+1})) of piece i. "Top" is the left
// side of the curve when walking along it (T = C + b/2 n, n the left normal).
struct Piece {
  Vec2 top_left;      // T(x_i)
  Vec2 bottom_left;   // B(x_i)
  Vec2 bottom_right;  // B(x_{i+1})
  Vec2 top_right;     // T(x_{i+1})
  double x0 = 0.0;    // arc length at the left edge
  double x1 = 0.0;    // arc length at the right edge (x1 - x0 < delta for a last fractional piece)

  // The paper's vectors from the top-left corner: l_i = B(x_i) - T(x_i), d_i, t_i.
  Vec2 l() const { return bottom_left - top_left; }
  Vec2 d() const { return bottom_right - top_left; }
  Vec2 t() const { return top_right - top_left; }
};

struct RibbonParams {
  double width = 0.0;  // b, metres
  double delta = 0.0;  // slicing step, metres
  // Half-window (metres) of the centred difference giving the normal at x_i; 0 -> delta / 2.
  double tangent_window = 0.0;
};

struct Ribbon {
  Curve centerline;
  double width = 0.0;
  double delta = 0.0;
  bool closed = false;
  std::vector<Piece> pieces;  // N = ceil(L / delta); piece N-1 may be fractional
  // On a closed ribbon, piece N-1's right edge is piece 0's left edge (the paper's terminal piece).
};

// Slices the band around `centerline` into pieces. Throws tw::Error if width or delta <= 0
// or the curve is shorter than delta.
Ribbon make_ribbon(const Curve& centerline, const RibbonParams& params);

}  // namespace tw
