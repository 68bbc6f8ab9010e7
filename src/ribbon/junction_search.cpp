#include "ribbon/junction_search.hpp"

#include <algorithm>

namespace tw {
namespace {

Extent box_of(const Curve& curve) {
  Extent box;
  for (const Vec2 p : curve.points) {
    box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y)};
    box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y)};
  }
  return box;
}

Extent grown(Extent box, double by) {
  box.min = box.min - Vec2{by, by};
  box.max = box.max + Vec2{by, by};
  return box;
}

bool meets_any(const Extent& box, const std::vector<Extent>& boxes) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const Extent& other) {
    return box.min.x <= other.max.x && other.min.x <= box.max.x && box.min.y <= other.max.y &&
           other.min.y <= box.max.y;
  });
}

}  // namespace

JunctionSearch search_junctions(const std::vector<Curve>& curves, double tolerance_m) {
  JunctionSearch search;
  search.tolerance_m = tolerance_m;
  search.junctions = find_junctions(curves, tolerance_m, search.extents);
  for (const Curve& curve : curves) search.boxes.push_back(box_of(curve));
  search.curves_searched = curves.size();
  return search;
}

// Why this equals a whole search: find_junctions merges meeting points ("candidates", each of
// one or two curves) closer than the tolerance t into one junction. A changed curve's candidates,
// before and after, lie within t of its box (`reach`). A junction of no changed curve whose
// extent, grown by t, misses `reach` had no neighbour among them and has none now: it is kept.
// Every other junction of the new curves has a candidate in `region` (reach and the dropped
// junctions' extents), whose curves lie within t of it, so within 4 t of the curves searched;
// a junction found there is whole unless a candidate of a curve left out lies within t of one
// of its own, which a curve left out 2 t from its extent cannot have. Kept junctions meet no
// part of the region (dropped until none does), so none is found twice.
JunctionSearch update_junctions(const JunctionSearch& previous, const std::vector<Curve>& curves,
                                const std::vector<bool>& changed) {
  if (previous.boxes.size() != curves.size() || changed.size() != curves.size() ||
      previous.extents.size() != previous.junctions.size())
    return search_junctions(curves, previous.tolerance_m);
  JunctionSearch out;
  out.tolerance_m = previous.tolerance_m;
  // The margins take a micrometre more than the tolerance: a meeting point computed on a segment
  // may lie a rounding error outside the box of the curve's points.
  const double t = previous.tolerance_m + 1e-6;
  for (const Curve& curve : curves) out.boxes.push_back(box_of(curve));
  std::vector<Extent> reach;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (!changed[i]) continue;
    // A point that is not finite has no box: the whole search names it, as without a cache.
    if (!std::all_of(curves[i].points.begin(), curves[i].points.end(), is_finite))
      return search_junctions(curves, out.tolerance_m);
    reach.push_back(grown(previous.boxes[i], t));
    reach.push_back(grown(out.boxes[i], t));
  }
  const auto& old = previous.junctions;
  std::vector<bool> dropped(old.size(), false);
  std::vector<Extent> region = reach;
  for (std::size_t j = 0; j < old.size(); ++j) {
    const bool of_changed = std::any_of(old[j].members.begin(), old[j].members.end(),
                                        [&](const JunctionMember& m) { return changed[m.curve]; });
    if (of_changed || meets_any(grown(previous.extents[j], t), reach)) {
      dropped[j] = true;
      region.push_back(previous.extents[j]);
    }
  }
  for (bool more = true; more;) {
    more = false;
    for (std::size_t j = 0; j < old.size(); ++j) {
      if (dropped[j] || !meets_any(previous.extents[j], region)) continue;
      dropped[j] = more = true;
      region.push_back(previous.extents[j]);
    }
  }
  std::vector<std::size_t> searched;
  std::vector<Curve> near;
  std::vector<Extent> left_out;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (meets_any(grown(out.boxes[i], 4.0 * t), region)) {
      searched.push_back(i);
      near.push_back(curves[i]);
    } else {
      left_out.push_back(out.boxes[i]);
    }
  }
  if (2 * searched.size() > curves.size()) return search_junctions(curves, out.tolerance_m);

  std::vector<std::pair<Junction, Extent>> found;
  for (std::size_t j = 0; j < old.size(); ++j)
    if (!dropped[j]) found.emplace_back(old[j], previous.extents[j]);
  out.curves_searched = searched.size();
  std::vector<Extent> near_extents;
  std::vector<Junction> near_junctions = find_junctions(near, out.tolerance_m, near_extents);
  for (std::size_t j = 0; j < near_junctions.size(); ++j) {
    if (!meets_any(near_extents[j], region)) continue;  // kept above, or far from the change
    if (meets_any(grown(near_extents[j], 2.0 * t), left_out))
      return search_junctions(curves, out.tolerance_m);
    for (JunctionMember& m : near_junctions[j].members) m.curve = searched[m.curve];
    found.emplace_back(std::move(near_junctions[j]), near_extents[j]);
  }
  std::sort(found.begin(), found.end(),
            [](const auto& a, const auto& b) { return junction_precedes(a.first, b.first); });
  for (auto& [junction, extent] : found) {
    out.junctions.push_back(std::move(junction));
    out.extents.push_back(extent);
  }
  return out;
}

}  // namespace tw
