#include "network/detail/cell_cycles.hpp"

#include <ogr_geometry.h>

#include <algorithm>
#include <array>
#include <map>
#include <memory>

#include "core/boost_geometry.hpp"

namespace tw::network_detail {

// Why cycles of directed edges reproduce polygonize (GEOS 3.11's Polygonizer, which OGR's
// Polygonize calls): it makes two directed edges of each line in the order the lines come (along
// its points, then against), deletes dangles and cut edges, and finds the rings from the first
// directed edge not yet in one, in that order: each ring starts at its least directed edge, the
// rings come in the order of their least directed edges (shells and holes alike), and a ring's
// points are its directed edges' points, a point equal to the one before left out. A cell is a
// shell; splitting it by a chord between two of its nodes or joining two cells across the line
// between them changes only their cycles, and an inserted node only the cycles through its edge.

namespace {

// Where a directed edge leaves its node: its first point and the next one different from it.
std::array<double, 4> cycle_step_key(Vec2 a, Vec2 b) {
  return {a.x, a.y, b.x, b.y};
}

// A directed edge's points in its direction.
template <class F>
void for_each_point_of(const NetworkEdge& e, bool against, F&& f) {
  if (against)
    for (auto it = e.points.rbegin(); it != e.points.rend(); ++it) f(*it);
  else
    for (Vec2 p : e.points) f(p);
}

}  // namespace

int CellCycles::end_node(int de) const {
  const NetworkEdge& e = network_.edges[std::size_t(de / 2)];
  return de % 2 ? e.from : e.to;
}

// The ring as polygonize writes it from the cycle (rotated to start at its least directed
// edge), its box and OGR's area of it.
void CellCycles::write_rings(Cell& cell) const {
  std::rotate(cell.cycle.begin(), std::min_element(cell.cycle.begin(), cell.cycle.end()),
              cell.cycle.end());
  std::vector<Vec2> ring;
  for (int de : cell.cycle)
    for_each_point_of(network_.edges[std::size_t(de / 2)], de % 2, [&](Vec2 p) {
      if (ring.empty() || !(ring.back() == p)) ring.push_back(p);
    });
  OGRLinearRing r;
  r.setNumPoints(int(ring.size()), FALSE);
  for (std::size_t k = 0; k < ring.size(); ++k) r.setPoint(int(k), ring[k].x, ring[k].y);
  cell.area = r.get_Area();
  cell.lo = cell.hi = ring[0];
  for (Vec2 p : ring)
    cell.lo = {std::min(cell.lo.x, p.x), std::min(cell.lo.y, p.y)},
    cell.hi = {std::max(cell.hi.x, p.x), std::max(cell.hi.y, p.y)};
  cell.rings.assign(1, std::move(ring));
}

int CellCycles::new_cell() {
  if (!free_.empty()) {
    const int s = free_.back();
    free_.pop_back();
    live_[std::size_t(s)] = 1;
    holed_[std::size_t(s)] = dirty_[std::size_t(s)] = 0;
    return s;
  }
  store_.emplace_back();
  live_.push_back(1);
  holed_.push_back(0);
  dirty_.push_back(0);
  return int(store_.size()) - 1;
}

void CellCycles::own(int cell) {
  for (int de : store_[std::size_t(cell)].cycle) owner_[std::size_t(de)] = cell;
  dirty_[std::size_t(cell)] = 1;
}

void CellCycles::find_all() {
  store_.clear();
  live_.clear();
  free_.clear();
  holed_.clear();
  dirty_.clear();
  owner_.assign(2 * network_.edges.size(), -1);
  known_edges_ = network_.edges.size();
  found_ = false;

  OGRMultiLineString all;
  for (std::size_t i = 0; i < network_.edges.size(); ++i) {
    if (!alive_[i]) continue;
    OGRLineString ls;
    for (Vec2 p : network_.edges[i].points) ls.addPoint(p.x, p.y);
    all.addGeometry(&ls);
  }
  const std::unique_ptr<OGRGeometry> faces(all.Polygonize());

  // Each directed edge by its first step (a ring's step onto the next directed edge).
  std::map<std::array<double, 4>, int> by_step;
  if (incremental_)
    for (std::size_t i = 0; i < network_.edges.size() && incremental_; ++i) {
      if (!alive_[i]) continue;
      const std::vector<Vec2>& pts = network_.edges[i].points;
      const auto ahead =
          std::find_if(pts.begin(), pts.end(), [&](Vec2 p) { return !(p == pts[0]); });
      if (ahead == pts.end()) continue;  // a point: polygonize leaves it out
      const auto back =
          std::find_if(pts.rbegin(), pts.rend(), [&](Vec2 p) { return !(p == pts.back()); });
      incremental_ = by_step.emplace(cycle_step_key(pts[0], *ahead), int(2 * i)).second &&
                     by_step.emplace(cycle_step_key(pts.back(), *back), int(2 * i + 1)).second;
    }
  const auto cycle_from = [&](const std::vector<Vec2>& ring, std::vector<int>& cycle) {
    std::size_t at = 0;
    while (at + 1 < ring.size()) {
      const auto it = by_step.find(cycle_step_key(ring[at], ring[at + 1]));
      if (it == by_step.end() || cycle.size() >= ring.size()) return false;
      const int de = it->second;
      if (!cycle.empty() &&
          end_node(cycle.back()) != (de % 2 ? network_.edges[std::size_t(de / 2)].to
                                            : network_.edges[std::size_t(de / 2)].from))
        return false;
      bool same = true;
      for_each_point_of(network_.edges[std::size_t(de / 2)], de % 2, [&](Vec2 p) {
        if (!same || p == ring[at]) return;
        same = ++at < ring.size() && ring[at] == p;
      });
      if (!same) return false;
      cycle.push_back(de);
    }
    return !cycle.empty() && at + 1 == ring.size() &&
           std::min_element(cycle.begin(), cycle.end()) == cycle.begin() &&
           end_node(cycle.back()) == (cycle[0] % 2
                                          ? network_.edges[std::size_t(cycle[0] / 2)].to
                                          : network_.edges[std::size_t(cycle[0] / 2)].from);
  };

  if (!faces) return;
  int previous = -1;
  for (const OGRGeometry* g : *faces->toGeometryCollection()) {
    if (wkbFlatten(g->getGeometryType()) != wkbPolygon) continue;
    const OGRPolygon* polygon = g->toPolygon();
    Cell cell;
    cell.area = polygon->get_Area();
    for (const OGRLinearRing* r : *polygon) {
      std::vector<Vec2> ring;
      for (const OGRPoint& p : *r) ring.push_back({p.getX(), p.getY()});
      cell.rings.push_back(std::move(ring));
    }
    if (cell.rings.empty() || cell.rings[0].size() < 4) {
      incremental_ = false;  // not a ring of directed edges
      continue;
    }
    cell.lo = cell.hi = cell.rings[0][0];
    for (Vec2 p : cell.rings[0])
      cell.lo = {std::min(cell.lo.x, p.x), std::min(cell.lo.y, p.y)},
      cell.hi = {std::max(cell.hi.x, p.x), std::max(cell.hi.y, p.y)};
    const int s = new_cell();
    if (incremental_) {
      std::vector<std::vector<int>> cycles(cell.rings.size());
      for (std::size_t k = 0; k < cell.rings.size() && incremental_; ++k)
        incremental_ = cycle_from(cell.rings[k], cycles[k]);
      // The rings must come in the order of their least directed edges.
      incremental_ = incremental_ && cycles[0][0] > previous;
      if (incremental_) {
        previous = cycles[0][0];
        for (std::size_t k = 0; k < cycles.size(); ++k)
          for (int de : cycles[k]) owner_[std::size_t(de)] = s;
        cell.cycle = std::move(cycles[0]);
        holed_[std::size_t(s)] = cell.rings.size() > 1;
      }
    }
    store_[std::size_t(s)] = std::move(cell);
  }
  found_ = incremental_;
}

std::vector<const CellCycles::Cell*> CellCycles::cells() {
  if (!found_ || network_.edges.size() != known_edges_) find_all();
  std::vector<std::pair<int, int>> order;  // (least directed edge, slot)
  for (std::size_t s = 0; s < store_.size(); ++s) {
    if (!live_[s]) continue;
    if (dirty_[s]) write_rings(store_[s]), dirty_[s] = 0;
    order.emplace_back(found_ ? store_[s].cycle[0] : int(s), int(s));
  }
  std::sort(order.begin(), order.end());
  std::vector<const Cell*> out;
  out.reserve(order.size());
  for (const auto& [key, s] : order) out.push_back(&store_[std::size_t(s)]);
  return out;
}

void CellCycles::edge_split(int id, int second) {
  if (!found_) return;
  if (std::size_t(second) != known_edges_) {
    found_ = false;
    return;
  }
  owner_.resize(2 * ++known_edges_, -1);
  for (int along = 0; along < 2; ++along) {
    const int s = owner_[std::size_t(2 * id + along)];
    if (s < 0) continue;
    if (holed_[std::size_t(s)]) {
      found_ = false;
      return;
    }
    // Along: from, the new node (id), the old end (second); against: the old end (second), the
    // new node, from (id).
    std::vector<int>& cycle = store_[std::size_t(s)].cycle;
    const auto at = std::find(cycle.begin(), cycle.end(), 2 * id + along);
    cycle.insert(along ? at : at + 1, 2 * second + along);
    owner_[std::size_t(2 * second + along)] = s;
    dirty_[std::size_t(s)] = 1;
  }
}

// Cell `cell`, whose cycle passes each end of the chord once, becomes the part from the chord's
// start to its end and back along it; a new cell the rest.
bool CellCycles::split_by_chord(int cell, int chord) {
  const NetworkEdge& e = network_.edges[std::size_t(chord)];
  const std::vector<int> cycle = store_[std::size_t(cell)].cycle;
  const std::size_t n = cycle.size();
  std::size_t at_from = n, at_to = n;
  for (std::size_t k = 0; k < n; ++k) {
    const int node = end_node(cycle[k]);
    if (node == e.from) {
      if (at_from != n) return false;
      at_from = k;
    }
    if (node == e.to) {
      if (at_to != n) return false;
      at_to = k;
    }
  }
  if (at_from == n || at_to == n) return false;
  const auto part = [&](std::size_t after, std::size_t last, int closing) {
    std::vector<int> out;
    for (std::size_t k = (after + 1) % n;; k = (k + 1) % n) {
      out.push_back(cycle[k]);
      if (k == last) break;
    }
    out.push_back(closing);
    return out;
  };
  store_[std::size_t(cell)].cycle = part(at_from, at_to, 2 * chord + 1);
  const int other = new_cell();
  store_[std::size_t(other)].cycle = part(at_to, at_from, 2 * chord);
  own(cell);
  own(other);
  return true;
}

void CellCycles::chord_added(int id) {
  if (!found_) return;
  if (std::size_t(id) != known_edges_) {
    found_ = false;
    return;
  }
  owner_.resize(2 * ++known_edges_, -1);
  const NetworkEdge& e = network_.edges[std::size_t(id)];
  // The cells through both of its ends, and among them the one that holds it.
  const auto cells_at = [&](int node) {
    std::vector<int> out;
    for (int f : incident_[std::size_t(node)])
      if (f != id && alive_[std::size_t(f)])
        for (int along = 0; along < 2; ++along)
          if (const int s = owner_[std::size_t(2 * f + along)]; s >= 0) out.push_back(s);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  };
  const std::vector<int> at_from = cells_at(e.from), at_to = cells_at(e.to);
  std::vector<int> both;
  std::set_intersection(at_from.begin(), at_from.end(), at_to.begin(), at_to.end(),
                        std::back_inserter(both));
  std::size_t best = 0;
  for (std::size_t k = 1; k + 1 < e.points.size(); ++k)
    if (distance(e.points[k], e.points[k + 1]) > distance(e.points[best], e.points[best + 1]))
      best = k;
  const Vec2 probe = lerp(e.points[best], e.points[best + 1], 0.5);
  int holder = -1;
  for (int s : both) {
    if (holed_[std::size_t(s)]) continue;
    Cell& cell = store_[std::size_t(s)];
    if (dirty_[std::size_t(s)]) write_rings(cell), dirty_[std::size_t(s)] = 0;
    geometry::BgPolygon polygon;
    for (Vec2 p : cell.rings[0]) polygon.outer().push_back(geometry::to_bg(p));
    geometry::bg::correct(polygon);
    if (!geometry::bg::within(geometry::to_bg(probe), polygon)) continue;
    if (holder >= 0) holder = -2;
    if (holder == -1) holder = s;
  }
  if (holder < 0 || !split_by_chord(holder, id)) found_ = false;
}

void CellCycles::line_taken_off(const std::vector<int>& edges) {
  if (!found_ || edges.empty()) return;
  const int a = owner_[std::size_t(2 * edges[0])], b = owner_[std::size_t(2 * edges[0] + 1)];
  bool followed = a >= 0 && b >= 0 && a != b && !holed_[std::size_t(a)] && !holed_[std::size_t(b)];
  for (std::size_t k = 0; k < edges.size() && followed; ++k) {
    const int x = owner_[std::size_t(2 * edges[k])], y = owner_[std::size_t(2 * edges[k] + 1)];
    followed = (x == a && y == b) || (x == b && y == a);
  }
  // Each cell's cycle without the line's run of directed edges, from its end on.
  const auto rest = [&](int cell, std::vector<int>& out) {
    const std::vector<int>& cycle = store_[std::size_t(cell)].cycle;
    const std::size_t n = cycle.size();
    const auto on_line = [&](int de) {
      return std::find(edges.begin(), edges.end(), de / 2) != edges.end();
    };
    std::size_t run_ends = n, off = 0;
    for (std::size_t k = 0; k < n; ++k) {
      if (on_line(cycle[k])) continue;
      ++off;
      if (on_line(cycle[(k + n - 1) % n])) {
        if (run_ends != n) return false;  // the line in two runs
        run_ends = k;
      }
    }
    if (run_ends == n || off + edges.size() != n) return false;
    for (std::size_t k = 0; k < off; ++k) out.push_back(cycle[(run_ends + k) % n]);
    return true;
  };
  std::vector<int> merged;
  followed = followed && rest(a, merged) && rest(b, merged);
  if (followed) {  // a ring that passes an edge or a node twice is not one polygonize writes
    std::vector<int> lines, nodes;
    for (int de : merged) lines.push_back(de / 2), nodes.push_back(end_node(de));
    std::sort(lines.begin(), lines.end());
    std::sort(nodes.begin(), nodes.end());
    followed = std::adjacent_find(lines.begin(), lines.end()) == lines.end() &&
               std::adjacent_find(nodes.begin(), nodes.end()) == nodes.end();
  }
  if (!followed) {
    found_ = false;
    return;
  }
  for (int e : edges) owner_[std::size_t(2 * e)] = owner_[std::size_t(2 * e + 1)] = -1;
  store_[std::size_t(a)].cycle = std::move(merged);
  own(a);
  live_[std::size_t(b)] = 0;
  store_[std::size_t(b)] = Cell{};
  free_.push_back(b);
}

}  // namespace tw::network_detail
