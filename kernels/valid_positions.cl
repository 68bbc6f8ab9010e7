// findValidPositions (Zhou et al. 2013, Section 2): one work-item per position u of the
// exemplar, u = (ux, uy) with uy in [-C, H). Host wrapper: OpenCLBackend::find_valid_positions;
// CPU twin: the CPU backend's find_valid_positions.
//
// A position is valid when every must-be-clear texel is transparent (the top and bottom edges
// do not cut the pattern, nothing opaque lands on a forbidden canvas pixel) and at least one
// min_opaque interior texels are opaque (the piece is not empty; the paper's rule is
// min_opaque = 1). Texels outside the exemplar read as transparent black.

uint texel_at(global const uint* texels, int width, int height, int x, int y) {
  return (x >= 0 && x < width && y >= 0 && y < height) ? texels[y * width + x] : 0u;
}

kernel void find_valid_positions(global const uint* texels, int width, int height, int column,
                                 global const int2* must_be_clear, int clear_count,
                                 global const int2* interior, int interior_count, int min_opaque,
                                 uint opaque_alpha, global uchar* flags) {
  const int index = (int)get_global_id(0);
  if (index >= width * (height + column)) return;
  const int ux = index % width;
  const int uy = index / width - column;

  uchar valid = 1;
  for (int i = 0; i < clear_count && valid; ++i) {
    const uint t =
        texel_at(texels, width, height, ux + must_be_clear[i].x, uy + must_be_clear[i].y);
    valid = (t >> 24) < opaque_alpha;
  }
  int opaque = 0;
  for (int i = 0; i < interior_count && valid && opaque < min_opaque; ++i) {
    const uint t = texel_at(texels, width, height, ux + interior[i].x, uy + interior[i].y);
    opaque += (t >> 24) >= opaque_alpha;
  }
  flags[index] = valid && opaque >= min_opaque;
}
