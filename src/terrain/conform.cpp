#include "terrain/conform.hpp"

#include <algorithm>
#include <cmath>
#include <compare>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>

#include "terrain/detail/feature_index.hpp"

namespace tw {

namespace {

// Cost per metre of path, in metres of height: a cell's height above the local floor (below
// the local crest), plus a length term that grows away from the given line, so a flat valley
// floor keeps the line where it was drawn and meanders are not cut short (docs/terrain.md).
constexpr double kLengthWeight = 1.0;           // metres of height per metre of path on the line
constexpr double kDistanceWeight = 4.0;         // times kLengthWeight at the corridor's edge
constexpr std::int64_t kMaxCells = 20'000'000;  // beyond this the corridor is not searched

struct CorridorCell {
  std::int64_t id = 0;    // row * grid.width + col
  double height = 0.0;    // NaN over nodata
  double distance = 0.0;  // metres from the given line
  double along = 0.0;     // arc length of the nearest point of the given line
};

// The cells whose centres lie within `corridor` of the line, sorted by id.
std::vector<CorridorCell> corridor_cells(HeightSampler& heights, const Curve& line,
                                         double corridor) {
  const GridSpec& grid = heights.grid();
  double x0 = line.points[0].x, x1 = x0, y0 = line.points[0].y, y1 = y0;
  for (const Vec2 p : line.points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const Vec2 a = grid.world_to_pixel({x0 - corridor, y1 + corridor});
  const Vec2 b = grid.world_to_pixel({x1 + corridor, y0 - corridor});
  const int c0 = int(std::clamp(std::floor(a.x), 0.0, double(grid.width)));
  const int c1 = int(std::clamp(std::ceil(b.x), 0.0, double(grid.width)));
  const int r0 = int(std::clamp(std::floor(a.y), 0.0, double(grid.height)));
  const int r1 = int(std::clamp(std::ceil(b.y), 0.0, double(grid.height)));
  std::vector<CorridorCell> cells;
  if (c1 <= c0 || r1 <= r0) return cells;
  const Window window{c0, r0, c1 - c0, r1 - r0};
  const detail::FeatureIndex index(grid, window, {&line}, {corridor});
  std::vector<detail::NearestSample> samples;
  for (int t = 0; t < index.tile_count(); ++t) {
    if (index.tile_is_empty(t)) continue;
    const Window tile = index.tile(t);
    index.for_each_feature(t, samples, [&](int, const std::vector<detail::NearestSample>& s) {
      for (int r = 0; r < tile.height; ++r)
        for (int c = 0; c < tile.width; ++c) {
          const auto& n = s[std::size_t(r) * tile.width + c];
          if (!std::isfinite(n.distance)) continue;
          const float h = heights.cell(tile.col0 + c, tile.row0 + r);
          cells.push_back(
              {std::int64_t(tile.row0 + r) * grid.width + tile.col0 + c, h, n.distance, n.along});
        }
    });
    if (std::int64_t(cells.size()) > kMaxCells) return {};
  }
  std::sort(cells.begin(), cells.end(), [](const auto& p, const auto& q) { return p.id < q.id; });
  return cells;
}

// Per cell, the cost per metre: height above the lowest (below the highest) cell of the
// corridor within one corridor width along the line, plus the length term. Over nodata the
// length term only: the path's length over nodata is minimized first (least_cost_path).
std::vector<double> cost_density(const std::vector<CorridorCell>& cells, double corridor,
                                 ConformTarget target) {
  const double sign = target == ConformTarget::valley_floor ? 1.0 : -1.0;
  double along_max = 0.0;
  for (const auto& c : cells) along_max = std::max(along_max, c.along);
  const std::size_t bins = std::size_t(along_max / corridor) + 1;
  std::vector<double> floor(bins, std::numeric_limits<double>::infinity());
  for (const auto& c : cells) {
    double& f = floor[std::size_t(c.along / corridor)];
    if (!std::isnan(c.height)) f = std::min(f, sign * c.height);
  }
  std::vector<double> density(cells.size());
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::size_t b = std::size_t(cells[i].along / corridor);
    double local = floor[b];
    if (b > 0) local = std::min(local, floor[b - 1]);
    if (b + 1 < bins) local = std::min(local, floor[b + 1]);
    // Nodata is never read as a height; what crossing it costs is least_cost_path's.
    const double above = std::isnan(cells[i].height) ? 0.0 : sign * cells[i].height - local;
    density[i] = above + kLengthWeight * (1.0 + kDistanceWeight * cells[i].distance / corridor);
  }
  return density;
}

// Index in `cells` of the corridor cell holding p, or -1.
std::ptrdiff_t cell_at(const std::vector<CorridorCell>& cells, const GridSpec& grid, Vec2 p) {
  const Vec2 px = grid.world_to_pixel(p);
  const double col = std::floor(px.x), row = std::floor(px.y);
  if (!(col >= 0.0 && row >= 0.0 && col < grid.width && row < grid.height)) return -1;
  const std::int64_t id = std::int64_t(row) * grid.width + std::int64_t(col);
  const auto it = std::lower_bound(cells.begin(), cells.end(), id,
                                   [](const CorridorCell& x, std::int64_t v) { return x.id < v; });
  return it != cells.end() && it->id == id ? it - cells.begin() : -1;
}

// What a path costs: first its metres over nodata, then the cost of its density (compared in
// that order), so nodata costs more than any path over valid cells: a river drawn along the
// DEM's nodata edge is not drawn into it, and crosses it only where the corridor has no way
// around (where nothing would be carved and the river would vanish).
struct PathCost {
  double nodata_metres = 0.0;
  double cost = 0.0;
  auto operator<=>(const PathCost&) const = default;
};

// Dijkstra over the 8-connected corridor cells; the cells of the cheapest path, start to
// goal (empty when the goal cannot be reached).
std::vector<std::size_t> least_cost_path(const std::vector<CorridorCell>& cells,
                                         const std::vector<double>& density, const GridSpec& grid,
                                         std::size_t start, std::size_t goal) {
  const std::size_t n = cells.size();
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<PathCost> cost(n, PathCost{kInfinity, kInfinity});
  std::vector<std::ptrdiff_t> previous(n, -1);
  using Entry = std::pair<PathCost, std::size_t>;  // ties: the lowest index first
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  cost[start] = PathCost{};
  open.push({PathCost{}, start});
  const double diagonal = std::hypot(grid.pixel_width, grid.pixel_height);
  const auto over_nodata = [&](std::size_t i) { return std::isnan(cells[i].height) ? 1.0 : 0.0; };
  while (!open.empty()) {
    const auto [c, i] = open.top();
    open.pop();
    if (cost[i] < c) continue;
    if (i == goal) break;
    const int col = int(cells[i].id % grid.width), row = int(cells[i].id / grid.width);
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        if (dr == 0 && dc == 0) continue;
        const int nc = col + dc, nr = row + dr;
        if (nc < 0 || nr < 0 || nc >= grid.width || nr >= grid.height) continue;
        const std::int64_t id = std::int64_t(nr) * grid.width + nc;
        const auto it =
            std::lower_bound(cells.begin(), cells.end(), id,
                             [](const CorridorCell& x, std::int64_t v) { return x.id < v; });
        if (it == cells.end() || it->id != id) continue;
        const std::size_t j = std::size_t(it - cells.begin());
        const double step = dr == 0 ? grid.pixel_width : dc == 0 ? grid.pixel_height : diagonal;
        const PathCost next{c.nodata_metres + step * 0.5 * (over_nodata(i) + over_nodata(j)),
                            c.cost + step * 0.5 * (density[i] + density[j])};
        if (next < cost[j]) {
          cost[j] = next;
          previous[j] = std::ptrdiff_t(i);
          open.push({next, j});
        }
      }
  }
  std::vector<std::size_t> path;
  if (!std::isfinite(cost[goal].cost)) return path;
  for (std::ptrdiff_t i = std::ptrdiff_t(goal); i >= 0; i = previous[std::size_t(i)])
    path.push_back(std::size_t(i));
  std::reverse(path.begin(), path.end());
  return path;
}

// A moving average over +-2 vertices takes the staircase out of a cell path; ends are pinned.
// A vertex whose window holds a `rigid` one (a cell next to nodata) keeps its cell's centre:
// averaging there would cut the corners of the nodata the path goes round.
Curve smoothed(std::vector<Vec2> points, const std::vector<bool>& rigid) {
  constexpr int kHalf = 2;
  const auto n = std::ptrdiff_t(points.size());
  std::vector<Vec2> out = points;
  for (std::ptrdiff_t i = 1; i + 1 < n; ++i) {
    const std::ptrdiff_t h = std::min<std::ptrdiff_t>({kHalf, i, n - 1 - i});
    if (std::any_of(rigid.begin() + (i - h), rigid.begin() + (i + h + 1), [](bool r) { return r; }))
      continue;
    Vec2 sum{0.0, 0.0};
    for (std::ptrdiff_t k = i - h; k <= i + h; ++k) sum += points[std::size_t(k)];
    out[std::size_t(i)] = sum / double(2 * h + 1);
  }
  return without_duplicates(Curve{std::move(out), false});
}

// Samples of `from` every `step` metres, with their distances to `to`.
std::vector<double> distances_along(const Curve& from, const Curve& to, double step) {
  const auto cumulative = cumulative_lengths(from);
  const double total = cumulative.back();
  const std::size_t count = std::size_t(std::ceil(total / step)) + 1;
  std::vector<double> d(count);
  for (std::size_t i = 0; i < count; ++i)
    d[i] = distance_to_line(to, point_at(from, cumulative, std::min(total, double(i) * step)));
  return d;
}

}  // namespace

