#include "synth/detail/footprint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <utility>
#include "raster/footprint.hpp"

namespace tw::detail {
namespace {

using TexelSet = std::set<std::pair<int, int>>;  // (dy, dx): ordered row by row

// Winding number of a closed polygon around p (Sunday's crossing rule).
template <std::size_t N>
int winding(const std::array<Vec2, N>& polygon, Vec2 p) {
  int w = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const Vec2 a = polygon[i], b = polygon[(i + 1) % N];
    const double side = cross(b - a, p - a);
    if (a.y <= p.y) {
      if (b.y > p.y && side > 0) ++w;
    } else if (b.y <= p.y && side < 0) {
      --w;
    }
  }
  return w;
}

// Texels touched by the segment a -> b (sampled every quarter texel, ends included).
void add_segment_texels(Vec2 a, Vec2 b, TexelSet& out) {
  const int steps = std::max(1, int(std::ceil(length(b - a) * 4.0)));
  for (int i = 0; i <= steps; ++i) {
    const Vec2 p = lerp(a, b, double(i) / steps);
    out.insert({int(std::floor(p.y)), int(std::floor(p.x))});
  }
}

// The 2 x 2 texels a bilinear read at exemplar point p touches.
void add_bilinear_texels(Vec2 p, TexelSet& out) {
  const int x0 = int(std::floor(p.x - 0.5)), y0 = int(std::floor(p.y - 0.5));
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) out.insert({y0 + dy, x0 + dx});
}

void append(const TexelSet& set, std::vector<TexelOffset>& out) {
  for (const auto& [dy, dx] : set) out.push_back({dx, dy});
}

}  // namespace

PieceFrame piece_frame(const Piece& piece, double scale) {
  PieceFrame frame;
  frame.origin = piece.top_left;
  frame.across = normalized(piece.l());
  frame.along = perp(frame.across);
  if (dot(frame.along, piece.t() + piece.d() - piece.l()) < 0.0) frame.along = -frame.along;
  frame.scale = scale;
  return frame;
}

Vec2 to_exemplar(const PieceFrame& frame, Vec2 world) {
  const Vec2 w = world - frame.origin;
  return {0.5 + frame.scale * dot(w, frame.along), frame.scale * dot(w, frame.across)};
}

Vec2 to_world(const PieceFrame& frame, Vec2 exemplar) {
  return frame.origin + frame.along * ((exemplar.x - 0.5) / frame.scale) +
         frame.across * (exemplar.y / frame.scale);
}

int column_count(double ribbon_width, double scale) {
  return std::max(1, int(std::ceil(ribbon_width * scale - 1e-9)));
}

int piece_winding(const Piece& piece, Vec2 world) {
  const std::array<Vec2, 4> quad{piece.top_left, piece.bottom_left, piece.bottom_right,
                                 piece.top_right};
  return winding(quad, world);
}

int supersampling(double scale, const GridSpec& canvas) {
  const double texels_per_pixel = scale * std::max(canvas.pixel_width, canvas.pixel_height);
  return std::clamp(int(std::ceil(texels_per_pixel - 1e-9)), 1, 4);
}

Vec2 subsample_world(const GridSpec& canvas, int col, int row, int i, int j, int n) {
  return canvas.pixel_to_world({col + (i + 0.5) / n, row + (j + 0.5) / n});
}

PieceFootprint make_piece_footprint(const Piece& piece, double scale, int column,
                                    const GridSpec& canvas,
                                    const SparseRaster<std::uint8_t>* forbidden,
                                    double min_coverage) {
  const PieceFrame frame = piece_frame(piece, scale);
  const Vec2 q_top_left = to_exemplar(frame, piece.top_left);
  const Vec2 q_bottom_left = to_exemplar(frame, piece.bottom_left);
  const Vec2 q_bottom_right = to_exemplar(frame, piece.bottom_right);
  const Vec2 q_top_right = to_exemplar(frame, piece.top_right);
  const std::array<Vec2, 4> quad{q_top_left, q_bottom_left, q_bottom_right, q_top_right};

  PieceFootprint footprint;
  footprint.column = column;
  // Right-edge samples at the same fractions of the edge as the left samples' k + 0.5 texels
  // of the left edge, so a straight ribbon tiles a straight pattern exactly.
  const double left_length = q_bottom_left.y - q_top_left.y;
  for (int k = 0; k < column; ++k) {
    const Vec2 p = lerp(q_top_right, q_bottom_right, (k + 0.5) / left_length);
    footprint.right_fx.push_back(std::int32_t(std::lround(p.x * 256.0)));
    footprint.right_fy.push_back(std::int32_t(std::lround(p.y * 256.0)));
  }

  TexelSet edges;
  add_segment_texels(q_top_left, q_top_right, edges);
  add_segment_texels(q_bottom_left, q_bottom_right, edges);
  append(edges, footprint.must_be_clear);

  // Interior texels: centres inside the quad.
  double min_x = 1e300, min_y = 1e300, max_x = -1e300, max_y = -1e300;
  for (const Vec2& q : quad) {
    min_x = std::min(min_x, q.x), max_x = std::max(max_x, q.x);
    min_y = std::min(min_y, q.y), max_y = std::max(max_y, q.y);
  }
  TexelSet blocked;
  for (int y = int(std::floor(min_y)) - 1; y <= int(std::ceil(max_y)); ++y) {
    for (int x = int(std::floor(min_x)) - 1; x <= int(std::ceil(max_x)); ++x) {
      const Vec2 centre{x + 0.5, y + 0.5};
      if (winding(quad, centre) == 0) continue;
      footprint.interior.push_back({x, y});
      if (!forbidden) continue;
      // A texel of the piece whose centre lands on a forbidden pixel must stay transparent.
      const Vec2 pixel = canvas.world_to_pixel(to_world(frame, centre));
      const int col = int(std::floor(pixel.x)), row = int(std::floor(pixel.y));
      if (forbidden->at(col, row)) blocked.insert({y, x});
    }
  }

  if (forbidden) {
    // The reverse direction: every subsample the renderer takes on a forbidden pixel inside
    // this piece reads only transparent texels (bilinear: the 2 x 2 around it).
    const int n = supersampling(scale, canvas);
    const PieceBox box = piece_pixel_box(piece, canvas);
    const double pmin_x = box.lo.x, pmin_y = box.lo.y, pmax_x = box.hi.x, pmax_y = box.hi.y;
    const int c0 = std::max(0, int(std::floor(pmin_x)) - 1);
    const int c1 = std::min(forbidden->width() - 1, int(std::floor(pmax_x)) + 1);
    const int r0 = std::max(0, int(std::floor(pmin_y)) - 1);
    const int r1 = std::min(forbidden->height() - 1, int(std::floor(pmax_y)) + 1);
    for (int row = r0; row <= r1; ++row) {
      for (int col = c0; col <= c1; ++col) {
        if (!forbidden->at(col, row)) continue;
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            const Vec2 w = subsample_world(canvas, col, row, i, j, n);
            if (piece_winding(piece, w) == 0) continue;
            add_bilinear_texels(to_exemplar(frame, w), blocked);
          }
        }
      }
    }
  }
  for (const auto& e : edges) blocked.erase(e);
  append(blocked, footprint.must_be_clear);
  footprint.min_opaque = min_opaque_texels(min_coverage, footprint.interior.size());
  return footprint;
}

int min_opaque_texels(double min_coverage, std::size_t interior) {
  return std::max(1, int(std::ceil(min_coverage * double(interior) - 1e-9)));
}

}  // namespace tw::detail
