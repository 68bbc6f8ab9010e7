// computeCostTable + updateTableRow (Zhou et al. 2013, Section 2), fused: one work-item per
// current valid position j loops over the previous valid positions v and keeps the exact
// lexicographic minimum of (P[v] + D(right_v, left_j), v), so the U x U cost table is never
// materialized. Host wrapper: OpenCLBackend::update_table_row; CPU twin: the CPU backend's
// update_table_row.
//
// Exact pruning (docs: DESIGN.md "Exact pruning"): the host sorts the previous positions by
// (P[v], v) ascending and passes per-column statistics (opaque count, sums of R, G, B).
// Because gamma exceeds any colour distance, xi(p, q) >= floor(16 |p - q|) >= 16 |p - q| - 1,
// so D >= gamma * |opaque count difference| and D >= 16 |difference of colour sums| - C.
// A candidate whose P[v] + bound exceeds the best total cannot win, and once P[v] alone
// exceeds it no later candidate can: the walk stops. Both tests compare integers exactly
// (the colour one squared), and ties are never pruned, so the result is the exact optimum
// whatever the visiting order of work-items.

// xi(p, q) as in synth/detail/cost.hpp. The colour term floor(16 |p - q|) over RGB comes
// from the host's table of floor(sqrt(256 d2)) (no floating point anywhere). Binary alpha:
// gamma when exactly one of p, q is opaque, else the colour term. Continuous alpha (a, b):
// floor((w_same * colour + w_diff * gamma) / 255^2), which stays below 2^31.
uint xi(uint p, uint q, global const uint* distance_table, uint gamma, uint opaque_alpha,
        int binary_alpha) {
  const int dr = (int)(p & 255u) - (int)(q & 255u);
  const int dg = (int)((p >> 8) & 255u) - (int)((q >> 8) & 255u);
  const int db = (int)((p >> 16) & 255u) - (int)((q >> 16) & 255u);
  const uint colour = distance_table[(uint)(dr * dr + dg * dg + db * db)];
  const uint a = p >> 24, b = q >> 24;
  if (binary_alpha) {
    const uint mismatch = (uint)((a >= opaque_alpha) != (b >= opaque_alpha));
    return select(colour, gamma, mismatch);
  }
  const uint same = a * b + (255u - a) * (255u - b);
  const uint diff = a * (255u - b) + (255u - a) * b;
  return (same * colour + diff * gamma) / (255u * 255u);
}

// True when no candidate with these column statistics can bring P + D down to best (the
// opaque-count bound holds for binary alpha only; continuous xi is at least the colour term).
bool cannot_reach(int4 right, int4 left, long slack, int column, uint gamma, int binary_alpha) {
  if (binary_alpha && (long)gamma * (long)abs(right.x - left.x) > slack) return true;
  const long reach = slack + column;
  if (reach >= (1L << 31)) return false;
  const long dr = right.y - left.y, dg = right.z - left.z, db = right.w - left.w;
  return 256 * (dr * dr + dg * dg + db * db) > reach * reach;
}

kernel void update_table_row(global const long* sorted_cost, global const int* sorted_position,
                             global const uint* sorted_right, global const int4* sorted_stats,
                             int previous_count, global const uint* left,
                             global const int4* left_stats, int current_count, int column,
                             global const uint* distance_table, uint gamma, uint opaque_alpha,
                             int binary_alpha, global long* cost, global int* argmin) {
  const int j = (int)get_global_id(0);
  if (j >= current_count) return;
  global const uint* left_column = left + (long)j * column;
  const int4 left_stat = left_stats[j];

  long best = LONG_MAX;
  int best_v = -1;
  for (int r = 0; r < previous_count; ++r) {
    const long p = sorted_cost[r];
    if (p > best) break;
    const long slack = best - p;  // >= 0; LONG_MAX - p until a first candidate is complete
    if (best_v >= 0 && cannot_reach(sorted_stats[r], left_stat, slack, column, gamma, binary_alpha))
      continue;

    // D in blocks of 8 samples (branch-free inside), leaving as soon as it exceeds the slack.
    global const uint* right_column = sorted_right + (long)r * column;
    long d = 0;
    for (int k = 0; k < column && d <= slack; k += 8) {
      const int end = min(k + 8, column);
      for (int i = k; i < end; ++i) {
        d += xi(right_column[i], left_column[i], distance_table, gamma, opaque_alpha, binary_alpha);
      }
    }
    if (d > slack) continue;
    const long total = p + d;
    const int v = sorted_position[r];
    if (total < best || (total == best && v < best_v)) {
      best = total;
      best_v = v;
    }
  }
  cost[j] = best;
  argmin[j] = best_v;
}
