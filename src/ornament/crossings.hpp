#pragma once
// The safety net after growth (issue #21): the lines that are written, checked exactly in
// vector space. Lines of one set (a class) may not cross each other (they may meet end to end,
// at an ornament's joint); lines of different sets may not overlap as footprints (each line
// buffered by its set's half width); no line's footprint may overlap a feature's, and no line
// may pass through a forbidden cell. Growth rejects every candidate that would (KeepOff), so
// each count is 0 unless growth has a bug.
#include <cstdint>
#include <string>
#include <vector>

#include "ornament/footprints.hpp"
#include "ornament/grow.hpp"

namespace tw {

struct GrownLineSet {
  const std::vector<GrownLine>* lines = nullptr;
  double half_width = 0.0;                // metres: the footprint is the line buffered by it
  const ForbiddenCells* cells = nullptr;  // none of its lines may pass through one
};

struct CrossingCounts {
  std::int64_t grown = 0;      // pairs of grown lines
  std::int64_t feature = 0;    // pairs (grown line, feature footprint)
  std::int64_t forbidden = 0;  // grown lines through a forbidden cell
  std::int64_t total() const { return grown + feature + forbidden; }
};

struct Crossing {
  enum class Kind { grown, feature, forbidden };
  Kind kind = Kind::grown;
  int set = 0, line = 0;           // the grown line (index into its set)
  int other_set = -1, other = -1;  // the other grown line, or the feature's footprint id
};

struct CrossingCheck {
  std::vector<CrossingCounts> per_set;  // a pair of two sets counts in the later one's
  CrossingCounts total;
  std::vector<Crossing> first;  // the first few, for the error message
};

// `features`: the footprints of the features read (ids as added).
CrossingCheck check_crossings(const std::vector<GrownLineSet>& sets,
                              const FootprintIndex& features);

// "hedges FID 12 overlaps ditches FID 3", with the sets' names and the features' (by id).
std::string describe(const Crossing& crossing, const std::vector<std::string>& set_names,
                     const std::vector<std::string>& feature_names);

}  // namespace tw
