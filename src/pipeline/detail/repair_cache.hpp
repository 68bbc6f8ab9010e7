#pragma once
// The ingest's line repairs through the run cache (docs/cache.md, "The plan's ribbons and
// terrain plan"; issue #23 item 2): a rerun in which one line moved repairs (GEOS-nodes) that
// line's pieces alone and takes every other piece's repair, with what it changed (the
// `repaired` warning's counts), from the cache.
//   DIR/plan/repair/<key>.twc   one piece's repair (geo/line_repair_memo.hpp's RepairedPiece),
//                               under plan_stage_hasher("repair") and the piece's
//                               line_repair_key: sections "key", "value"
#include <filesystem>

#include "core/warnings.hpp"
#include "geo/line_repair_memo.hpp"
#include "pipeline/detail/cache_entry.hpp"

namespace tw::detail {

class RepairCache {
 public:
  // A corrupt entry is the warning `cache_corrupt` (subject plan.repair) in `warnings`, and is
  // repaired again and replaced.
  RepairCache(const std::filesystem::path& dir, Warnings& warnings);

  // The memo for LineClassSpec::repair_memo; valid while this lives.
  LineRepairMemo memo();

  int pieces_repaired() const { return pieces_repaired_; }  // not found: stored

 private:
  std::filesystem::path dir_;
  Warnings& warnings_;
  CacheFolder folder_;
  int pieces_repaired_ = 0;
};

}  // namespace tw::detail
