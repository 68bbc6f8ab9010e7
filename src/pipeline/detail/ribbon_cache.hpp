#pragma once
// The ribbons stage through the run cache, per feature (docs/cache.md, "The plan's ribbons";
// issue #23 item 2): a moved road makes its own ribbon again and searches the junctions near it
// alone, and writes only what changed.
//   DIR/plan/ribbon/<key>.twc     one feature's ribbon (make_ribbon), under the hash of its
//                                 centreline, width and piece length: sections "key", "value"
//   DIR/plan/junctions/<key>.twc  the latest junction search at one tolerance, under the hash of
//                                 the tolerance: sections "key", "curves" (each curve's hash),
//                                 "value" (ribbon/junction_search.hpp's JunctionSearch)
#include <filesystem>
#include <string>
#include <vector>

#include "core/warnings.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "pipeline/detail/stages.hpp"

namespace tw::detail {

class RibbonCache {
 public:
  // A corrupt entry is the warning `cache_corrupt` (subject plan.ribbon or plan.junctions) in
  // `warnings`, and is made again and replaced.
  RibbonCache(const std::filesystem::path& dir, Warnings& warnings);

  // The steps of make_feature_ribbons through the cache: a ribbon found under its key or made
  // and stored; the junctions of curves whose hashes are the latest search's as found, else
  // searched again near the changed curves (update_junctions) and stored.
  RibbonSteps steps();

  int ribbons_made() const { return ribbons_made_; }
  std::size_t curves_searched() const { return curves_searched_; }  // by both tolerances

 private:
  Ribbon ribbon(const Curve& centerline, const RibbonParams& params);
  std::vector<Junction> junctions(const std::vector<Curve>& curves, double tolerance_m);

  std::filesystem::path dir_;
  Warnings& warnings_;
  CacheFolder folder_;
  int ribbons_made_ = 0;
  std::size_t curves_searched_ = 0;
};

}  // namespace tw::detail
