#pragma once
// Cleaning one clipped line: near-duplicate vertices, spikes and tiny loops (docs/pipeline.md,
// "repair"). Self-intersections are found by GEOS through OGR; what is left crossing itself
// after the repair is a genuine self-crossing and stays.
#include <string>
#include <vector>

#include "core/vec2.hpp"
#include "geo/features.hpp"

namespace tw::detail {

// What a repair changed, summed over the pieces of one feature.
struct RepairCounts {
  int duplicates = 0;         // vertices merged into their neighbour
  int spikes = 0;             // vertices where the line doubled back
  std::vector<double> loops;  // lengths (metres) of the loops cut out
  int zero_length_parts = 0;  // pieces left with no length, dropped
  int self_crossings = 0;     // places where the kept line still meets itself

  bool changed() const {
    return duplicates > 0 || spikes > 0 || !loops.empty() || zero_length_parts > 0;
  }
};

// "removed 3 duplicate vertices, 1 spike, 1 loop of 0.8 m" (only what changed).
std::string describe(const RepairCounts& counts);

// Repairs `points` in place (a closed ring does not repeat its first point; its first vertex
// stays). Returns false when nothing with length is left (the piece is to be dropped). Throws
// tw::Error when GEOS cannot node a line that meets itself.
bool repair_line(std::vector<Vec2>& points, bool closed, const LineRepair& options,
                 RepairCounts& counts);

}  // namespace tw::detail
