#pragma once
// The instantiation half of area synthesis: candidates in input-space coordinates, before the
// world filter (polygon, avoidance, overlap) of area_filter.hpp.
#include <cstdint>
#include <functional>
#include <vector>

#include "core/split_mix.hpp"
#include "core/vec2.hpp"
#include "sketch/hierarchy.hpp"

namespace tw::detail {

struct Candidate {
  int shape = 0;
  int lead = 0;
  bool unbounded = false;
  bool original = false;                   // the sketch's own shape, unperturbed
  std::vector<std::vector<Vec2>> strokes;  // one per stroke of the shape, same order
  Vec2 centre;
  Vec2 axis{1.0, 0.0};
};

// Every candidate of the hierarchy over the rectangle [lo, hi] of input space (the output space
// covering the domain), lead by lead, originals first within each, handed to `visit` one at a
// time: none is held, so memory does not grow with the rectangle. A bounded candidate whose
// centre `near(centre, shape)` rejects (input space) is skipped before its strokes are built and
// counted in `skipped`; the random draws are the same either way, so `near` only saves work.
using CandidateVisitor = std::function<void(Candidate&&)>;
using CandidateFilter = std::function<bool(Vec2, int)>;
void area_candidates(const SupportHierarchy& h, Vec2 lo, Vec2 hi, double jitter, bool keep_input,
                     std::uint64_t seed, const CandidateFilter& near, const CandidateVisitor& visit,
                     std::int64_t& skipped);

}  // namespace tw::detail
