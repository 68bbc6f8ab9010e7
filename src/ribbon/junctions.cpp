#include "ribbon/junctions.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <unordered_map>

#include "core/error.hpp"

namespace tw {
namespace {

struct Segment {
  std::size_t curve;
  std::size_t index;  // segment k runs from point k to point k + 1 (wrapping on closed curves)
  Vec2 a, b;
  double arc0;  // arc length at a
};

struct Candidate {
  Vec2 position;
  std::vector<JunctionMember> members;
};

// A uniform grid of segments: each is walked in steps of a cell, and each step's box, grown by
// `grow`, is added, so a long diagonal segment covers a band of cells, not the square of its
// bounding box.
class SegmentGrid {
 public:
  SegmentGrid(const std::vector<Segment>& segments, double cell, double grow) : cell_(cell) {
    for (std::uint32_t id = 0; id < segments.size(); ++id) {
      const Segment& s = segments[id];
      const double span = std::max(std::abs(s.b.x - s.a.x), std::abs(s.b.y - s.a.y));
      const int steps = int(std::min(1e7, std::max(1.0, std::ceil(span / cell))));
      for (int k = 0; k < steps; ++k) {
        const Vec2 p = lerp(s.a, s.b, double(k) / steps);
        const Vec2 q = lerp(s.a, s.b, double(k + 1) / steps);
        for (std::int64_t r = coord(std::min(p.y, q.y) - grow);
             r <= coord(std::max(p.y, q.y) + grow); ++r) {
          for (std::int64_t c = coord(std::min(p.x, q.x) - grow);
               c <= coord(std::max(p.x, q.x) + grow); ++c) {
            std::vector<std::uint32_t>& ids = cells_[key(c, r)];
            if (ids.empty() || ids.back() != id) ids.push_back(id);  // once per cell
          }
        }
      }
    }
  }
  std::int64_t coord(double v) const { return std::int64_t(std::floor(v / cell_)); }
  static std::int64_t key(std::int64_t c, std::int64_t r) {
    return std::int64_t((std::uint64_t(c) << 32) ^ (std::uint64_t(r) & 0xffffffffULL));
  }
  const std::unordered_map<std::int64_t, std::vector<std::uint32_t>>& cells() const {
    return cells_;
  }
  const std::vector<std::uint32_t>* at(Vec2 p) const {
    auto it = cells_.find(key(coord(p.x), coord(p.y)));
    return it == cells_.end() ? nullptr : &it->second;
  }

 private:
  double cell_;
  std::unordered_map<std::int64_t, std::vector<std::uint32_t>> cells_;
};

// The pairs of segments that share a cell of about one segment's length, sorted and unique:
// a cell holds a few segments even where vertices are far closer than the junction tolerance
// (cells of the tolerance's size held every segment of a 100 000-vertex line over 100 m,
// compared pair by pair: minutes). Boxes grow by a millionth of a cell, so two segments
// meeting on a cell border share a cell whatever the rounding.
std::vector<std::pair<std::uint32_t, std::uint32_t>> crossing_pairs(
    const std::vector<Segment>& segments, double total_length) {
  const double cell = std::max(total_length / double(segments.size()), 1e-6);
  const SegmentGrid grid(segments, cell, 1e-6 * cell);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const auto& [key, ids] : grid.cells())
    for (std::size_t i = 0; i < ids.size(); ++i)
      for (std::size_t j = i + 1; j < ids.size(); ++j) pairs.emplace_back(ids[i], ids[j]);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

double closest_parameter(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  return len2 > 0.0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
}

// Intersection parameters of segments ab and cd (touching included), if they meet at one point.
bool segment_intersection(Vec2 a, Vec2 b, Vec2 c, Vec2 d, double& t, double& u) {
  const Vec2 r = b - a, s = d - c;
  const double denom = cross(r, s);
  if (denom == 0.0) return false;  // parallel: overlaps are caught by the endpoint tests
  t = cross(c - a, s) / denom;
  u = cross(c - a, r) / denom;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}

struct UnionFind {
  std::vector<std::size_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

bool junction_precedes(const Junction& a, const Junction& b) {
  const auto& ma = a.members.front();
  const auto& mb = b.members.front();
  if (ma.curve != mb.curve) return ma.curve < mb.curve;
  if (ma.arc_length != mb.arc_length) return ma.arc_length < mb.arc_length;
  return a.position.x != b.position.x ? a.position.x < b.position.x : a.position.y < b.position.y;
}

std::vector<Junction> find_junctions(const std::vector<Curve>& curves, double tolerance_m) {
  std::vector<Extent> extents;
  return find_junctions(curves, tolerance_m, extents);
}

std::vector<Junction> find_junctions(const std::vector<Curve>& curves, double tolerance_m,
                                     std::vector<Extent>& extents) {
  extents.clear();
  if (!(tolerance_m >= 0.0) || !std::isfinite(tolerance_m))
    fail("find_junctions: tolerance {} m must be >= 0", tolerance_m);
  std::vector<Segment> segments;
  std::vector<double> lengths(curves.size(), 0.0);
  double total_length = 0.0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const auto& pts = curves[c].points;
    for (std::size_t i = 0; i < pts.size(); ++i)
      if (!is_finite(pts[i])) fail("curve {}: point {} is not finite", c, i);
    const auto cumulative = cumulative_lengths(curves[c]);
    if (pts.empty()) continue;
    lengths[c] = cumulative.back();
    total_length += lengths[c];
    const std::size_t count = curves[c].closed && pts.size() > 1 ? pts.size() : pts.size() - 1;
    for (std::size_t i = 0; i < count; ++i)
      segments.push_back({c, i, pts[i], pts[(i + 1) % pts.size()], cumulative[i]});
    if (pts.size() == 1) segments.push_back({c, 0, pts[0], pts[0], 0.0});
  }
  if (segments.empty()) return {};

