// computeCostTable + updateTableRow (Zhou et al. 2013, Section 2), fused: one work-item per
// current valid position j loops over the previous valid positions v and keeps the exact
// lexicographic minimum of (P[v] + D(right_v, left_j), v), so the U x U cost table is never
// materialized. Host wrapper: OpenCLBackend::update_table_row; CPU twin: the CPU backend's
// update_table_row.
//
// Exact pruning (DESIGN.md "Exact pruning"): the host sorts the previous positions by
// (P[v], v) ascending and passes per column its opaque mask (one bit per sample, 64 per word)
// and its sums of R, G, B. With m = popcount(right mask ^ left mask), the exact number of
// samples whose alphas differ (binary alpha):
//   D >= gamma * m, and
//   D >= 16 |difference of colour sums| - C + mismatch_extra * m,
// because a matched sample costs floor(16 |p - q|) >= 16 |p - q| - 1 and a mismatched one
// costs gamma >= 16 |p - q| - 1 + mismatch_extra (gamma exceeds any colour term), summed with
// the triangle inequality. Continuous alpha keeps the colour bound with m = 0.
// A candidate can only win when D <= limit = best - P[v] (- 1 when v > best v: a tie goes to
// the lowest v); once P[v] alone exceeds best, no later candidate can win and the walk stops.
// Every test is an exact integer comparison (the colour one squared), so the result is the
// exact lexicographic optimum, the same as the CPU twin's.

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

// True when the colour bound 16 |dS| - reach_offset exceeds limit, i.e. 16 |dS| > rhs.
bool colour_exceeds(int4 right, int4 left, long rhs) {
  if (rhs < 0) return true;
  if (rhs >= (1L << 31)) return false;  // 16 |dS| stays far below 2^31 for any sane C
  const long dr = right.x - left.x, dg = right.y - left.y, db = right.z - left.z;
  return 256 * (dr * dr + dg * dg + db * db) > rhs * rhs;
}

kernel void update_table_row(global const long* sorted_cost, global const int* sorted_position,
                             global const uint* sorted_right, global const ulong* sorted_masks,
                             global const int4* sorted_sums, int previous_count,
                             global const uint* left, global const ulong* left_masks,
                             global const int4* left_sums, int current_count, int column,
                             global const uint* distance_table, uint gamma, uint opaque_alpha,
                             int mismatch_extra, int binary_alpha, global long* cost,
                             global int* argmin) {
  const int j = (int)get_global_id(0);
  if (j >= current_count) return;
  const int words = (column + 63) / 64;
  global const uint* left_column = left + (long)j * column;
  global const ulong* left_mask = left_masks + (long)j * words;
  const int4 left_sum = left_sums[j];

  long best = LONG_MAX;
  int best_v = INT_MAX;
  for (int r = 0; r < previous_count; ++r) {
    const long p = sorted_cost[r];
    if (p > best) break;
    const int v = sorted_position[r];
    const long limit = best - p - (v > best_v ? 1 : 0);
    if (limit < 0) continue;

    // No bound until a first candidate is complete (limit is then near LONG_MAX).
    if (best_v != INT_MAX) {
      if (binary_alpha) {
        global const ulong* right_mask = sorted_masks + (long)r * words;
        int mismatched = 0;
        for (int w = 0; w < words; ++w) mismatched += (int)popcount(right_mask[w] ^ left_mask[w]);
        if ((long)gamma * mismatched > limit) continue;
        if (colour_exceeds(sorted_sums[r], left_sum,
                           limit + column - (long)mismatch_extra * mismatched))
          continue;
      } else if (colour_exceeds(sorted_sums[r], left_sum, limit + column)) {
        continue;
      }
    }

    // D in blocks of 8 samples (branch-free inside), leaving as soon as it exceeds the limit.
    global const uint* right_column = sorted_right + (long)r * column;
    long d = 0;
    for (int k = 0; k < column && d <= limit; k += 8) {
      const int end = min(k + 8, column);
      for (int i = k; i < end; ++i) {
        d += xi(right_column[i], left_column[i], distance_table, gamma, opaque_alpha, binary_alpha);
      }
    }
    if (d > limit) continue;
    best = p + d;  // d <= limit: strictly better, or equal with a lower v
    best_v = v;
  }
  cost[j] = best;
  argmin[j] = best_v == INT_MAX ? -1 : best_v;
}