Vec2 nearest_point(const Curve& line, Vec2 p) {
  double best = std::numeric_limits<double>::infinity();
  Vec2 nearest = line.points.front();
  const std::size_t n = line.points.size();
  const std::size_t segments = line.closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec2 a = line.points[i], ab = line.points[(i + 1) % n] - a;
    const double l2 = dot(ab, ab);
    const double t = l2 > 0.0 ? std::clamp(dot(p - a, ab) / l2, 0.0, 1.0) : 0.0;
    const Vec2 q = a + ab * t;
    if (const double d = distance(q, p); d < best) best = d, nearest = q;
  }
  return nearest;
}

double distance_to_line(const Curve& line, Vec2 p) {
  return distance(nearest_point(line, p), p);
}

void reattach_ends(const std::vector<Curve>& drawn, std::vector<Curve>& conformed,
                   const std::vector<double>& tolerance) {
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    if (drawn[i].closed || drawn[i].points.size() < 2) continue;
    for (const bool at_start : {true, false}) {
      const Vec2 end = at_start ? drawn[i].points.front() : drawn[i].points.back();
      for (std::size_t j = 0; j < drawn.size(); ++j) {
        if (j == i || conformed[j].points == drawn[j].points) continue;
        const auto& other = drawn[j].points;
        const bool near_an_end = distance(end, other.front()) <= tolerance[i] ||
                                 distance(end, other.back()) <= tolerance[i];
        if (near_an_end || distance_to_line(drawn[j], end) > tolerance[i]) continue;
        Vec2& moved = at_start ? conformed[i].points.front() : conformed[i].points.back();
        moved = nearest_point(conformed[j], end);
        break;  // the first line it touches, in order: deterministic
      }
    }
    conformed[i] = without_duplicates(conformed[i]);
  }
}

