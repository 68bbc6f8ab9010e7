#include "raster/foldover.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <optional>

#include "core/error.hpp"
#include "raster/detail/edge_builder.hpp"
#include "raster/detail/scanline.hpp"
#include "raster/detail/window_raster.hpp"

namespace tw {
namespace {

constexpr int kBlockRows = 16;

double signed_area(const std::vector<Vec2>& ring) {
  double twice = 0.0;
  for (std::size_t i = 0; i < ring.size(); ++i)
    twice += cross(ring[i], ring[(i + 1) % ring.size()]);
  return twice / 2.0;
}

// Proper crossing point of segments ab and cd, if any.
std::optional<Vec2> crossing_point(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const Vec2 r = b - a, s = d - c;
  const double denom = cross(r, s);
  if (denom == 0.0) return std::nullopt;
  const double t = cross(c - a, s) / denom;
  const double u = cross(c - a, r) / denom;
  if (t <= 0.0 || t >= 1.0 || u <= 0.0 || u >= 1.0) return std::nullopt;
  return a + r * t;
}

// The inverted lobe of a bow-tie piece (left edge TL-BL crossed by right edge TR-BR): of the two
// triangles the quad falls into, the one whose orientation is opposite to a healthy piece's.
std::optional<std::vector<Vec2>> inverted_lobe(const Piece& piece) {
  const auto p =
      crossing_point(piece.top_left, piece.bottom_left, piece.top_right, piece.bottom_right);
  if (!p) return std::nullopt;
  // A healthy piece (TL, BL, BR, TR) is counter-clockwise: T is on the left of the curve.
  std::vector<Vec2> top_lobe{piece.top_left, *p, piece.top_right};
  std::vector<Vec2> bottom_lobe{*p, piece.bottom_left, piece.bottom_right};
  return signed_area(top_lobe) < 0.0 ? top_lobe : bottom_lobe;
}

}  // namespace

std::vector<Polygon> piece_polygons(const Ribbon& ribbon) {
  std::vector<Polygon> polygons;
  polygons.reserve(ribbon.pieces.size());
  for (const Piece& p : ribbon.pieces)
    polygons.push_back({{p.top_left, p.bottom_left, p.bottom_right, p.top_right}});
  return polygons;
}

Raster<std::uint8_t> foldover_mask(const Ribbon& ribbon, const GridSpec& grid,
                                   const Window& window) {
  detail::check_window(window, "foldover_mask");
  Raster<std::uint8_t> mask(window.width, window.height, 0);
  const auto n = std::uint32_t(ribbon.pieces.size());
  if (n == 0 || window.width == 0 || window.height == 0) return mask;

  // Per pixel: the lowest and highest piece covering it and how many pieces do. A set of pieces
  // holds a non-adjacent pair unless it is one piece or two neighbours.
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  const std::size_t cells = std::size_t(window.width) * window.height;
  std::vector<std::uint32_t> lowest(cells, kNone), highest(cells, 0);
  std::vector<std::uint16_t> count(cells, 0);

  detail::EdgeBuilder pieces(grid, 1.0, window);
  for (std::uint32_t i = 0; i < n; ++i) {
    const Piece& p = ribbon.pieces[i];
    const std::array<std::array<Vec2, 4>, 1> quad{
        {{p.top_left, p.bottom_left, p.bottom_right, p.top_right}}};
    if (!pieces.add_shape(quad, i))
      fail("foldover_mask: ribbon piece {} has a non-finite corner", i);
  }
  detail::scan_spans(pieces.edges, window.row0, window.row_end(), window.col0, window.col_end(),
                     kBlockRows, [&](int row, std::uint32_t piece, int c0, int c1) {
                       const std::size_t base = std::size_t(row - window.row0) * window.width;
                       for (int c = c0; c < c1; ++c) {
                         const std::size_t i = base + (c - window.col0);
                         lowest[i] = std::min(lowest[i], piece);
                         highest[i] = std::max(highest[i], piece);
                         if (count[i] < std::numeric_limits<std::uint16_t>::max()) ++count[i];
                       }
                     });
  const bool closed = ribbon.closed;
  for (std::size_t i = 0; i < cells; ++i) {
    if (count[i] < 2) continue;
    const bool neighbours =
        highest[i] - lowest[i] == 1 || (closed && lowest[i] == 0 && highest[i] == n - 1);
    if (count[i] > 2 || !neighbours) mask.pixels[i] = 1;
  }

  std::vector<Polygon> lobes;
  for (const Piece& piece : ribbon.pieces)
    if (auto lobe = inverted_lobe(piece)) lobes.push_back({std::move(*lobe)});
  if (!lobes.empty()) {
    detail::EdgeBuilder lobe_edges(grid, 1.0, window);
    for (std::size_t i = 0; i < lobes.size(); ++i) lobe_edges.add_shape(lobes[i], std::uint32_t(i));
    detail::scan_spans(lobe_edges.edges, window.row0, window.row_end(), window.col0,
                       window.col_end(), kBlockRows, [&](int row, std::uint32_t, int c0, int c1) {
                         std::uint8_t* line =
                             mask.pixels.data() + std::size_t(row - window.row0) * window.width;
                         std::fill(line + (c0 - window.col0), line + (c1 - window.col0), 1);
                       });
  }
  return mask;
}

void add_foldovers(const Ribbon& ribbon, const GridSpec& grid, SparseRaster<std::uint8_t>& mask) {
  for (const TileIndex t : mask.tiles()) {
    const Raster<std::uint8_t> folds = foldover_mask(ribbon, grid, mask.tile_window(t));
    Raster<std::uint8_t>& tile = *mask.tile(t);
    for (std::size_t i = 0; i < folds.pixels.size(); ++i) tile.pixels[i] |= folds.pixels[i];
  }
}

}  // namespace tw
