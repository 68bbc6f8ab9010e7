#pragma once
// Graph quilting (docs/networks.md, "Quilting"): the region is covered by overlapping square
// blocks of the exemplar, each chosen among random candidates by how well its lines agree with
// the blocks already placed in the overlap (image quilting, Efros & Freeman 2001, with the
// lines' clamped distance fields as the images), cut along the seams between the blocks' cells,
// and stitched: cut ends facing each other across a seam are joined at their midpoint.
#include <vector>

#include "core/split_mix.hpp"
#include "network/network.hpp"

namespace tw::network_detail {

struct QuiltLine {
  std::vector<Vec2> points;
  // Per end (front, back): cut at a seam between two blocks (joined or not to a line of the
  // other block; an end left alone there is a stub to link or trim).
  bool seam_end[2] = {false, false};
  // Per seam end: the exemplar line it was cut from, beyond the cut (starting at the end, at
  // most QuiltSettings::continuation long): where the line would have gone on.
  std::vector<Vec2> continuation[2];
};

struct QuiltSettings {
  Vec2 lo, hi;                // the region's extent
  double stitch = 0.0;        // seam ends closer than this (metres) are joined
  double clearance = 0.0;     // lines closer than this to each other are one too many
  double turn = 0.0;          // the exemplar turned by this (radians) before it is copied
  double continuation = 0.0;  // a seam end's continuation is this long (metres)
  int candidates = 32;        // exemplar squares tried per block
};

// The lines of the quilt over [lo, hi], drawn from `rng` in a fixed order (same seed, same
// lines). Throws nothing: an exemplar smaller than a block is copied from its middle.
std::vector<QuiltLine> quilt_lines(const Network& exemplar, const QuiltSettings& settings,
                                   SplitMix64& rng);

}  // namespace tw::network_detail
