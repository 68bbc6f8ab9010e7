// computeCostTable + updateTableRow (Zhou et al. 2013, Section 2), fused and pruned exactly as
// the CPU backend's row (synth/detail/cpu_backend.cpp, update_table_row_pruned): for every
// current position j, the lexicographic minimum of (P[v] + D(right_v, left_j), v) over the
// previous positions v, so the U x U cost table is never materialized. Host wrapper:
// OpenCLBackend::run_row (synth/detail/opencl_dp_row.cpp).
//
// The host orders the previous positions in "slots" (synth/detail/mask_groups.hpp): grouped
// by exact opaque mask, groups in increasing lowest P, members in increasing (P, v). Each j
// tries its neighbour's argmin first, walks the group of its own mask (no mismatched sample),
// then the other groups only while min P + mismatch * m can still win (m = popcount of the
// mask difference). Per candidate, cheapest first: P alone (stop the walk), mismatch * m, the
// whole-edge colour-sum bound (exact integers), the per-16-sample block bound (float, lowered
// by a margin: it only skips), then D with an early exit every 16 samples (edge_bound.hpp has
// the proofs). Every bound is a true lower bound and ties keep the lowest v, so the result is
// the exact optimum whatever is skipped: the same bytes as the CPU and as `prune = 0` (every
// pair, every sample).
//
// A work-group handles a tile of group_size * per_item consecutive current positions; it first
// copies their left columns into local memory (each is read once per candidate evaluated);
// work-item t then handles per_item consecutive positions in order, each starting from the
// previous one's argmin.

// floor(sqrt(x)) for x = 256 d2 < 2^26 from one float root; x is exact in float and the root
// is off by less than one, which the two integer comparisons correct.
int colour_term(int d2) {
  const int x = 256 * d2;
  int r = (int)sqrt((float)x);
  if (r * r > x) --r;
  if ((r + 1) * (r + 1) <= x) ++r;
  return r;
}

// xi(p, q) of synth/detail/cost.hpp. Binary alpha: gamma when exactly one of p, q is opaque
// (alpha >= 128 is the top bit), else the colour term. Continuous alpha (a, b):
// floor((w_same * colour + w_diff * gamma) / 255^2).
int xi(uint p, uint q, int binary_alpha, int gamma) {
  const int dr = (int)(p & 255u) - (int)(q & 255u);
  const int dg = (int)((p >> 8) & 255u) - (int)((q >> 8) & 255u);
  const int db = (int)((p >> 16) & 255u) - (int)((q >> 16) & 255u);
  const int colour = colour_term(dr * dr + dg * dg + db * db);
  if (binary_alpha) return ((p ^ q) >> 31) ? gamma : colour;
  const long a = p >> 24, b = q >> 24;
  const long same = a * b + (255 - a) * (255 - b), diff = a * (255 - b) + (255 - a) * b;
  return (int)((same * colour + diff * gamma) / (255 * 255));
}

// The sum of xi over 8 samples with binary alpha: xi of each lane as above (the same float
// root and integer corrections), 8 lanes per vector instruction on CPU devices.
int xi_sum8(uint8 p, uint8 q, int gamma) {
  const int8 dr = convert_int8(p & 255u) - convert_int8(q & 255u);
  const int8 dg = convert_int8((p >> 8) & 255u) - convert_int8((q >> 8) & 255u);
  const int8 db = convert_int8((p >> 16) & 255u) - convert_int8((q >> 16) & 255u);
  const int8 x = 256 * (dr * dr + dg * dg + db * db);
  int8 r = convert_int8(sqrt(convert_float8(x)));
  r += r * r > x;             // a true comparison is -1
  r -= (r + 1) * (r + 1) <= x;
  const int8 xi = select(r, (int8)(gamma), ((p ^ q) >> 31) != 0u);
  const int4 sum4 = xi.lo + xi.hi;
  const int2 sum2 = sum4.lo + sum4.hi;
  return sum2.x + sum2.y;
}

struct Edges {
  global const uint* right_samples;  // by v
  global const ulong* right_masks;
  global const int4* right_sums;
  global const float* right_blocks;
  global const long* slot_cost;      // P by slot
  global const int* slot_position;   // slot -> v
  int column, words, blocks, binary_alpha, gamma, prune;
  long mismatch, mismatch_extra;
};

struct Left {
  local const uint* samples;
  global const ulong* mask;
  int4 sums;
  global const float* blocks;
};

int mismatched(global const ulong* a, global const ulong* b, int words) {
  int m = 0;
  for (int w = 0; w < words; ++w) m += (int)popcount(a[w] ^ b[w]);
  return m;
}

