#include "cache_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <sstream>

#include "test_support.hpp"
#include "test_world.hpp"

namespace tw::test {

namespace fs = std::filesystem;

const char* const kCachePipeline = R"(
version: 1
seed: 5
generate: { width: 160, height: 160, pixel_size: 4, relief: 40, origin: [500000, 5000640] }
synthesis_resolution: 1
features:
  roads:
    source: roads.gpkg
    layer: roads
    kind: road
    width: 6
    profile: { shoulder_width: 2, falloff: 10 }
    synthesis: { exemplar: cobble.png, width: 8, scale: 5, delta: 8 }
)";

std::vector<Line> roads() {
  return {{{50, 300}, {590, 300}},
          {{320, 50}, {320, 590}},
          {{50, 450}, {250, 450}},
          {{450, 318}, {590, 318}},
          {{50, 100}, {250, 100}}};
}

std::vector<Line> roads_with_r1_moved() {
  std::vector<Line> lines = roads();
  lines[0][1] = {590, 310};
  return lines;
}

std::vector<Line> roads_with_r1_west_moved() {
  std::vector<Line> lines = roads();
  lines[0][0] = {50, 290};
  return lines;
}

void write_roads(const fs::path& path, const std::vector<Line>& lines) {
  std::vector<VectorFeature> features;
  for (const Line& line : lines) {
    std::ostringstream wkt;
    wkt.precision(12);
    wkt << "LINESTRING (";
    for (std::size_t i = 0; i < line.size(); ++i)
      wkt << (i ? ", " : "") << kX0 + line[i].x << ' ' << kY0 + line[i].y;
    wkt << ")";
    features.emplace_back(wkt.str(), kWidth);
  }
  fs::remove(path);
  write_layer(path, "roads", features);
}

void write_exemplar(const fs::path& dir) {
  const fs::path exemplars = source_dir() / "samples/exemplars";
  crop_raster(exemplars / "cobble_edging_200x56.png", dir / "cobble.png", "PNG", 60, 56);
  crop_raster(exemplars / "cobble_edging_200x56_height.tif", dir / "cobble_height.tif", "GTiff", 60,
              56);
}

Box line_box(const Line& line, double grow) {
  Box b{1e9, 1e9, -1e9, -1e9};
  for (const Vec2 p : line)
    b = {std::min(b.x0, p.x), std::min(b.y0, p.y), std::max(b.x1, p.x), std::max(b.y1, p.y)};
  return {b.x0 - grow, b.y0 - grow, b.x1 + grow, b.y1 + grow};
}

namespace {

std::optional<Vec2> crossing(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  const double den = cross(b - a, d - c);
  if (den == 0.0) return std::nullopt;
  const double t = cross(c - a, d - c) / den, u = cross(c - a, b - a) / den;
  if (t < 0 || t > 1 || u < 0 || u > 1) return std::nullopt;
  return a + (b - a) * t;
}

}  // namespace

std::vector<Vec2> crossings(const std::vector<Line>& lines) {
  std::vector<Vec2> points;
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (std::size_t j = i + 1; j < lines.size(); ++j)
      for (std::size_t s = 0; s + 1 < lines[i].size(); ++s)
        for (std::size_t t = 0; t + 1 < lines[j].size(); ++t)
          if (auto p = crossing(lines[i][s], lines[i][s + 1], lines[j][t], lines[j][t + 1]))
            points.push_back(*p);
  return points;
}

std::vector<Vec2> changed_crossings(const std::vector<Line>& before,
                                    const std::vector<Line>& after) {
  const std::vector<Vec2> old_points = crossings(before), new_points = crossings(after);
  std::vector<Vec2> changed;
  for (const Vec2 p : old_points)
    if (std::find(new_points.begin(), new_points.end(), p) == new_points.end())
      changed.push_back(p);
  for (const Vec2 p : new_points)
    if (std::find(old_points.begin(), old_points.end(), p) == old_points.end())
      changed.push_back(p);
  return changed;
}

// A synthesis reads its canvas: the ribbon's box plus a cell, here within half the synthesis
// width plus 2 m of the line's box. It is rebuilt when its own line changed, when a junction
// (a crossing of two lines) on its canvas moved, appeared or went, or when a feature synthesized
// before it whose canvas met its own (before or after the change) was rebuilt.
std::set<int> expected_rebuilds(const std::vector<Line>& before, const std::vector<Line>& after) {
  const std::vector<Vec2> moved = changed_crossings(before, after);
  const double canvas = kSynthesisWidth / 2 + 2.0;
  const double disc = kSynthesisWidth / 2 + 1.0;  // the widest member's half width + a cell
  std::set<int> rebuilt;
  for (std::size_t f = 0; f < after.size(); ++f) {
    const Box old_box = line_box(before[f], canvas), new_box = line_box(after[f], canvas);
    bool changed = before[f] != after[f];
    for (const Vec2 p : moved)
      changed = changed || old_box.holds(p, disc) || new_box.holds(p, disc);
    for (std::size_t g = 0; g < f; ++g) {
      if (!rebuilt.count(int(g) + 1)) continue;
      for (const Box& mine : {old_box, new_box})
        for (const Box& theirs : {line_box(before[g], canvas), line_box(after[g], canvas)})
          changed = changed || mine.meets(theirs);
    }
    if (changed) rebuilt.insert(int(f) + 1);
  }
  return rebuilt;
}

std::map<std::string, std::string> output_files(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (auto it = fs::recursive_directory_iterator(root); it != fs::end(it); ++it) {
    const std::string name = it->path().lexically_relative(root).string();
    if (name == ".terraweave") {
      it.disable_recursion_pending();
      continue;
    }
    if (fs::is_directory(it->path()) || name == "report.json") continue;
    files[name] = read_file(it->path());
  }
  return files;
}

std::size_t expect_same_output_files(const fs::path& a, const fs::path& b) {
  const auto x = output_files(a), y = output_files(b);
  EXPECT_EQ(x.size(), y.size()) << a << " and " << b;
  for (const auto& [name, bytes] : x) {
    const auto it = y.find(name);
    if (it == y.end()) {
      ADD_FAILURE() << name << " is in " << a << " but not in " << b;
      continue;
    }
    EXPECT_TRUE(bytes == it->second) << name << " differs between " << a << " and " << b;
  }
  return x.size();
}

}  // namespace tw::test
