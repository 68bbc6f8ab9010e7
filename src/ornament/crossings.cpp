#include "ornament/crossings.hpp"

#include <fmt/format.h>

namespace tw {

namespace {

constexpr std::size_t kFirstKept = 10;

void record(CrossingCheck& check, const Crossing& c) {
  CrossingCounts& counts = check.per_set[std::size_t(c.set)];
  switch (c.kind) {
    case Crossing::Kind::grown:
      ++counts.grown, ++check.total.grown;
      break;
    case Crossing::Kind::feature:
      ++counts.feature, ++check.total.feature;
      break;
    case Crossing::Kind::forbidden:
      ++counts.forbidden, ++check.total.forbidden;
      break;
  }
  if (check.first.size() < kFirstKept) check.first.push_back(c);
}

bool passes_forbidden(const ForbiddenCells& cells, const std::vector<Vec2>& line) {
  if (line.size() == 1)
    return enters_forbidden(cells.grid, cells.window, cells.allowed, line[0], line[0]);
  for (std::size_t k = 0; k + 1 < line.size(); ++k)
    if (enters_forbidden(cells.grid, cells.window, cells.allowed, line[k], line[k + 1]))
      return true;
  return false;
}

}  // namespace

CrossingCheck check_crossings(const std::vector<GrownLineSet>& sets,
                              const FootprintIndex& features) {
  CrossingCheck check;
  check.per_set.resize(sets.size());
  // Every earlier set's footprints, with (set, line) of each id.
  FootprintIndex earlier;
  std::vector<std::pair<int, int>> earlier_line;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const std::vector<GrownLine>& lines = *sets[s].lines;
    const double half_width = sets[s].half_width;
    FootprintIndex own;  // this set's lines so far: each pair once
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::vector<Vec2>& points = lines[i].points;
      for (int j : own.crossed(points))
        record(check, {Crossing::Kind::grown, int(s), int(i), int(s), j});
      for (int id : earlier.overlapped(points, half_width)) {
        const auto [other_set, other] = earlier_line[std::size_t(id)];
        record(check, {Crossing::Kind::grown, int(s), int(i), other_set, other});
      }
      for (int id : features.overlapped(points, half_width))
        record(check, {Crossing::Kind::feature, int(s), int(i), -1, id});
      if (sets[s].cells && passes_forbidden(*sets[s].cells, points))
        record(check, {Crossing::Kind::forbidden, int(s), int(i), -1, -1});
      own.add_line(points, 0.0);
    }
    for (std::size_t i = 0; i < lines.size(); ++i) {
      earlier.add_line(lines[i].points, half_width);
      earlier_line.emplace_back(int(s), int(i));
    }
  }
  return check;
}

std::string describe(const Crossing& c, const std::vector<std::string>& set_names,
                     const std::vector<std::string>& feature_names) {
  const auto name = [&](int set) {
    return std::size_t(set) < set_names.size() ? set_names[std::size_t(set)] : "grown lines";
  };
  // Line n of a set is FID n + 1 in ornaments.gpkg.
  const std::string line = fmt::format("{} FID {}", name(c.set), c.line + 1);
  switch (c.kind) {
    case Crossing::Kind::grown:
      return c.other_set == c.set
                 ? fmt::format("{} crosses FID {} of its class", line, c.other + 1)
                 : fmt::format("{} overlaps {} FID {}", line, name(c.other_set), c.other + 1);
    case Crossing::Kind::feature:
      return std::size_t(c.other) < feature_names.size()
                 ? fmt::format("{} overlaps the footprint of {}", line,
                               feature_names[std::size_t(c.other)])
                 : fmt::format("{} overlaps the footprint of a feature it keeps off", line);
    case Crossing::Kind::forbidden:
      return fmt::format("{} passes through a forbidden cell (nodata)", line);
  }
  return line;
}

}  // namespace tw
