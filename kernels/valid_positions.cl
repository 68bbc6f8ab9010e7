// findValidPositions (Zhou et al. 2013, Section 2), 64 positions per work-item as in the CPU
// backend: work-item (row, block) tests positions ux = 64 block .. 64 block + 63 of one row of
// u (uy = row - C in [-C, H)). Host wrapper: OpenCLBackend::find_valid_positions; CPU twin:
// the CPU backend's find_valid_positions.
//
// A position is valid when every must-be-clear texel is transparent (the top and bottom edges
// do not cut the pattern, nothing opaque lands on a forbidden canvas pixel) and at least
// min_opaque interior texels are opaque (the piece is not empty; the paper's rule is
// min_opaque = 1). `bits` holds the exemplar's opacity (alpha >= 128), one bit per texel,
// words_per_row 64-bit words per texel row; texels outside the exemplar read as transparent.

ulong word_at(global const ulong* bits, int words_per_row, int height, int y, int w) {
  return (y >= 0 && y < height && w >= 0 && w < words_per_row) ? bits[(long)y * words_per_row + w]
                                                              : 0ul;
}

// The opacity of texels (x .. x + 63, y), bit i for texel x + i.
ulong window(global const ulong* bits, int words_per_row, int height, int x, int y) {
  const int w = x >= 0 ? x / 64 : -((-x + 63) / 64);
  const int shift = x - 64 * w;
  const ulong low = word_at(bits, words_per_row, height, y, w);
  if (shift == 0) return low;
  return (low >> shift) | (word_at(bits, words_per_row, height, y, w + 1) << (64 - shift));
}

// Opaque interior texels at position (x, uy), at least up to `enough`: one popcount per 64
// texels of each row run (dy, first dx, last dx) of the interior (synth/detail/opaque_count.hpp,
// row_runs: every listed offset counted once).
int opaque_count(global const ulong* bits, int words_per_row, int height, global const int4* runs,
                 int run_count, int x, int uy, int enough) {
  int count = 0;
  for (int i = 0; i < run_count && count < enough; ++i) {
    const int4 run = runs[i];
    for (int first = run.y; first <= run.z; first += 64) {
      const int n = min(64, run.z - first + 1);
      const ulong w = window(bits, words_per_row, height, x + first, uy + run.x);
      count += (int)popcount(n == 64 ? w : w & ((1ul << n) - 1ul));
    }
  }
  return count;
}

kernel void find_valid_positions(global const ulong* bits, int words_per_row, int width,
                                 int height, int column, global const int2* must_be_clear,
                                 int clear_count, global const int2* interior, int interior_count,
                                 global const int4* interior_runs, int run_count, int min_opaque,
                                 global uchar* flags) {
  const int blocks = (width + 63) / 64;
  const int id = (int)get_global_id(0);
  if (id >= blocks * (height + column)) return;
  const int row = id / blocks, x0 = 64 * (id % blocks), uy = row - column;
  const int in_row = min(64, width - x0);
  const ulong all = in_row == 64 ? ~0ul : (1ul << in_row) - 1ul;
  ulong blocked = 0;
  for (int i = 0; i < clear_count && (blocked & all) != all; ++i)
    blocked |= window(bits, words_per_row, height, x0 + must_be_clear[i].x, uy + must_be_clear[i].y);
  const ulong open = all & ~blocked;
  ulong any = 0;
  for (int i = 0; i < interior_count && open && (any & open) != open; ++i)
    any |= window(bits, words_per_row, height, x0 + interior[i].x, uy + interior[i].y);
  const ulong valid = open & any;
  for (int lane = 0; lane < in_row; ++lane) {
    bool flag = (valid >> lane) & 1ul;
    if (flag && min_opaque > 1)
      flag = opaque_count(bits, words_per_row, height, interior_runs, run_count, x0 + lane, uy,
                          min_opaque) >= min_opaque;
    flags[(long)row * width + x0 + lane] = flag;
  }
}
