#include "geo/detail/line_repair.hpp"

#include <ogr_geometry.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <utility>

#include "core/error.hpp"
#include "geo/detail/gdal_support.hpp"

namespace tw::detail {
namespace {

// The line turns back at b by more than the angle whose cosine is cos_limit.
bool is_spike(Vec2 a, Vec2 b, Vec2 c, double cos_limit) {
  const Vec2 in = b - a;
  const Vec2 out = c - b;
  const double lengths = length(in) * length(out);
  return lengths > 0.0 && dot(in, out) < cos_limit * lengths;
}

// One pass over the vertices: near-duplicates merge (the line's first and last vertex stay where
// they are) and every vertex where the line doubles back goes, as does any duplicate that
// removing it leaves behind.
void remove_duplicates_and_spikes(std::vector<Vec2>& points, const LineRepair& options,
                                  LineRepairCounts& counts) {
  const double cos_limit = std::cos(options.spike_angle * std::numbers::pi / 180.0);
  std::vector<Vec2> kept;
  kept.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec2 p = points[i];
    if (!kept.empty() && distance(kept.back(), p) < options.merge_distance) {
      if (i + 1 == points.size() && kept.size() > 1) kept.back() = p;
      ++counts.duplicates;
      continue;
    }
    kept.push_back(p);
    while (kept.size() >= 3 && is_spike(kept.end()[-3], kept.end()[-2], kept.back(), cos_limit)) {
      kept.erase(kept.end() - 2);
      ++counts.spikes;
      if (distance(kept.end()[-2], kept.back()) < options.merge_distance) {
        kept.erase(kept.size() > 2 ? kept.end() - 2 : kept.end() - 1);
        ++counts.duplicates;
      }
    }
  }
  points = std::move(kept);
}

void collect_line_ends(const OGRGeometry& geometry,
                       std::map<std::pair<double, double>, int>& ends) {
  const OGRwkbGeometryType type = wkbFlatten(geometry.getGeometryType());
  if (type == wkbLineString) {
    const OGRLineString& line = *geometry.toLineString();
    if (line.getNumPoints() < 2) return;
    ++ends[{line.getX(0), line.getY(0)}];
    ++ends[{line.getX(line.getNumPoints() - 1), line.getY(line.getNumPoints() - 1)}];
  } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
    for (const OGRGeometry* part : *geometry.toGeometryCollection()) collect_line_ends(*part, ends);
  }
}

// Where the line crosses or touches itself, from GEOS: a line that is not simple is noded by a
// union (with its own first point, which adds nothing), and a node where three or more of the
// noded pieces end is such a place. OGR exposes no call that returns the points directly.
std::vector<Vec2> self_meeting_points(const std::vector<Vec2>& points) {
  OGRLineString line;
  line.setNumPoints(int(points.size()), FALSE);
  for (std::size_t i = 0; i < points.size(); ++i) line.setPoint(int(i), points[i].x, points[i].y);
  QuietGdalErrors quiet;
  if (line.IsSimple()) return {};
  const OGRPoint first(points.front().x, points.front().y);
  const std::unique_ptr<OGRGeometry> noded(line.Union(&first));
  if (!noded) fail("cannot node a line that meets itself: {}", last_gdal_error());
  std::map<std::pair<double, double>, int> ends;
  collect_line_ends(*noded, ends);
  std::vector<Vec2> meeting;
  for (const auto& [point, count] : ends) {
    if (count >= 3) meeting.push_back({point.first, point.second});
  }
  return meeting;
}

struct Loop {
  double start = 0.0;  // arc lengths where the line passes through `at`
  double end = 0.0;
  Vec2 at;
};

// Arc lengths at which the line passes through p (once per pass, not once per segment).
std::vector<double> passes_through(const std::vector<Vec2>& points,
                                   const std::vector<double>& cumulative, Vec2 p) {
  const double tolerance = std::max(1e-6, 1e-12 * length(p));
  std::vector<double> passes;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Vec2 a = points[i];
    const Vec2 ab = points[i + 1] - a;
    const double t = std::clamp(dot(p - a, ab) / dot(ab, ab), 0.0, 1.0);
    if (distance(a + ab * t, p) > tolerance) continue;
    const double s = cumulative[i] + t * length(ab);
    if (passes.empty() || s - passes.back() > 10.0 * tolerance) passes.push_back(s);
  }
  return passes;
}