  auto at_endpoint = [&](std::size_t c, double arc) {
    return !curves[c].closed && (arc <= tolerance_m || arc >= lengths[c] - tolerance_m);
  };
  // A member within the tolerance of an end is reported exactly at that end.
  auto member = [&](std::size_t c, double arc) {
    if (!at_endpoint(c, arc)) return JunctionMember{c, arc, false};
    return JunctionMember{c, arc <= tolerance_m ? 0.0 : lengths[c], true};
  };
  // Neighbouring segments of one curve always touch; they are not junctions.
  auto adjacent = [&](const Segment& s, const Segment& t) {
    if (s.curve != t.curve) return false;
    const std::size_t n = curves[s.curve].points.size();
    const std::size_t i = std::min(s.index, t.index), j = std::max(s.index, t.index);
    return j - i <= 1 || (curves[s.curve].closed && i == 0 && j == n - 1);
  };

  std::vector<Candidate> candidates;

  // Crossings (exact: touching included, no tolerance), each pair of segments tested once.
  for (const auto& [first, second] : crossing_pairs(segments, total_length)) {
    const Segment& s = segments[first];
    const Segment& t = segments[second];
    if (adjacent(s, t)) continue;
    double u, v;
    if (!segment_intersection(s.a, s.b, t.a, t.b, u, v)) continue;
    const double arc_s = s.arc0 + u * distance(s.a, s.b);
    const double arc_t = t.arc0 + v * distance(t.a, t.b);
    if (s.curve == t.curve && std::abs(arc_s - arc_t) <= tolerance_m) continue;
    candidates.push_back({lerp(s.a, s.b, u), {member(s.curve, arc_s), member(t.curve, arc_t)}});
  }
  // Endpoints of open curves near any other part of any curve (shared ends, T-junctions): in
  // cells of at least twice the tolerance holding the boxes grown by it, one cell per endpoint.
  const double cell = std::max({total_length / double(segments.size()), 2.0 * tolerance_m, 1e-6});
  const SegmentGrid grid(segments, cell, tolerance_m);
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (curves[c].closed || curves[c].points.empty()) continue;
    for (const bool last : {false, true}) {
      const Vec2 e = last ? curves[c].points.back() : curves[c].points.front();
      const double arc_e = last ? lengths[c] : 0.0;
      const auto* ids = grid.at(e);
      if (ids == nullptr) continue;
      struct Hit {
        std::size_t curve;
        double arc, gap;
      };
      std::vector<Hit> hits;
      for (const std::uint32_t id : *ids) {
        const Segment& s = segments[id];
        const double u = closest_parameter(e, s.a, s.b);
        const Vec2 q = lerp(s.a, s.b, u);
        if (distance(e, q) > tolerance_m) continue;
        const double arc_s = s.arc0 + u * distance(s.a, s.b);
        if (s.curve == c && std::abs(arc_s - arc_e) <= 2.0 * tolerance_m + 1e-9) continue;
        hits.push_back({s.curve, arc_s, distance(e, q)});
      }
      // One member per passage of a curve near the endpoint, at its closest point: where
      // vertices are denser than the tolerance, many segments of one passage are near it.
      std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) {
        return a.curve != b.curve ? a.curve < b.curve : a.arc < b.arc;
      });
      for (std::size_t first = 0; first < hits.size();) {
        std::size_t end = first + 1, closest = first;
        while (end < hits.size() && hits[end].curve == hits[first].curve &&
               hits[end].arc - hits[end - 1].arc <= tolerance_m) {
          if (hits[end].gap < hits[closest].gap) closest = end;
          ++end;
        }
        candidates.push_back(
            {e, {member(c, arc_e), member(hits[closest].curve, hits[closest].arc)}});
        first = end;
      }
    }
  }

  // The grid's hash order must not leak into the output: canonical order first.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    if (a.position.x != b.position.x) return a.position.x < b.position.x;
    if (a.position.y != b.position.y) return a.position.y < b.position.y;
    const auto key = [](const Candidate& c) {
      return std::tuple(c.members[0].curve, c.members[0].arc_length, c.members[1].curve,
                        c.members[1].arc_length);
    };
    return key(a) < key(b);
  });
  // Merge candidates closer than the tolerance: sweep in x.
  std::vector<std::size_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return candidates[a].position.x < candidates[b].position.x;
  });
  UnionFind groups(candidates.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    for (std::size_t j = i + 1; j < order.size(); ++j) {
      const Vec2 a = candidates[order[i]].position, b = candidates[order[j]].position;
      if (b.x - a.x > tolerance_m) break;
      if (distance(a, b) <= tolerance_m) groups.join(order[i], order[j]);
    }
  }
  std::vector<std::vector<std::size_t>> by_root(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) by_root[groups.find(i)].push_back(i);

  std::vector<std::pair<Junction, Extent>> junctions;
  for (const auto& ids : by_root) {
    if (ids.empty()) continue;
    Junction j;
    Extent extent;
    std::vector<JunctionMember> all;
    for (const std::size_t id : ids) {
      const Vec2 p = candidates[id].position;
      j.position += p;
      extent.min = {std::min(extent.min.x, p.x), std::min(extent.min.y, p.y)};
      extent.max = {std::max(extent.max.x, p.x), std::max(extent.max.y, p.y)};
      all.insert(all.end(), candidates[id].members.begin(), candidates[id].members.end());
    }
    j.position = j.position / double(ids.size());
    std::sort(all.begin(), all.end(), [](const JunctionMember& a, const JunctionMember& b) {
      return a.curve != b.curve ? a.curve < b.curve : a.arc_length < b.arc_length;
    });
    // One member per passage of a curve: same curve within the tolerance is the same place.
    for (const JunctionMember& m : all) {
      if (!j.members.empty() && j.members.back().curve == m.curve &&
          m.arc_length - j.members.back().arc_length <= tolerance_m) {
        j.members.back().at_endpoint = j.members.back().at_endpoint || m.at_endpoint;
        continue;
      }
      j.members.push_back(m);
    }
    if (j.members.size() < 2) continue;
    const auto through = std::count_if(j.members.begin(), j.members.end(),
                                       [](const JunctionMember& m) { return !m.at_endpoint; });
    j.crossing = through >= 2;
    junctions.emplace_back(std::move(j), extent);
  }
  std::sort(junctions.begin(), junctions.end(),
            [](const auto& a, const auto& b) { return junction_precedes(a.first, b.first); });
  std::vector<Junction> out;
  for (auto& [j, extent] : junctions) {
    out.push_back(std::move(j));
    extents.push_back(extent);
  }
  return out;
}

