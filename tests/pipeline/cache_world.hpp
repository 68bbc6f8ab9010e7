#pragma once
// The small world of the cache tests (cache_test.cpp, tile_cache_test.cpp): a generated 640 m
// terrain with five roads, changes to one of them, the rebuilds those imply worked out from
// the geometry alone, and byte comparisons of output folders.
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/vec2.hpp"

namespace tw::test {

inline constexpr double kX0 = 500000.0, kY0 = 5000000.0;  // south-west corner of the world
inline constexpr double kWidth = 6.0;                     // every road's width
inline constexpr double kSynthesisWidth = 8.0;

// The pipeline (relative paths: roads.gpkg, cobble.png in the test's folder); extra top-level
// keys may follow it.
extern const char* const kCachePipeline;

using Line = std::vector<Vec2>;  // local metres from (kX0, kY0)

// FID 1..5 in this order (the synthesis order). R1 and R2 cross; R4 runs beside R1's east end,
// 18 m north of it; R3 and R5 are far from everything.
std::vector<Line> roads();
// R1 with its east end moved 10 m north: now 8 m from R4 there.
std::vector<Line> roads_with_r1_moved();
// R1 with its west end moved 10 m south: away from everything but R2, which it still crosses.
std::vector<Line> roads_with_r1_west_moved();

// Writes the roads.gpkg layer `roads` (replacing the file), and the cropped cobble exemplar.
void write_roads(const std::filesystem::path& path, const std::vector<Line>& lines);
void write_exemplar(const std::filesystem::path& dir);

struct Box {
  double x0, y0, x1, y1;
  bool meets(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  bool holds(Vec2 p, double grow) const {
    return p.x > x0 - grow && p.x < x1 + grow && p.y > y0 - grow && p.y < y1 + grow;
  }
};
// The line's bounding box grown by `grow` metres.
Box line_box(const Line& line, double grow);
// Every point where two lines cross.
std::vector<Vec2> crossings(const std::vector<Line>& lines);
// The crossings of one set that the other lacks (moved, appeared or gone).
std::vector<Vec2> changed_crossings(const std::vector<Line>& before,
                                    const std::vector<Line>& after);

// FIDs (1-based) whose synthesis must be rebuilt when the roads go from `before` to `after`.
std::set<int> expected_rebuilds(const std::vector<Line>& before, const std::vector<Line>& after);

// Every output of a run folder but report.json (timings, cache statuses), by name, read through
// the links.
std::map<std::string, std::string> output_files(const std::filesystem::path& root);

// Expects the run folders a and b to hold the same outputs (output_files), byte for byte;
// returns how many a holds, for the caller's count.
std::size_t expect_same_output_files(const std::filesystem::path& a,
                                     const std::filesystem::path& b);

}  // namespace tw::test
