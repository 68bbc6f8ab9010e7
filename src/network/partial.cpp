#include "network/partial.hpp"

#include <ogr_geometry.h>

#include <memory>

#include "core/error.hpp"
#include "network/check.hpp"

namespace tw {

namespace {

OGRLineString ogr_line(const std::vector<Vec2>& points) {
  OGRLineString line;
  for (Vec2 p : points) line.addPoint(p.x, p.y);
  return line;
}

}  // namespace

Network partial_network(const NetworkLines& lines, const std::vector<Polygon>& region,
                        const std::string& subject, const std::string& source, Warnings& warnings) {
  Network drawn;  // each line one edge, as drawn
  for (std::size_t i = 0; i < lines.lines.size(); ++i) {
    NetworkEdge e;
    e.from = int(drawn.nodes.size());
    drawn.nodes.push_back(lines.lines[i].front());
    e.to = int(drawn.nodes.size());
    drawn.nodes.push_back(lines.lines[i].back());
    e.points = lines.lines[i];
    e.fid = lines.fids[i];
    drawn.edges.push_back(std::move(e));
  }
  const NetworkCheck outside = check_network(drawn, region, nullptr);
  if (outside.outside > 0)
    for (const NetworkEdge& e : drawn.edges)
      if (check_network({{e.points.front(), e.points.back()}, {{0, 1, e.points, false, e.fid}}, {}},
                        region, nullptr)
              .outside > 0)
        fail("{} {}: FID {}: outside the region", subject, source, e.fid);
  // A line crossing itself (a loop closed at its own end is no crossing).
  for (const NetworkEdge& e : drawn.edges)
    if (!ogr_line(e.points).IsSimple())
      fail(
          "{} {}: FID {} crosses itself (a partial network may meet itself only where a line "
          "ends)",
          subject, source, e.fid);
  // Crossings: two lines meeting where neither ends.
  for (std::size_t i = 0; i < drawn.edges.size(); ++i)
    for (std::size_t j = i + 1; j < drawn.edges.size(); ++j) {
      const auto& a = drawn.edges[i].points;
      const auto& b = drawn.edges[j].points;
      const OGRLineString la = ogr_line(a), lb = ogr_line(b);
      if (!la.Intersects(&lb)) continue;
      const std::unique_ptr<OGRGeometry> common(la.Intersection(&lb));
      const auto at_an_end = [&](double x, double y) {
        const Vec2 p{x, y};
        for (Vec2 q : {a.front(), a.back(), b.front(), b.back()})
          if (distance(p, q) < 1e-9 * (1.0 + length(p))) return true;
        return false;
      };
      bool bad = false;
      const auto type = wkbFlatten(common->getGeometryType());
      if (type == wkbPoint)
        bad = !at_an_end(common->toPoint()->getX(), common->toPoint()->getY());
      else if (type == wkbMultiPoint)
        for (const OGRPoint* p : *common->toMultiPoint())
          bad = bad || !at_an_end(p->getX(), p->getY());
      else
        bad = !common->IsEmpty();
      if (bad)
        fail(
            "{} {}: FID {} crosses FID {} (a partial network may meet itself only where a line "
            "ends)",
            subject, source, drawn.edges[i].fid, drawn.edges[j].fid);
    }
  NetworkLines in = lines;
  in.region = region;
  Network net = build_planar_network(in, 0.0, subject, warnings);
  for (NetworkEdge& e : net.edges) e.kept = true;
  return net;
}

}  // namespace tw
