#include "geo/detail/line_clipping.hpp"

#include <cmath>
#include <memory>
#include <optional>

#include "core/error.hpp"

namespace tw::detail {
namespace {

void check_finite(const std::vector<Vec2>& points, const OpenVectorLayer& layer, std::int64_t fid) {
  for (const Vec2& p : points) {
    if (!is_finite(p)) {
      fail("{}: FID {}: reprojection gave a non-finite coordinate", layer.label, fid);
    }
  }
}

ClippedLine whole_line(const OGRLineString& line) {
  ClippedLine result{curve_points(line), false};
  if (result.points.size() >= 4 && result.points.front() == result.points.back()) {
    result.points.pop_back();
    result.closed = true;
  }
  return result;
}

void collect_lines(const OGRGeometry& geometry, std::vector<std::vector<Vec2>>& pieces) {
  const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbLineString) {
    std::vector<Vec2> points = curve_points(*geometry.toLineString());
    if (points.size() >= 2) pieces.push_back(std::move(points));
  } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *geometry.toGeometryCollection()) collect_lines(*part, pieces);
  }
  // Points (where the line only touches the border) carry no length: dropped.
}

// GEOS splits a ring at its start vertex and may split a line where pieces meet; join every
// piece whose end is another's start.
void join_touching_pieces(std::vector<std::vector<Vec2>>& pieces) {
  bool joined = true;
  while (joined) {
    joined = false;
    for (std::size_t a = 0; a < pieces.size() && !joined; ++a) {
      for (std::size_t b = 0; b < pieces.size() && !joined; ++b) {
        if (a == b || pieces[a].back() != pieces[b].front()) continue;
        pieces[a].insert(pieces[a].end(), pieces[b].begin() + 1, pieces[b].end());
        pieces.erase(pieces.begin() + std::ptrdiff_t(b));
        joined = true;
      }
    }
  }
}

// The pieces of `line` inside `extent` (GEOS), those meeting at a vertex joined again.
std::vector<std::vector<Vec2>> pieces_inside(const OGRLineString& line, const OGRPolygon& extent,
                                             const OpenVectorLayer& layer, std::int64_t fid) {
  QuietGdalErrors quiet;
  std::unique_ptr<OGRGeometry> inside(line.Intersection(&extent));
  if (!inside) fail("{}: FID {}: cannot clip to the grid: {}", layer.label, fid, last_gdal_error());
  std::vector<std::vector<Vec2>> pieces;
  collect_lines(*inside, pieces);
  join_touching_pieces(pieces);
  return pieces;
}

}  // namespace

std::unique_ptr<OGRMultiLineString> cut_to_box(const OGRMultiLineString& parts,
                                               const OGREnvelope& box, const OpenVectorLayer& layer,
                                               std::int64_t fid) {
  auto result = std::make_unique<OGRMultiLineString>();
  std::optional<OGRPolygon> box_polygon;
  for (const OGRLineString* part : parts) {
    OGREnvelope part_box;
    part->getEnvelope(&part_box);
    if (box.Contains(part_box)) {
      result->addGeometry(part);
      continue;
    }
    if (!box.Intersects(part_box)) continue;
    if (!box_polygon) box_polygon = densified_box(box);
    for (const std::vector<Vec2>& piece : pieces_inside(*part, *box_polygon, layer, fid)) {
      OGRLineString line;
      for (const Vec2& p : piece) line.addPoint(p.x, p.y);
      result->addGeometry(&line);
    }
  }
  return result;
}

std::vector<ClippedLine> clip_line(const OGRLineString& line, const OGRPolygon& extent,
                                   const OpenVectorLayer& layer, std::int64_t fid) {
  std::vector<ClippedLine> result;
  OGREnvelope line_box;
  OGREnvelope extent_box;
  line.getEnvelope(&line_box);
  extent.getEnvelope(&extent_box);
  if (extent_box.Contains(line_box)) {
    result.push_back(whole_line(line));
    check_finite(result.back().points, layer, fid);
    return result;
  }
  if (!extent_box.Intersects(line_box)) return result;

  for (std::vector<Vec2>& piece : pieces_inside(line, extent, layer, fid)) {
    check_finite(piece, layer, fid);
    const bool closed = piece.size() >= 4 && piece.front() == piece.back();
    if (closed) piece.pop_back();
    result.push_back({std::move(piece), closed});
  }
  return result;
}

}  // namespace tw::detail
