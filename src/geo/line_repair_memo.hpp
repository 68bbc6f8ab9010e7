#pragma once
// A memo of line repairs that a caller may hand read_line_features (LineClassSpec::repair_memo):
// repairing a piece (GEOS noding every line) was the ingest's largest cost on a rerun in which
// one line changed (docs/performance.md, issue #23 item 2). The reader asks the memo under the
// hash of what a repair reads and stores what it computed; it knows nothing of where the memo
// keeps it (the pipeline: its run cache, docs/cache.md).
#include <functional>
#include <optional>
#include <vector>

#include "core/content_hash.hpp"
#include "core/vec2.hpp"

namespace tw {

struct LineRepair;

// What a repair changed, summed over the pieces of one feature (the `repaired` warning says it).
struct LineRepairCounts {
  int duplicates = 0;         // vertices merged into their neighbour
  int spikes = 0;             // vertices where the line doubled back
  std::vector<double> loops;  // lengths (metres) of the loops cut out
  int zero_length_parts = 0;  // pieces left with no length, dropped
  int self_crossings = 0;     // places where the kept line still meets itself

  bool changed() const {
    return duplicates > 0 || spikes > 0 || !loops.empty() || zero_length_parts > 0;
  }
  // Adds another piece's counts (its loops after these).
  void add(const LineRepairCounts& other);
};

// One clipped piece as its repair left it.
struct RepairedPiece {
  std::vector<Vec2> points;  // empty: nothing with length was left, the piece is dropped
  LineRepairCounts counts;   // what repairing this piece alone changed
};

// Both or neither set. lookup gives what `store` was given under the same key, or nullopt.
struct LineRepairMemo {
  std::function<std::optional<RepairedPiece>(const ContentHash& key)> lookup;
  std::function<void(const ContentHash& key, const RepairedPiece& repaired)> store;

  explicit operator bool() const { return lookup && store; }
};

// The key of one piece's repair: its points, whether it is closed, the repair options and the
// repair's own version (kLineRepairVersion), so that a changed point, option or algorithm misses.
inline constexpr std::uint64_t kLineRepairVersion = 1;
ContentHash line_repair_key(const std::vector<Vec2>& points, bool closed,
                            const LineRepair& options);

}  // namespace tw
