#include "geo/line_repair_memo.hpp"

#include "geo/features.hpp"

namespace tw {

void LineRepairCounts::add(const LineRepairCounts& other) {
  duplicates += other.duplicates;
  spikes += other.spikes;
  loops.insert(loops.end(), other.loops.begin(), other.loops.end());
  zero_length_parts += other.zero_length_parts;
  self_crossings += other.self_crossings;
}

ContentHash line_repair_key(const std::vector<Vec2>& points, bool closed,
                            const LineRepair& options) {
  return Hasher()
      .text("terraweave.line_repair")
      .u64(kLineRepairVersion)
      .points(points)
      .boolean(closed)
      .real(options.merge_distance)
      .real(options.spike_angle)
      .real(options.min_loop)
      .digest();
}

}  // namespace tw
