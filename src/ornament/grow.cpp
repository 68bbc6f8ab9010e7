#include "ornament/grow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <queue>

#include "core/error.hpp"
#include "ornament/segment_index.hpp"
#include "ornament/trace.hpp"

namespace tw {

namespace {

// SplitMix64: the same draws on every platform (std distributions are not portable).
std::uint64_t mix(std::uint64_t a, std::uint64_t b, std::uint64_t c) {
  std::uint64_t z = a * 0x9E3779B97F4A7C15ull ^ (b + 0xBF58476D1CE4E5B9ull) * 0x94D049BB133111EBull;
  z += c * 0xD6E8FEB86659FD93ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
double unit_draw(std::uint64_t h) {
  return double(h >> 11) * 0x1.0p-53;
}

struct QueuedGrowth {
  int priority = 0;
  std::uint64_t order = 0;  // first in, first out among equal priorities
  SurfaceFrame frame;
  std::string tag;
  int ornament = 0;
  bool seed = false;  // an ornament's first element
  bool operator<(const QueuedGrowth& o) const {
    return priority != o.priority ? priority < o.priority : order > o.order;
  }
};

struct Candidate {
  const DecorativeElement* element = nullptr;
  TracedElement traced;
  std::vector<std::vector<Vec2>> polylines;
  double score = 0.0;
};

class Grower {
 public:
  Grower(const TerrainSurface& surface, const Raster<std::uint8_t>& allowed, const ElementSet& set,
         const GrowthParams& params, const KeepOff& keep_off)
      : surface_(surface),
        allowed_(allowed),
        set_(set),
        params_(params),
        keep_off_(keep_off),
        index_(std::max({set.clearance_m, 2.0 * surface.grid().pixel_width, 1e-3})) {
    const int n = surface.vertex_count(), w = surface.window().width, h = surface.window().height;
    // Forbidden ground and the window's border (a walk cannot leave the window) as seen from
    // each vertex: the score of an ornament's first element, and where new ornaments start.
    std::vector<SurfacePoint> blocked;
    for (int v = 0; v < n; ++v) {
      const int i = v % w, j = v / w;
      if (!allowed.at(i, j) || i == 0 || j == 0 || i == w - 1 || j == h - 1) {
        blocked.push_back(surface.vertex_point(v));
      }
    }
    to_blocked_ = surface.heat_distances(blocked);
    to_placed_.assign(std::size_t(n), std::numeric_limits<double>::infinity());
    dead_.assign(std::size_t(n), 0);
  }

  GrowthResult run() {
    const double min_seed = params_.min_seed_distance_m > 0.0
                                ? params_.min_seed_distance_m
                                : std::max(2.0 * set_.clearance_m, 0.5 * set_.scale_m);
    for (int attempt = 0;
         result_.ornaments < params_.max_ornaments && attempt < 4 * params_.max_ornaments &&
         result_.elements < params_.max_elements;
         ++attempt) {
      const int seed = farthest_vertex();
      if (seed < 0 || reach(seed) < min_seed) break;
      const int before = result_.elements;
      queue_.push(seed_growth(seed, result_.ornaments));
      while (!queue_.empty() && result_.elements < params_.max_elements) {
        const QueuedGrowth g = queue_.top();
        queue_.pop();
        grow_from(g);
      }
      if (result_.elements > before) {
        ++result_.ornaments;
      } else {
        bury(seed, min_seed / 2);  // nothing fits here: do not try this spot again
      }
    }
    return std::move(result_);
  }

 private:
  double reach(int v) const { return std::min(to_placed_[v], to_blocked_[v]); }

  int farthest_vertex() const {
    int best = -1;
    double best_reach = -1.0;
    const int w = surface_.window().width;
    for (int v = 0; v < surface_.vertex_count(); ++v) {
      if (!allowed_.at(v % w, v / w) || dead_[v]) continue;
      if (reach(v) > best_reach) {
        best = v;
        best_reach = reach(v);
      }
    }
    return best;
  }

  void bury(int v, double radius) {
    const int w = surface_.window().width, n = surface_.vertex_count();
    const double px = surface_.grid().pixel_width;
    const int r = int(std::ceil(radius / px));
    for (int j = v / w - r; j <= v / w + r; ++j) {
      for (int i = v % w - r; i <= v % w + r; ++i) {
        const int u = j * w + i;
        if (i >= 0 && i < w && u >= 0 && u < n) dead_[u] = 1;
      }
    }
  }

  QueuedGrowth seed_growth(int vertex, int ornament) {
    const SurfacePoint origin = surface_.vertex_point(vertex);
    const double angle =
        2.0 * std::numbers::pi * unit_draw(mix(params_.seed, 0x5eed, std::uint64_t(vertex)));
    Vec2 heading{std::cos(angle), std::sin(angle)};
    if (params_.alignment == OrnamentAlignment::contour) {
      const Vec2 c = surface_.contour_direction(origin);
      if (length(c) > 0.0) heading = dot(c, heading) < 0.0 ? -c : c;
    }
    return {std::numeric_limits<int>::max(),
            order_++,
            {origin, heading},
            set_.seed_tag,
            ornament,
            true};
  }

  SurfaceFrame aligned(const SurfaceFrame& growth) const {
    if (params_.alignment != OrnamentAlignment::contour) return growth;
    const Vec2 c = surface_.contour_direction(growth.origin);
    if (length(c) == 0.0) return growth;
    return {growth.origin, dot(c, growth.heading) < 0.0 ? -c : c};
  }

  double score(const TracedElement& traced) const {
    double sum = 0.0;
    int count = 0;
    for (const SurfaceCurve& curve : traced.curves) {
      for (const SurfacePoint& p : curve.points) {
        // The paper's D, with forbidden ground and the window's edge counted as placed: in a
        // bounded region the farthest candidate would otherwise run into the edge and die.
        sum += std::min(surface_.interpolate(to_placed_, p), surface_.interpolate(to_blocked_, p));
        ++count;
      }
    }
    return sum / std::max(count, 1);
  }

  bool forbidden(const std::vector<Vec2>& line) const {
    const ForbiddenCells* cells = keep_off_.cells;
    for (std::size_t k = 0; k + 1 < line.size(); ++k) {
      if (enters_forbidden(surface_.grid(), surface_.window(), allowed_, line[k], line[k + 1]))
        return true;
      if (cells &&
          enters_forbidden(cells->grid, cells->window, cells->allowed, line[k], line[k + 1]))
        return true;
    }
    return false;
  }

  void grow_from(const QueuedGrowth& g) {
    const std::vector<int> elements = elements_with_tag(set_, g.tag);
    const Vec2 joint = surface_.world(g.frame.origin);
    std::optional<Candidate> best;
    for (int trial = 0; trial < params_.trials; ++trial) {
      const std::uint64_t h = mix(params_.seed, g.order, std::uint64_t(trial));
      SurfaceFrame frame = g.frame;
      if (g.seed && params_.alignment == OrnamentAlignment::growth) {
        // A new ornament may start in any direction; each candidate draws its own.
        const double angle = 2.0 * std::numbers::pi * unit_draw(mix(h, 3, 0));
        frame.heading = {std::cos(angle), std::sin(angle)};
      }
      frame = aligned(frame);
      const DecorativeElement& e = set_.elements[std::size_t(elements[h % elements.size()])];
      const double size = e.sizes[mix(h, 1, 0) % e.sizes.size()];
      const double rotation = (2.0 * unit_draw(mix(h, 2, 0)) - 1.0) * e.rotation_jitter;
      auto traced = trace_element(surface_, e, frame, set_.scale_m * size, rotation,
                                  params_.subdivision_depth);
      if (!traced) {
        ++result_.rejected_untraceable;
        continue;
      }
      Candidate c{&e, std::move(*traced), {}, 0.0};
      for (const SurfaceCurve& curve : c.traced.curves) {
        auto& line = c.polylines.emplace_back();
        for (const SurfacePoint& p : curve.points) line.push_back(surface_.world(p));
      }
      if (std::any_of(c.polylines.begin(), c.polylines.end(),
                      [&](const auto& l) { return forbidden(l); })) {
        ++result_.rejected_forbidden;
        continue;
      }
      if (keep_off_.footprints &&
          std::any_of(c.polylines.begin(), c.polylines.end(), [&](const auto& l) {
            return keep_off_.footprints->overlaps(l, keep_off_.half_width);
          })) {
        ++result_.rejected_footprint;
        continue;
      }
      if (std::any_of(c.polylines.begin(), c.polylines.end(), [&](const auto& l) {
            return index_.conflicts(l, joint, set_.clearance_m);
          })) {
        ++result_.rejected_crossing;
        continue;
      }
      c.score = score(c.traced);
      if (!best || c.score > best->score) best = std::move(c);
      if (params_.selection == CandidateSelection::first_fit) break;
    }
    if (best) place(*best, g.ornament);
  }

  void place(const Candidate& c, int ornament) {
    std::vector<SurfacePoint> sources;
    for (std::size_t k = 0; k < c.polylines.size(); ++k) {
      index_.insert(c.polylines[k]);
      GrownLine& line = result_.lines.emplace_back();
      line.ornament = ornament;
      line.element = result_.elements;
      line.name = c.element->name;
      line.material = c.traced.curves[k].material;
      line.points = c.polylines[k];
      for (const SurfacePoint& p : c.traced.curves[k].points) {
        line.heights.push_back(surface_.height(p));
        sources.push_back(p);
      }
    }
    ++result_.elements;
    update_distances(sources);
    for (const TracedGrowthPoint& p : c.traced.growth_points) {
      queue_.push({p.priority, order_++, p.frame, p.tag, ornament});
    }
  }

  // The paper's update_geodesic_distances: distance to a union is the least distance. Only
  // reach = min(to_placed, to_blocked) is ever read (the score, the next seed), so a vertex
  // needs the new distance only where it can fall below its reach; the new distance is at
  // least the horizontal distance to the element's box, so every such vertex, and the path to
  // it, lies within the largest such reach of the box. The heat method runs on that part of
  // the mesh plus a margin (its boundary bends distances near it), or on the whole mesh,
  // already factored, when the part would be a large share of it.
  void update_distances(const std::vector<SurfacePoint>& sources) {
    const int w = surface_.window().width, h = surface_.window().height;
    if (!params_.local_distances) {
      const std::vector<double> d = surface_.heat_distances(sources);
      for (std::size_t v = 0; v < d.size(); ++v) to_placed_[v] = std::min(to_placed_[v], d[v]);
      ++result_.whole_solves;
      return;
    }
    int i0 = w, j0 = h, i1 = -1, j1 = -1;
    for (const SurfacePoint& p : sources) {
      const int v = surface_.nearest_vertex(p);
      i0 = std::min(i0, v % w), i1 = std::max(i1, v % w);
      j0 = std::min(j0, v / w), j1 = std::max(j1, v / w);
    }
    const double dx = surface_.grid().pixel_width, dy = surface_.grid().pixel_height;
    // Slack for the heat method's error against the true geodesic (it may read a little
    // shorter than the straight line on a coarse mesh).
    constexpr double kSlack = 1.25;
    const double spacing = std::max(dx, dy);
    double reach_max = 0.0;
    for (int j = 0; j < h; ++j) {
      const double hy = std::max({0, j0 - j, j - j1}) * dy;
      for (int i = 0; i < w; ++i) {
        const double hx = std::max({0, i0 - i, i - i1}) * dx;
        const double r = reach(j * w + i);
        if (r > reach_max && std::hypot(hx, hy) < kSlack * r + 2.0 * spacing) reach_max = r;
      }
    }
    const int margin = int(std::ceil(kSlack * reach_max / spacing)) + 4;
    Window part;
    part.col0 = std::max(i0 - margin, 0);
    part.row0 = std::max(j0 - margin, 0);
    part.width = std::min(i1 + margin + 1, w) - part.col0;
    part.height = std::min(j1 + margin + 1, h) - part.row0;
    // A factorization costs about ten solves of the same size.
    if (std::int64_t(part.width) * part.height * 8 > std::int64_t(w) * h) {
      const std::vector<double> d = surface_.heat_distances(sources);
      for (std::size_t v = 0; v < d.size(); ++v) to_placed_[v] = std::min(to_placed_[v], d[v]);
      ++result_.whole_solves;
      return;
    }
    const std::vector<double> d = surface_.heat_distances(sources, part);
    for (int j = 0; j < part.height; ++j)
      for (int i = 0; i < part.width; ++i) {
        double& t = to_placed_[std::size_t(j + part.row0) * w + i + part.col0];
        t = std::min(t, d[std::size_t(j) * part.width + i]);
      }
    ++result_.local_solves;
  }

  const TerrainSurface& surface_;
  const Raster<std::uint8_t>& allowed_;
  const ElementSet& set_;
  const GrowthParams& params_;
  const KeepOff& keep_off_;
  SegmentIndex index_;
  std::vector<double> to_blocked_, to_placed_;
  std::vector<std::uint8_t> dead_;
  std::priority_queue<QueuedGrowth> queue_;
  std::uint64_t order_ = 1;
  GrowthResult result_;
};

}  // namespace

bool enters_forbidden(const GridSpec& grid, const Window& window,
                      const Raster<std::uint8_t>& allowed, Vec2 a, Vec2 b) {
  const Vec2 origin{double(window.col0), double(window.row0)};
  const Vec2 p = grid.world_to_pixel(a) - origin, q = grid.world_to_pixel(b) - origin;
  int x = int(std::floor(p.x)), y = int(std::floor(p.y));
  const int end_x = int(std::floor(q.x)), end_y = int(std::floor(q.y));
  const auto blocked = [&](int cx, int cy) {
    return !allowed.inside(cx, cy) || !allowed.at(cx, cy);
  };
  if (blocked(x, y)) return true;
  const double dx = q.x - p.x, dy = q.y - p.y;
  const int step_x = dx > 0 ? 1 : -1, step_y = dy > 0 ? 1 : -1;
  const double inf = std::numeric_limits<double>::infinity();
  double next_x = dx != 0 ? (dx > 0 ? (x + 1 - p.x) / dx : (p.x - x) / -dx) : inf;
  double next_y = dy != 0 ? (dy > 0 ? (y + 1 - p.y) / dy : (p.y - y) / -dy) : inf;
  const double delta_x = dx != 0 ? 1.0 / std::abs(dx) : inf,
               delta_y = dy != 0 ? 1.0 / std::abs(dy) : inf;
  for (int steps = std::abs(end_x - x) + std::abs(end_y - y); steps > 0; --steps) {
    // Through a corner exactly, both neighbours are visited (one now, one next step).
    if (next_x < next_y) {
      x += step_x;
      next_x += delta_x;
    } else {
      y += step_y;
      next_y += delta_y;
    }
    if (blocked(x, y)) return true;
  }
  return false;
}

GrowthResult grow_ornaments(const TerrainSurface& surface, const Raster<std::uint8_t>& allowed,
                            const ElementSet& set, const GrowthParams& params,
                            const KeepOff& keep_off) {
  if (allowed.width != surface.window().width || allowed.height != surface.window().height) {
    fail("grow: the allowed mask is {}x{}, the surface window {}x{}", allowed.width, allowed.height,
         surface.window().width, surface.window().height);
  }
  if (params.trials < 1) fail("grow: trials must be >= 1, not {}", params.trials);
  if (elements_with_tag(set, set.seed_tag).empty()) fail("grow: no element has the seed tag");
  return Grower(surface, allowed, set, params, keep_off).run();
}

double ornament_coverage(const TerrainSurface& surface, const Raster<std::uint8_t>& allowed,
                         const std::vector<GrownLine>& lines, double radius_m) {
  std::vector<SurfacePoint> sources;
  for (const GrownLine& line : lines) {
    for (Vec2 p : line.points) {
      if (const auto s = surface.locate(p)) sources.push_back(*s);
    }
  }
  const std::vector<double> d = surface.heat_distances(sources);
  const int w = surface.window().width;
  int inside = 0, covered = 0;
  for (int v = 0; v < surface.vertex_count(); ++v) {
    if (!allowed.at(v % w, v / w)) continue;
    ++inside;
    covered += d[std::size_t(v)] <= radius_m;
  }
  return inside ? double(covered) / inside : 0.0;
}

}  // namespace tw