std::vector<Junction> at_grade(const std::vector<Junction>& junctions,
                               const std::vector<CurveLevel>& levels) {
  std::vector<Junction> out;
  for (const Junction& j : junctions) {
    std::vector<JunctionMember> members;
    for (const JunctionMember& m : j.members) {
      if (!m.at_endpoint && levels[m.curve].structure != Structure::ground) continue;
      members.push_back(m);
    }
    const bool all_end = std::all_of(members.begin(), members.end(),
                                     [](const JunctionMember& m) { return m.at_endpoint; });
    std::vector<std::vector<JunctionMember>> groups;
    if (all_end) {
      groups.push_back(std::move(members));
    } else {
      std::vector<int> layers;
      for (const JunctionMember& m : members) layers.push_back(levels[m.curve].layer);
      std::sort(layers.begin(), layers.end());
      layers.erase(std::unique(layers.begin(), layers.end()), layers.end());
      for (const int layer : layers) {
        auto& group = groups.emplace_back();
        for (const JunctionMember& m : members)
          if (levels[m.curve].layer == layer) group.push_back(m);
      }
    }
    for (auto& group : groups) {
      if (group.size() < 2) continue;
      Junction kept{j.position, std::move(group), false};
      kept.crossing = std::count_if(kept.members.begin(), kept.members.end(),
                                    [](const JunctionMember& m) { return !m.at_endpoint; }) >= 2;
      out.push_back(std::move(kept));
    }
  }
  return out;
}

}  // namespace tw
