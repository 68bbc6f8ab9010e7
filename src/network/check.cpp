#include "network/check.hpp"

#include <fmt/format.h>
#include <ogr_geometry.h>

#include <cmath>
#include <memory>

#include "core/boost_geometry.hpp"
#include "network/detail/ogr_polygons.hpp"

namespace tw {

namespace {

using namespace geometry;

OGRLineString ogr_line(const std::vector<Vec2>& pts) {
  OGRLineString ls;
  for (Vec2 p : pts) ls.addPoint(p.x, p.y);
  return ls;
}

}  // namespace

NetworkCheck check_network(const Network& net, const std::vector<Polygon>& region,
                           const ForbiddenMask* forbidden) {
  NetworkCheck check;
  std::vector<OGRLineString> lines;
  bgi::rtree<std::pair<BgBox, int>, bgi::quadratic<16>> boxes;
  for (std::size_t i = 0; i < net.edges.size(); ++i) {
    lines.push_back(ogr_line(net.edges[i].points));
    OGREnvelope e;
    lines.back().getEnvelope(&e);
    boxes.insert({BgBox({e.MinX, e.MinY}, {e.MaxX, e.MaxY}), int(i)});
  }
  const auto note = [&](std::string what) {
    if (check.first.empty()) check.first = std::move(what);
  };
  std::vector<std::pair<BgBox, int>> near;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    near.clear();
    OGREnvelope e;
    lines[i].getEnvelope(&e);
    boxes.query(bgi::intersects(BgBox({e.MinX, e.MinY}, {e.MaxX, e.MaxY})),
                std::back_inserter(near));
    const NetworkEdge& a = net.edges[i];
    for (const auto& [box, j] : near) {
      if (j <= int(i)) continue;
      const NetworkEdge& b = net.edges[std::size_t(j)];
      if (!lines[i].Intersects(&lines[std::size_t(j)])) continue;
      std::unique_ptr<OGRGeometry> common(lines[i].Intersection(&lines[std::size_t(j)]));
      bool bad = false;
      const auto allowed = [&](double x, double y) {
        const Vec2 p{x, y};
        for (int na : {a.from, a.to})
          for (int nb : {b.from, b.to})
            if (na == nb && distance(p, net.nodes[std::size_t(na)]) < 1e-9 * (1.0 + length(p)))
              return true;
        return false;
      };
      if (!common || common->IsEmpty()) continue;
      const auto type = wkbFlatten(common->getGeometryType());
      if (type == wkbPoint)
        bad = !allowed(common->toPoint()->getX(), common->toPoint()->getY());
      else if (type == wkbMultiPoint) {
        for (const OGRPoint* p : *common->toMultiPoint())
          bad = bad || !allowed(p->getX(), p->getY());
      } else {
        bad = true;  // an overlap along a line
      }
      if (bad) {
        ++check.crossings;
        note(fmt::format("edges {} and {} cross", i, j));
      }
    }
  }
  if (!region.empty()) {
    const OGRMultiPolygon mp = detail::to_ogr(region);
    OGREnvelope env;
    mp.getEnvelope(&env);
    const double tolerance = 1e-6 * std::max({1.0, env.MaxX - env.MinX, env.MaxY - env.MinY});
    std::unique_ptr<OGRGeometry> grown(mp.Buffer(tolerance, 2));
    for (std::size_t i = 0; i < lines.size(); ++i)
      if (!grown->Contains(&lines[i])) {
        ++check.outside;
        note(fmt::format("edge {} leaves the region", i));
      }
  }
  if (forbidden) {
    const GridSpec& g = forbidden->grid;
    const double step = 0.25 * std::min(g.pixel_width, g.pixel_height);
    for (std::size_t i = 0; i < net.edges.size(); ++i) {
      const auto& pts = net.edges[i].points;
      bool hit = false;
      for (std::size_t k = 0; k + 1 < pts.size() && !hit; ++k) {
        const int n = std::max(1, int(std::ceil(distance(pts[k], pts[k + 1]) / step)));
        for (int s = 0; s <= n && !hit; ++s) {
          const Vec2 px = g.world_to_pixel(lerp(pts[k], pts[k + 1], double(s) / n));
          const int c = int(std::floor(px.x)), r = int(std::floor(px.y));
          hit = forbidden->cells.inside(c, r) && forbidden->cells.at(c, r) != 0;
        }
      }
      if (hit) {
        ++check.forbidden;
        note(fmt::format("edge {} enters a forbidden cell", i));
      }
    }
  }
  return check;
}

}  // namespace tw
