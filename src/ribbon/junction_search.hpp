#pragma once
// Junctions found again after some curves changed, near those curves alone (issue #23 item 2: a
// moved road changes only the junctions it and its partners meet at): the same junctions, bit
// for bit and in the same order, as find_junctions over every curve.
#include <cstddef>
#include <vector>

#include "ribbon/junctions.hpp"

namespace tw {

// A search's junctions with what a later update reads.
struct JunctionSearch {
  double tolerance_m = 0.0;
  std::vector<Junction> junctions;  // find_junctions(curves, tolerance_m)
  std::vector<Extent> extents;      // per junction: the box of the meeting points merged into it
  std::vector<Extent> boxes;        // per curve: the box of its points
  std::size_t curves_searched = 0;  // by the search or update that gave it
};

JunctionSearch search_junctions(const std::vector<Curve>& curves, double tolerance_m);

// search_junctions(curves, previous.tolerance_m), from `previous`, a search over as many curves,
// of which those with changed[i] differ now. Only the curves near a changed one (its box before
// and after) or near a junction it was part of are searched; the junctions elsewhere are kept.
// Searches every curve when the counts differ, when most curves are near a change, or when a
// junction found near the change reaches a curve left out (a chain of meeting points longer than
// the margins).
JunctionSearch update_junctions(const JunctionSearch& previous, const std::vector<Curve>& curves,
                                const std::vector<bool>& changed);

}  // namespace tw
