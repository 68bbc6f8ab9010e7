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

// Pairs of lines (i < j, in order) meeting where neither ends.
std::vector<std::pair<std::size_t, std::size_t>> crossing_lines(const NetworkLines& lines) {
  std::vector<OGRLineString> ogr;
  std::vector<OGREnvelope> envelopes(lines.lines.size());
  for (std::size_t i = 0; i < lines.lines.size(); ++i) {
    ogr.push_back(ogr_line(lines.lines[i]));
    ogr.back().getEnvelope(&envelopes[i]);
  }
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t i = 0; i < ogr.size(); ++i)
    for (std::size_t j = i + 1; j < ogr.size(); ++j) {
      if (!envelopes[i].Intersects(envelopes[j]) || !ogr[i].Intersects(&ogr[j])) continue;
      const auto& a = lines.lines[i];
      const auto& b = lines.lines[j];
      const std::unique_ptr<OGRGeometry> common(ogr[i].Intersection(&ogr[j]));
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
      if (bad) out.emplace_back(i, j);
    }
  return out;
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
  const std::vector<std::pair<std::size_t, std::size_t>> crossing = crossing_lines(lines);
  if (!crossing.empty())
    fail(
        "{} {}: FID {} crosses FID {} (a partial network may meet itself only where a line "
        "ends)",
        subject, source, lines.fids[crossing.front().first], lines.fids[crossing.front().second]);
  NetworkLines in = lines;
  in.region = region;
  Network net = build_planar_network(in, 0.0, subject, warnings);
  for (NetworkEdge& e : net.edges) e.kept = true;
  return net;
}

}  // namespace tw

namespace tw {

Network kept_map_network(const NetworkLines& lines, double snap_m, const std::string& subject,
                         Warnings& warnings) {
  for (const auto& [i, j] : crossing_lines(lines))
    warnings.add("crossing_lines", subject, lines.fids[i],
                 fmt::format("crosses FID {} where neither ends: noded into a junction there",
                             lines.fids[j]));
  Network net = build_planar_network(lines, snap_m, subject, warnings);
  for (NetworkEdge& e : net.edges) e.kept = true;
  return net;
}

}  // namespace tw
