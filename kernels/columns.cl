// extractColumns (Zhou et al. 2013, Section 2): one work-item per valid position (a column of
// C samples). Host wrappers: OpenCLBackend::extract_right_columns / extract_left_columns;
// CPU twins: the CPU backend's functions of the same names.
//
// Positions are indices into U = W * (H + C): ux = index % W, uy = index / W - C.
// Texels outside the exemplar read as transparent black.

uint texel_at(global const uint* texels, int width, int height, int x, int y) {
  return (x >= 0 && x < width && y >= 0 && y < height) ? texels[y * width + x] : 0u;
}

// floor(value / 256) for negative values too (no reliance on signed shifts).
int floor_div256(int value) {
  return value >= 0 ? value / 256 : -((-value + 255) / 256);
}

// Bilinear sample at (px, py) in 1/256 texel, texel centres at +128: every channel (alpha
// included) is weighted in 16-bit fixed point and rounded half up.
uint bilinear(global const uint* texels, int width, int height, int px, int py) {
  const int qx = px - 128;
  const int qy = py - 128;
  const int x0 = floor_div256(qx);
  const int y0 = floor_div256(qy);
  const uint wx = (uint)(qx - x0 * 256);
  const uint wy = (uint)(qy - y0 * 256);
  const uint t00 = texel_at(texels, width, height, x0, y0);
  const uint t10 = texel_at(texels, width, height, x0 + 1, y0);
  const uint t01 = texel_at(texels, width, height, x0, y0 + 1);
  const uint t11 = texel_at(texels, width, height, x0 + 1, y0 + 1);
  uint result = 0;
  for (uint shift = 0; shift < 32; shift += 8) {
    const uint c00 = (t00 >> shift) & 255u, c10 = (t10 >> shift) & 255u;
    const uint c01 = (t01 >> shift) & 255u, c11 = (t11 >> shift) & 255u;
    const uint top = c00 * (256u - wx) + c10 * wx;
    const uint bottom = c01 * (256u - wx) + c11 * wx;
    const uint value = (top * (256u - wy) + bottom * wy + 32768u) >> 16;
    result |= value << shift;
  }
  return result;
}

kernel void extract_right_columns(global const uint* texels, int width, int height, int column,
                                  global const int* right_fx, global const int* right_fy,
                                  global const int* indices, int count, global uint* samples) {
  const int j = (int)get_global_id(0);
  if (j >= count) return;
  const int index = indices[j];
  const int ux = index % width;
  const int uy = index / width - column;
  for (int k = 0; k < column; ++k) {
    samples[(long)j * column + k] =
        bilinear(texels, width, height, ux * 256 + right_fx[k], uy * 256 + right_fy[k]);
  }
}

kernel void extract_left_columns(global const uint* texels, int width, int height, int column,
                                 global const int* indices, int count, global uint* samples) {
  const int j = (int)get_global_id(0);
  if (j >= count) return;
  const int index = indices[j];
  const int ux = index % width;
  const int uy = index / width - column;
  for (int k = 0; k < column; ++k) {
    samples[(long)j * column + k] = texel_at(texels, width, height, ux, uy + k);
  }
}

// The pruning statistics of each column (synth/detail/edge_bound.hpp, make_edge_stats): its
// opaque mask (bit k of word k / 64: sample k has alpha >= 128), its R, G, B sums and the same
// sums per block of 16 samples. Host wrapper: OpenCLBackend::enqueue_stats; CPU twin:
// make_edge_stats.
kernel void edge_stats(global const uint* samples, int count, int column, global ulong* masks,
                       global int4* sums, global float* block_sums) {
  const int j = (int)get_global_id(0);
  if (j >= count) return;
  const int words = (column + 63) / 64, blocks = (column + 15) / 16;
  global const uint* s = samples + (long)j * column;
  for (int w = 0; w < words; ++w) {
    ulong mask = 0;
    for (int k = 64 * w; k < min(column, 64 * (w + 1)); ++k)
      mask |= (ulong)(s[k] >> 31) << (k - 64 * w);
    masks[(long)j * words + w] = mask;
  }
  int4 total = (int4)(0);
  for (int b = 0; b < blocks; ++b) {
    int4 sum = (int4)(0);
    for (int k = 16 * b; k < min(column, 16 * (b + 1)); ++k)
      sum += (int4)((int)(s[k] & 255u), (int)((s[k] >> 8) & 255u), (int)((s[k] >> 16) & 255u), 0);
    block_sums[((long)j * blocks + b) * 3] = (float)sum.x;
    block_sums[((long)j * blocks + b) * 3 + 1] = (float)sum.y;
    block_sums[((long)j * blocks + b) * 3 + 2] = (float)sum.z;
    total += sum;
  }
  sums[j] = total;
}