// True when the whole-edge bound 16 |dS| - C + mismatch_extra * m proves D > limit.
bool whole_edge_exceeds(const struct Edges* e, int v, const struct Left* left, int m, long limit) {
  const long rhs = limit + e->column - e->mismatch_extra * m;
  if (rhs < 0) return true;
  if (rhs >= (1L << 31)) return false;
  const int4 r = e->right_sums[v];
  const long dr = r.x - left->sums.x, dg = r.y - left->sums.y, db = r.z - left->sums.z;
  return 256 * (dr * dr + dg * dg + db * db) > rhs * rhs;
}

// Sum over blocks of max(0, 16 |dS_b| - n_b), lowered by a margin for float rounding.
float block_bound(const struct Edges* e, int v, const struct Left* left) {
  global const float* r = e->right_blocks + (long)v * e->blocks * 3;
  float bound = 0.0f;
  for (int b = 0; b < e->blocks; ++b) {
    const float dr = r[3 * b] - left->blocks[3 * b], dg = r[3 * b + 1] - left->blocks[3 * b + 1];
    const float db = r[3 * b + 2] - left->blocks[3 * b + 2];
    const int size = min(e->column, (b + 1) * 16) - b * 16;
    bound += max(0.0f, 16.0f * sqrt(dr * dr + dg * dg + db * db) - (float)size);
  }
  return bound * (1.0f - 1e-4f) - 1.0f;
}

// D(right_v, left) with an early exit: a value > limit as soon as a partial sum passes it.
long edge_cost(const struct Edges* e, int v, const struct Left* left, long limit) {
  global const uint* right = e->right_samples + (long)v * e->column;
  long sum = 0;
  for (int k0 = 0; k0 < e->column; k0 += 16) {
    const int k1 = min(e->column, k0 + 16);
    int block = 0, k = k0;
    if (e->binary_alpha)
      for (; k + 8 <= k1; k += 8)
        block += xi_sum8(vload8(0, right + k), vload8(0, left->samples + k), e->gamma);
    for (; k < k1; ++k) block += xi(right[k], left->samples[k], e->binary_alpha, e->gamma);
    sum += block;
    if (sum > limit) return sum;
  }
  return sum;
}

// Considers slot s (m mismatched samples): false once P alone exceeds the best, so that no
// later slot of an increasing-P walk can win.
bool consider(const struct Edges* e, const struct Left* left, int s, int m, long* best,
              int* best_v) {
  const long p = e->slot_cost[s];
  if (p > *best) return false;
  const int v = e->slot_position[s];
  const long limit = *best - p - (v > *best_v ? 1 : 0);  // ties go to the lowest v
  if (limit < 0) return true;
  if (*best_v != INT_MAX) {
    if (e->mismatch * m > limit) return true;
    if (whole_edge_exceeds(e, v, left, m, limit)) return true;
    if (limit < (1L << 24) && block_bound(e, v, left) > (float)limit) return true;
  }
  const long d = edge_cost(e, v, left, limit);
  if (d <= limit) {  // strictly better, or equal with a lower v
    *best = p + d;
    *best_v = v;
  }
  return true;
}

// The exact minimum for left position j, pruned.
void pruned_minimum(const struct Edges* e, const struct Left* left, int neighbour,
                    int previous_count, global const int* slot_of, global const int* group_begin,
                    global const int* bucket_begin, global const int* scan_group,
                    global const long* scan_min, global const ulong* scan_masks, int scan_stride,
                    int own, long* best, int* best_v) {
  // A good first guess makes the bounds prune from the start: consecutive current positions
  // are usually exemplar neighbours, and so are their optimal predecessors.
  if (neighbour >= 0) {
    for (int v = neighbour; v <= neighbour + 1 && v < previous_count; ++v)
      consider(e, left, slot_of[v], mismatched(e->right_masks + (long)v * e->words, left->mask,
                                               e->words),
               best, best_v);
  }
  if (own >= 0) {
    for (int s = group_begin[own]; s < group_begin[own + 1]; ++s)
      if (!consider(e, left, s, 0, best, best_v)) break;
  }
  if (own >= 0 && *best - e->slot_cost[0] < e->mismatch) return;
  // The other groups, bucketed by their number of opaque samples c (the host lists each bucket
  // in increasing lowest P, padded to 8 entries, scan_group -1 for padding): a group of bucket
  // c has m >= max(1, |c - q|) mismatched samples for a left mask of q opaque ones, so buckets
  // are visited at growing distance d while the row's lowest P + mismatch * max(1, d) can still
  // win, and inside a bucket while its lowest P + mismatch * max(1, d) can. 8 groups per test
  // (vector popcounts over word-major masks, scan_stride apart); the best only falls, so each
  // test keeps a superset of the groups that can win.
  int q = 0;
  for (int w = 0; w < e->words; ++w) q += (int)popcount(left->mask[w]);
  for (int d = 0; d <= e->column; ++d) {
    const long least = e->mismatch * max(d, 1);
    if (e->slot_cost[0] + least > *best) break;
    for (int side = 0; side < (d == 0 ? 1 : 2); ++side) {
      const int c = side == 0 ? q - d : q + d;
      if (c < 0 || c > e->column) continue;
      for (int i0 = bucket_begin[c]; i0 < bucket_begin[c + 1]; i0 += 8) {
        if (scan_min[i0] + least > *best) break;
        ulong8 m8 = (ulong8)(0);
        for (int w = 0; w < e->words; ++w)
          m8 += popcount(vload8(0, scan_masks + (long)w * scan_stride + i0) ^
                         (ulong8)(left->mask[w]));
        const long8 bound8 = vload8(0, scan_min + i0) + as_long8(m8) * e->mismatch;
        if (!any(bound8 <= (long8)(*best))) continue;
        long bound[8], mismatches[8];
        vstore8(bound8, 0, bound);
        vstore8(as_long8(m8), 0, mismatches);
        for (int i = 0; i < 8; ++i) {
          const int g = scan_group[i0 + i];
          if (g < 0 || g == own || bound[i] > *best) continue;
          const long gap = e->mismatch * mismatches[i];
          for (int s = group_begin[g]; s < group_begin[g + 1] && e->slot_cost[s] + gap <= *best;
               ++s)
            if (!consider(e, left, s, (int)mismatches[i], best, best_v)) break;
        }
      }
    }
  }
}

