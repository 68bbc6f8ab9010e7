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
// Since gamma * m > limit prunes every candidate with a mismatched sample as soon as
// best - min P < gamma, the host groups the previous positions by exact opaque mask; each
// work-item first walks the group whose mask equals its left column's, and walks all previous
// positions only when the best found still leaves room for a mismatched sample.
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

struct Column {
  global const uint* samples;
  global const ulong* mask;
  int4 sums;
};

struct Previous {
  global const long* cost;  // sorted by (P[v], v)
  global const int* position;
  global const uint* samples;
  global const ulong* masks;
  global const int4* sums;
};

struct Costs {
  global const uint* distance_table;
  uint gamma, opaque_alpha;
  int mismatch_extra, binary_alpha, column, words;
};

// Considers previous rank r for the left column: updates (best, best_v) when P + D beats it.
// Returns false once P[r] alone exceeds best (no later rank of the same walk can win).
bool consider(int r, const struct Previous* prev, const struct Column* left, const struct Costs* c,
              long* best, int* best_v) {
  const long p = prev->cost[r];
  if (p > *best) return false;
  const int v = prev->position[r];
  const long limit = *best - p - (v > *best_v ? 1 : 0);
  if (limit < 0) return true;

  // No bound until a first candidate is complete (limit is then near LONG_MAX).
  if (*best_v != INT_MAX) {
    if (c->binary_alpha) {
      global const ulong* right_mask = prev->masks + (long)r * c->words;
      int mismatched = 0;
      for (int w = 0; w < c->words; ++w) mismatched += (int)popcount(right_mask[w] ^ left->mask[w]);
      if ((long)c->gamma * mismatched > limit) return true;
      if (colour_exceeds(prev->sums[r], left->sums,
                         limit + c->column - (long)c->mismatch_extra * mismatched))
        return true;
    } else if (colour_exceeds(prev->sums[r], left->sums, limit + c->column)) {
      return true;
    }
  }

  // D in blocks of 8 samples (branch-free inside), leaving as soon as it exceeds the limit.
  global const uint* right_column = prev->samples + (long)r * c->column;
  long d = 0;
  for (int k = 0; k < c->column && d <= limit; k += 8) {
    const int end = min(k + 8, c->column);
    for (int i = k; i < end; ++i) {
      d += xi(right_column[i], left->samples[i], c->distance_table, c->gamma, c->opaque_alpha,
              c->binary_alpha);
    }
  }
  if (d <= limit) {
    *best = p + d;  // strictly better, or equal with a lower v
    *best_v = v;
  }
  return true;
}

// group_start[g] .. group_start[g + 1]: the ranks (ascending) of previous positions whose
// opaque mask is the g-th distinct one; left_group[j]: the group of j's mask, or -1.
kernel void update_table_row(global const long* sorted_cost, global const int* sorted_position,
                             global const uint* sorted_right, global const ulong* sorted_masks,
                             global const int4* sorted_sums, int previous_count,
                             global const int* group_start, global const int* group_ranks,
                             global const uint* left, global const ulong* left_masks,
                             global const int4* left_sums, global const int* left_group,
                             int current_count, int column, global const uint* distance_table,
                             uint gamma, uint opaque_alpha, int mismatch_extra, int binary_alpha,
                             global long* cost, global int* argmin) {
  const int j = (int)get_global_id(0);
  if (j >= current_count) return;
  const struct Costs c = {distance_table, gamma,  opaque_alpha,      mismatch_extra,
                          binary_alpha,   column, (column + 63) / 64};
  const struct Previous prev = {sorted_cost, sorted_position, sorted_right, sorted_masks,
                                sorted_sums};
  const struct Column left_column = {left + (long)j * column, left_masks + (long)j * c.words,
                                     left_sums[j]};

  long best = LONG_MAX;
  int best_v = INT_MAX;
  const int group = binary_alpha ? left_group[j] : -1;
  if (group >= 0) {
    for (int i = group_start[group]; i < group_start[group + 1]; ++i) {
      if (!consider(group_ranks[i], &prev, &left_column, &c, &best, &best_v)) break;
    }
  }
  // Candidates with m >= 1 mismatched samples cost at least min P + gamma.
  if (group < 0 || best - sorted_cost[0] >= (long)gamma) {
    for (int r = 0; r < previous_count; ++r) {
      if (!consider(r, &prev, &left_column, &c, &best, &best_v)) break;
    }
  }
  cost[j] = best;
  argmin[j] = best_v == INT_MAX ? -1 : best_v;
}