// Loops shorter than min_loop between consecutive passes through a meeting point, the ones
// starting first kept where they overlap.
std::vector<Loop> short_loops(const std::vector<Vec2>& points, const std::vector<Vec2>& meeting,
                              double min_loop) {
  std::vector<double> cumulative(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i)
    cumulative[i] = cumulative[i - 1] + distance(points[i - 1], points[i]);
  std::vector<Loop> loops;
  for (const Vec2 p : meeting) {
    const std::vector<double> passes = passes_through(points, cumulative, p);
    for (std::size_t k = 0; k + 1 < passes.size(); ++k) {
      if (passes[k + 1] - passes[k] < min_loop) loops.push_back({passes[k], passes[k + 1], p});
    }
  }
  std::sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    return std::pair(a.start, a.end) < std::pair(b.start, b.end);
  });
  std::vector<Loop> disjoint;
  for (const Loop& loop : loops) {
    if (disjoint.empty() || loop.start >= disjoint.back().end) disjoint.push_back(loop);
  }
  return disjoint;
}

// The line with each loop replaced by its meeting point.
std::vector<Vec2> cut_loops(const std::vector<Vec2>& points, const std::vector<Loop>& loops) {
  std::vector<Vec2> result;
  std::size_t next = 0;
  double s = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i > 0) s += distance(points[i - 1], points[i]);
    while (next < loops.size() && s > loops[next].end) ++next;
    const bool inside = next < loops.size() && s > loops[next].start && s < loops[next].end;
    if (next < loops.size() && s > loops[next].start &&
        (result.empty() || result.back() != loops[next].at)) {
      result.push_back(loops[next].at);
    }
    if (!inside && (result.empty() || result.back() != points[i])) result.push_back(points[i]);
  }
  return result;
}

}  // namespace

std::string describe(const LineRepairCounts& counts) {
  std::vector<std::string> parts;
  auto plural = [](int n, const char* one, const char* many) {
    return fmt::format("{} {}", n, n == 1 ? one : many);
  };
  if (counts.duplicates > 0)
    parts.push_back(plural(counts.duplicates, "duplicate vertex", "duplicate vertices"));
  if (counts.spikes > 0) parts.push_back(plural(counts.spikes, "spike", "spikes"));
  if (!counts.loops.empty()) {
    auto metres = [](double loop) {
      return loop < 100.0 ? fmt::format("{:.2g}", loop) : fmt::format("{:.0f}", loop);
    };
    std::string lengths;
    if (counts.loops.size() <= 3) {
      for (const double loop : counts.loops)
        lengths += (lengths.empty() ? "" : ", ") + metres(loop);
    } else {
      const auto [shortest, longest] =
          std::minmax_element(counts.loops.begin(), counts.loops.end());
      lengths = metres(*shortest) + " to " + metres(*longest);
    }
    parts.push_back(
        fmt::format("{} of {} m", plural(int(counts.loops.size()), "loop", "loops"), lengths));
  }
  if (counts.zero_length_parts > 0)
    parts.push_back(plural(counts.zero_length_parts, "zero-length part", "zero-length parts"));
  std::string text = "removed ";
  for (std::size_t i = 0; i < parts.size(); ++i)
    text += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return text;
}

bool repair_line(std::vector<Vec2>& points, bool closed, const LineRepair& options,
                 LineRepairCounts& counts) {
  // A ring is repaired as a line from its first vertex back to it.
  if (closed && !points.empty()) points.push_back(points.front());
  const std::size_t minimum = closed ? 4 : 2;
  std::vector<Vec2> meeting;
  // Cutting a loop can leave a spike or a shorter loop behind; a few rounds settle it.
  for (int round = 0; round < 16; ++round) {
    remove_duplicates_and_spikes(points, options, counts);
    if (points.size() < minimum) break;
    meeting = self_meeting_points(points);
    const std::vector<Loop> loops = short_loops(points, meeting, options.min_loop);
    if (loops.empty()) break;
    for (const Loop& loop : loops) counts.loops.push_back(loop.end - loop.start);
    points = cut_loops(points, loops);
    meeting.clear();
  }
  if (points.size() < minimum) {
    ++counts.zero_length_parts;
    points.clear();
    return false;
  }
  if (closed) points.pop_back();
  counts.self_crossings += int(meeting.size());
  return true;
}

}  // namespace tw::detail