// The definition: every previous position, every sample.
void full_minimum(const struct Edges* e, const struct Left* left, int previous_count,
                  global const int* slot_of, long* best, int* best_v) {
  for (int v = 0; v < previous_count; ++v) {
    const long total = e->slot_cost[slot_of[v]] + edge_cost(e, v, left, LONG_MAX);
    if (total < *best) {  // v ascends: strict < keeps the lowest v
      *best = total;
      *best_v = v;
    }
  }
}

kernel void update_table_row(
    global const long* slot_cost, global const int* slot_position, global const int* slot_of,
    int previous_count, global const int* group_begin, global const int* bucket_begin,
    global const int* scan_group, global const long* scan_min, global const ulong* scan_masks,
    int scan_stride, global const uint* right_samples, global const ulong* right_masks,
    global const int4* right_sums, global const float* right_blocks,
    global const uint* left_samples, global const ulong* left_masks, global const int4* left_sums,
    global const float* left_blocks, global const int* left_group, int current_count, int column,
    int binary_alpha, int gamma, long mismatch, long mismatch_extra, int per_item, int prune,
    local uint* tile, global long* cost, global int* argmin) {
  const int local_id = (int)get_local_id(0), group_size = (int)get_local_size(0);
  const int tile_size = group_size * per_item;
  const int tile_begin = (int)get_group_id(0) * tile_size;
  const int tile_count = min(tile_size, current_count - tile_begin);
  for (int i = local_id; i < tile_count * column; i += group_size)
    tile[i] = left_samples[(long)tile_begin * column + i];
  barrier(CLK_LOCAL_MEM_FENCE);

  const int words = (column + 63) / 64, blocks = (column + 15) / 16;
  const struct Edges e = {right_samples, right_masks, right_sums, right_blocks, slot_cost,
                          slot_position, column,      words,      blocks,       binary_alpha,
                          gamma,         prune,       mismatch,   mismatch_extra};
  int neighbour = -1;
  for (int k = 0; k < per_item; ++k) {
    const int in_tile = local_id * per_item + k;
    if (in_tile >= tile_count) break;
    const int j = tile_begin + in_tile;
    const struct Left left = {tile + (long)in_tile * column, left_masks + (long)j * words,
                              left_sums[j], left_blocks + (long)j * blocks * 3};
    long best = LONG_MAX;
    int best_v = INT_MAX;
    if (prune)
      pruned_minimum(&e, &left, neighbour, previous_count, slot_of, group_begin, bucket_begin,
                     scan_group, scan_min, scan_masks, scan_stride, left_group[j], &best, &best_v);
    else
      full_minimum(&e, &left, previous_count, slot_of, &best, &best_v);
    cost[j] = best;
    argmin[j] = best_v == INT_MAX ? -1 : best_v;
    neighbour = argmin[j];
  }
}

// The previous costs in slot order: slot_cost[s] = cost[slot_position[s]] (the cost row stays
// on the device between rows; only the slot order comes from the host).
kernel void gather_slot_costs(global const long* cost, global const int* slot_position, int count,
                              global long* slot_cost) {
  const int s = (int)get_global_id(0);
  if (s < count) slot_cost[s] = cost[slot_position[s]];
}
