// compactValidPositions (Zhou et al. 2013, Section 2): a parallel stream compaction in three
// kernels, so the ascending order of the indices is guaranteed by construction:
//   1. scan_blocks: each work-group computes the exclusive prefix sums of its flags in local
//      memory (Hillis-Steele) and writes its block total;
//   2. scan_block_sums: one work-group turns the block totals into exclusive block offsets,
//      looping over chunks of its size with a running carry (any number of blocks);
//   3. scatter_valid: every set flag writes its index at block offset + local offset.
// Host wrapper: OpenCLBackend::compact_valid_positions; CPU twin: the CPU backend's
// compact_valid_positions.

// Inclusive Hillis-Steele scan of `values` (one per work-item) in local memory.
uint inclusive_scan(local uint* scratch, uint value) {
  const uint lid = get_local_id(0);
  const uint size = get_local_size(0);
  scratch[lid] = value;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (uint offset = 1; offset < size; offset <<= 1) {
    const uint add = lid >= offset ? scratch[lid - offset] : 0u;
    barrier(CLK_LOCAL_MEM_FENCE);
    scratch[lid] += add;
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  return scratch[lid];
}

kernel void scan_blocks(global const uchar* flags, uint count, global uint* local_offsets,
                        global uint* block_sums, local uint* scratch) {
  const uint gid = get_global_id(0);
  const uint flag = gid < count ? (uint)(flags[gid] != 0) : 0u;
  const uint inclusive = inclusive_scan(scratch, flag);
  if (gid < count) local_offsets[gid] = inclusive - flag;
  if (get_local_id(0) == get_local_size(0) - 1) block_sums[get_group_id(0)] = inclusive;
}

// block_offsets[b] = sum of block_sums[0..b); block_offsets[block_count] = the total.
kernel void scan_block_sums(global const uint* block_sums, uint block_count,
                            global uint* block_offsets, local uint* scratch) {
  const uint lid = get_local_id(0);
  const uint size = get_local_size(0);
  uint carry = 0;
  for (uint base = 0; base < block_count; base += size) {
    const uint b = base + lid;
    const uint value = b < block_count ? block_sums[b] : 0u;
    const uint inclusive = inclusive_scan(scratch, value);
    if (b < block_count) block_offsets[b] = carry + inclusive - value;
    carry += scratch[size - 1];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid == 0) block_offsets[block_count] = carry;
}

kernel void scatter_valid(global const uchar* flags, uint count, global const uint* local_offsets,
                          global const uint* block_offsets, global int* indices) {
  const uint gid = get_global_id(0);
  if (gid < count && flags[gid] != 0) {
    indices[block_offsets[get_group_id(0)] + local_offsets[gid]] = (int)gid;
  }
}