ConformResult conform_line(const Raster<float>& height, const GridSpec& grid, const Curve& line,
                           const ConformOptions& options) {
  const auto source = in_memory_heightfield(height, grid);
  HeightSampler heights(*source);
  return conform_line(heights, line, options);
}

ConformResult conform_line(HeightSampler& heights, const Curve& line,
                           const ConformOptions& options) {
  const GridSpec& grid = heights.grid();
  ConformResult result;
  result.line = line;
  if (!(options.corridor > 0.0)) {
    result.kept_because = "no corridor";
    return result;
  }
  const Curve given = without_duplicates(line);
  if (given.closed || given.points.size() < 2) {
    result.kept_because = "a closed line keeps its course";
    return result;
  }
  const auto cells = corridor_cells(heights, given, options.corridor);
  if (cells.empty()) {
    result.kept_because = "no DEM cell in its corridor (off the grid, or too many cells)";
    return result;
  }
  if (std::all_of(cells.begin(), cells.end(), [](const auto& c) { return std::isnan(c.height); })) {
    result.kept_because = "its corridor lies over nodata";
    return result;
  }
  // The line is conformed between the first and the last of its points on the grid; beyond
  // them (a line clipped with a margin) it is kept.
  const auto cumulative = cumulative_lengths(given);
  const double total = cumulative.back();
  const double sample = 0.5 * std::min(grid.pixel_width, grid.pixel_height);
  const std::size_t count = std::size_t(std::ceil(total / sample)) + 1;
  std::ptrdiff_t start = -1, goal = -1;
  double s_start = 0.0, s_goal = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double s = std::min(total, double(i) * sample);
    const std::ptrdiff_t c = cell_at(cells, grid, point_at(given, cumulative, s));
    if (c < 0) continue;
    if (start < 0) start = c, s_start = s;
    goal = c, s_goal = s;
  }
  if (start < 0 || s_goal <= s_start) {
    result.kept_because = "it lies off the grid";
    return result;
  }
  const auto path = least_cost_path(cells, cost_density(cells, options.corridor, options.target),
                                    grid, std::size_t(start), std::size_t(goal));
  if (path.empty()) {
    result.kept_because = "its corridor is cut in two by the grid's edge";
    return result;
  }
  // The exact points where the conformed stretch begins and ends take the place of their
  // cells' centres.
  std::vector<Vec2> middle{point_at(given, cumulative, s_start)};
  std::vector<bool> rigid(path.size(), false);
  for (std::size_t k = 0; k < path.size(); ++k) {
    const int col = int(cells[path[k]].id % grid.width), row = int(cells[path[k]].id / grid.width);
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) {
        const int c = col + dc, r = row + dr;
        const bool on_grid = c >= 0 && r >= 0 && c < grid.width && r < grid.height;
        if (on_grid && std::isnan(heights.cell(c, r))) rigid[k] = true;
      }
    if (k > 0 && k + 1 < path.size()) middle.push_back(grid.pixel_centre_world(col, row));
  }
  middle.push_back(point_at(given, cumulative, s_goal));
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < given.points.size() && cumulative[i] < s_start; ++i)
    points.push_back(given.points[i]);
  for (const Vec2 p : smoothed(std::move(middle), rigid).points) points.push_back(p);
  for (std::size_t i = 0; i < given.points.size(); ++i)
    if (cumulative[i] > s_goal) points.push_back(given.points[i]);
  result.line = without_duplicates(Curve{std::move(points), false});
  if (result.line.points.size() < 2) result.line = given;
  result.conformed = true;

  const double step = 0.5 * std::min(grid.pixel_width, grid.pixel_height);
  const auto moved = distances_along(result.line, given, step);
  const auto back = distances_along(given, result.line, step);
  double sum = 0.0;
  for (const double d : moved) sum += d;
  result.mean_move = sum / double(moved.size());
  result.max_offset = *std::max_element(moved.begin(), moved.end());
  result.max_move = std::max(result.max_offset, *std::max_element(back.begin(), back.end()));
  return result;
}

}  // namespace tw
