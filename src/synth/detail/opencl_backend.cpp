#include "synth/detail/opencl_backend.hpp"

#include <algorithm>
#include <numeric>
#include <string>
#include <unordered_map>

#include "core/error.hpp"
#include "synth/detail/cost.hpp"

namespace tw::detail {

namespace {

constexpr std::size_t kScanGroup = 256;   // work-group size of the compaction scan
constexpr std::size_t kColumnGroup = 64;  // one work-item per column
constexpr std::size_t kRowGroup = 16;     // small groups balance the pruned walks
constexpr std::uint32_t kMaxColourDistance2 = 3 * 255 * 255;
// A mismatched sample costs gamma, at least this much more than 16 |p - q| - 1.
constexpr std::int32_t kMismatchExtra = kGamma - kMaxColourTerm - 1;

// floor(sqrt(n)) in integers only.
std::uint32_t integer_sqrt(std::uint64_t n) {
  std::uint64_t low = 0, high = std::min<std::uint64_t>(n, 0xFFFFFFFFu) + 1;
  while (high - low > 1) {
    std::uint64_t mid = (low + high) / 2;
    (mid * mid <= n ? low : high) = mid;
  }
  return std::uint32_t(low);
}

// Buffers may not be empty in OpenCL: an empty vector becomes one zero element.
template <class T>
cl::Buffer input_buffer(const cl::Context& context, const std::vector<T>& values) {
  std::vector<T> padded;
  const std::vector<T>* source = &values;
  if (values.empty()) {
    padded.resize(1);
    source = &padded;
  }
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, source->size() * sizeof(T),
                    const_cast<T*>(source->data()), &status);
  check_cl(status, "clCreateBuffer (input)");
  return buffer;
}

cl::Buffer output_buffer(const cl::Context& context, std::size_t bytes) {
  cl_int status = CL_SUCCESS;
  cl::Buffer buffer(context, CL_MEM_READ_WRITE, std::max<std::size_t>(bytes, 16), nullptr, &status);
  check_cl(status, "clCreateBuffer (output)");
  return buffer;
}

template <class T>
void read_buffer(const cl::CommandQueue& queue, const cl::Buffer& buffer, std::vector<T>& out) {
  if (out.empty()) return;
  check_cl(queue.enqueueReadBuffer(buffer, CL_TRUE, 0, out.size() * sizeof(T), out.data()),
           "clEnqueueReadBuffer");
}

template <class... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (check_cl(kernel.setArg(index++, args), "clSetKernelArg"), ...);
}

// The pruning statistics of each column: its opaque mask (bit k of word k / 64 set when
// sample k is opaque) and its sums of R, G, B (kernels/row_update.cl).
struct ColumnStats {
  std::vector<cl_ulong> masks;  // count * words
  std::vector<cl_int4> sums;    // count
};

ColumnStats column_stats(const ColumnSet& set, std::size_t count) {
  const std::size_t words = (std::size_t(set.column) + 63) / 64;
  ColumnStats stats{std::vector<cl_ulong>(count * words, 0), std::vector<cl_int4>(count)};
  for (std::size_t j = 0; j < count; ++j) {
    cl_int4 sum{{0, 0, 0, 0}};
    for (std::size_t k = 0; k < std::size_t(set.column); ++k) {
      const std::uint32_t t = set.samples[j * set.column + k];
      if (is_opaque(t)) stats.masks[j * words + k / 64] |= cl_ulong(1) << (k % 64);
      for (int c = 0; c < 3; ++c) sum.s[c] += cl_int(channel_of(t, c));
    }
    stats.sums[j] = sum;
  }
  return stats;
}

// Previous positions grouped by exact opaque mask (ranks ascending within a group), and the
// group of each current column's mask (-1 when no previous position shares it).
struct MaskGroups {
  std::vector<cl_int> start{0};  // groups + 1
  std::vector<cl_int> ranks;
  std::vector<cl_int> of_left;
};

MaskGroups group_by_mask(const ColumnStats& previous, std::size_t previous_count,
                         const ColumnStats& left, std::size_t left_count, std::size_t words) {
  auto key = [words](const ColumnStats& stats, std::size_t j) {
    return std::string(reinterpret_cast<const char*>(stats.masks.data() + j * words),
                       words * sizeof(cl_ulong));
  };
  std::unordered_map<std::string, int> group_of;
  std::vector<std::vector<cl_int>> members;
  for (std::size_t r = 0; r < previous_count; ++r) {
    auto [it, added] = group_of.try_emplace(key(previous, r), int(members.size()));
    if (added) members.emplace_back();
    members[std::size_t(it->second)].push_back(cl_int(r));
  }
  MaskGroups groups;
  for (const auto& group : members) {
    groups.ranks.insert(groups.ranks.end(), group.begin(), group.end());
    groups.start.push_back(cl_int(groups.ranks.size()));
  }
  groups.of_left.resize(left_count);
  for (std::size_t j = 0; j < left_count; ++j) {
    auto found = group_of.find(key(left, j));
    groups.of_left[j] = found == group_of.end() ? -1 : found->second;
  }
  return groups;
}

std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

}  // namespace

const char* cl_error_name(cl_int status) {
  switch (status) {
    case CL_SUCCESS:
      return "CL_SUCCESS";
    case CL_DEVICE_NOT_FOUND:
      return "CL_DEVICE_NOT_FOUND";
    case CL_DEVICE_NOT_AVAILABLE:
      return "CL_DEVICE_NOT_AVAILABLE";
    case CL_COMPILER_NOT_AVAILABLE:
      return "CL_COMPILER_NOT_AVAILABLE";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE:
      return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_OUT_OF_RESOURCES:
      return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY:
      return "CL_OUT_OF_HOST_MEMORY";
    case CL_BUILD_PROGRAM_FAILURE:
      return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE:
      return "CL_INVALID_VALUE";
    case CL_INVALID_PLATFORM:
      return "CL_INVALID_PLATFORM";
    case CL_INVALID_DEVICE:
      return "CL_INVALID_DEVICE";
    case CL_INVALID_CONTEXT:
      return "CL_INVALID_CONTEXT";
    case CL_INVALID_COMMAND_QUEUE:
      return "CL_INVALID_COMMAND_QUEUE";
    case CL_INVALID_MEM_OBJECT:
      return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_BUILD_OPTIONS:
      return "CL_INVALID_BUILD_OPTIONS";
    case CL_INVALID_PROGRAM:
      return "CL_INVALID_PROGRAM";
    case CL_INVALID_PROGRAM_EXECUTABLE:
      return "CL_INVALID_PROGRAM_EXECUTABLE";
    case CL_INVALID_KERNEL_NAME:
      return "CL_INVALID_KERNEL_NAME";
    case CL_INVALID_KERNEL:
      return "CL_INVALID_KERNEL";
    case CL_INVALID_ARG_INDEX:
      return "CL_INVALID_ARG_INDEX";
    case CL_INVALID_ARG_VALUE:
      return "CL_INVALID_ARG_VALUE";
    case CL_INVALID_ARG_SIZE:
      return "CL_INVALID_ARG_SIZE";
    case CL_INVALID_KERNEL_ARGS:
      return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE:
      return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_WORK_ITEM_SIZE:
      return "CL_INVALID_WORK_ITEM_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE:
      return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_BUFFER_SIZE:
      return "CL_INVALID_BUFFER_SIZE";
    case CL_PLATFORM_NOT_FOUND_KHR:
      return "CL_PLATFORM_NOT_FOUND_KHR";
    default:
      return "unknown OpenCL error";
  }
}

void check_cl(cl_int status, const char* what) {
  if (status != CL_SUCCESS) fail("OpenCL: {} failed: {} ({})", what, cl_error_name(status), status);
}

OpenCLBackend::OpenCLBackend(OpenCLContext context) : context_(std::move(context)) {
  std::vector<std::uint32_t> table(kMaxColourDistance2 + 1);
  for (std::uint32_t d2 = 0; d2 <= kMaxColourDistance2; ++d2) table[d2] = integer_sqrt(256ull * d2);
  distance_table_ = input_buffer(context_.context(), table);
}

std::string OpenCLBackend::name() const {
  return "opencl (" + context_.device_name() + ")";
}

cl::Kernel& OpenCLBackend::kernel(const std::string& family, const std::string& name) {
  auto found = kernels_.find(name);
  if (found != kernels_.end()) return found->second;
  cl_int status = CL_SUCCESS;
  cl::Kernel made(context_.program(family), name.c_str(), &status);
  if (status != CL_SUCCESS) {
    fail("OpenCL: kernel {} not found in {}/{}.cl: {}", name, context_.kernel_dir(), family,
         cl_error_name(status));
  }
  return kernels_.emplace(name, made).first->second;
}

void OpenCLBackend::launch(cl::Kernel& kernel, const std::string& name, std::size_t items,
                           std::size_t local_size) {
  if (items == 0) return;
  cl::Event done;
  check_cl(context_.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                                 cl::NDRange(round_up(items, local_size)),
                                                 cl::NDRange(local_size), nullptr, &done),
           ("clEnqueueNDRangeKernel " + name).c_str());
  check_cl(done.wait(), ("waiting for kernel " + name).c_str());
  cl_ulong start = 0, end = 0;
  done.getProfilingInfo(CL_PROFILING_COMMAND_START, &start);
  done.getProfilingInfo(CL_PROFILING_COMMAND_END, &end);
  KernelTiming& timing = timings_[name];
  timing.milliseconds += double(end - start) * 1e-6;
  timing.launches += 1;
}

cl::Buffer OpenCLBackend::texel_buffer(const CostTexels& texels) {
  if (texels.rgba.size() != std::size_t(texels.width) * std::size_t(texels.height)) {
    fail("OpenCL backend: exemplar texels hold {} values, expected {} x {}", texels.rgba.size(),
         texels.width, texels.height);
  }
  return input_buffer(context_.context(), texels.rgba);
}

void OpenCLBackend::find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                                         const PieceFootprint& piece,
                                         std::vector<std::uint8_t>& flags) {
  const std::size_t count = std::size_t(space.count());
  flags.assign(count, 0);
  if (count == 0) return;
  const cl::Context& context = context_.context();
  cl::Buffer texel = texel_buffer(texels);
  cl::Buffer clear = input_buffer(context, piece.must_be_clear);
  cl::Buffer interior = input_buffer(context, piece.interior);
  cl::Buffer out = output_buffer(context, count);
  cl::Kernel& k = kernel("valid_positions", "find_valid_positions");
  set_args(k, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column), clear,
           cl_int(piece.must_be_clear.size()), interior, cl_int(piece.interior.size()),
           cl_int(piece.min_opaque), cl_uint(kOpaqueAlphaMin), out);
  launch(k, "find_valid_positions", count, kColumnGroup);
  read_buffer(context_.queue(), out, flags);
}

void OpenCLBackend::compact_valid_positions(const std::vector<std::uint8_t>& flags,
                                            std::vector<std::int32_t>& indices) {
  indices.clear();
  const std::size_t count = flags.size();
  if (count == 0) return;
  const cl::Context& context = context_.context();
  const std::size_t blocks = (count + kScanGroup - 1) / kScanGroup;
  cl::Buffer flag_buffer = input_buffer(context, flags);
  cl::Buffer local_offsets = output_buffer(context, count * sizeof(cl_uint));
  cl::Buffer block_sums = output_buffer(context, blocks * sizeof(cl_uint));
  cl::Buffer block_offsets = output_buffer(context, (blocks + 1) * sizeof(cl_uint));
  const cl::LocalSpaceArg scratch = cl::Local(kScanGroup * sizeof(cl_uint));

  cl::Kernel& scan = kernel("compact", "scan_blocks");
  set_args(scan, flag_buffer, cl_uint(count), local_offsets, block_sums, scratch);
  launch(scan, "scan_blocks", count, kScanGroup);

  cl::Kernel& sums = kernel("compact", "scan_block_sums");
  set_args(sums, block_sums, cl_uint(blocks), block_offsets, scratch);
  launch(sums, "scan_block_sums", kScanGroup, kScanGroup);

  cl_uint total = 0;
  check_cl(context_.queue().enqueueReadBuffer(block_offsets, CL_TRUE, blocks * sizeof(cl_uint),
                                              sizeof(cl_uint), &total),
           "clEnqueueReadBuffer (valid count)");
  if (total == 0) return;
  cl::Buffer out = output_buffer(context, total * sizeof(cl_int));
  cl::Kernel& scatter = kernel("compact", "scatter_valid");
  set_args(scatter, flag_buffer, cl_uint(count), local_offsets, block_offsets, out);
  launch(scatter, "scatter_valid", count, kScanGroup);
  indices.resize(total);
  read_buffer(context_.queue(), out, indices);
}

void OpenCLBackend::extract_right_columns(const CostTexels& texels, const PositionSpace& space,
                                          const PieceFootprint& piece,
                                          const std::vector<std::int32_t>& indices,
                                          ColumnSet& out) {
  if (piece.right_fx.size() != std::size_t(piece.column) ||
      piece.right_fy.size() != std::size_t(piece.column) || piece.column != space.column) {
    fail("OpenCL backend: piece footprint has {} / {} right samples for C = {} (space C = {})",
         piece.right_fx.size(), piece.right_fy.size(), piece.column, space.column);
  }
  out.column = space.column;
  out.binary_alpha = texels.binary_alpha;
  out.samples.assign(indices.size() * std::size_t(space.column), 0);
  if (out.samples.empty()) return;
  const cl::Context& context = context_.context();
  cl::Buffer texel = texel_buffer(texels);
  cl::Buffer fx = input_buffer(context, piece.right_fx);
  cl::Buffer fy = input_buffer(context, piece.right_fy);
  cl::Buffer index_buffer = input_buffer(context, indices);
  cl::Buffer samples = output_buffer(context, out.samples.size() * sizeof(cl_uint));
  cl::Kernel& k = kernel("columns", "extract_right_columns");
  set_args(k, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column), fx, fy,
           index_buffer, cl_int(indices.size()), samples);
  launch(k, "extract_right_columns", indices.size(), kColumnGroup);
  read_buffer(context_.queue(), samples, out.samples);
}

void OpenCLBackend::extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                                         const std::vector<std::int32_t>& indices, ColumnSet& out) {
  out.column = space.column;
  out.binary_alpha = texels.binary_alpha;
  out.samples.assign(indices.size() * std::size_t(space.column), 0);
  if (out.samples.empty()) return;
  const cl::Context& context = context_.context();
  cl::Buffer texel = texel_buffer(texels);
  cl::Buffer index_buffer = input_buffer(context, indices);
  cl::Buffer samples = output_buffer(context, out.samples.size() * sizeof(cl_uint));
  cl::Kernel& k = kernel("columns", "extract_left_columns");
  set_args(k, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column), index_buffer,
           cl_int(indices.size()), samples);
  launch(k, "extract_left_columns", indices.size(), kColumnGroup);
  read_buffer(context_.queue(), samples, out.samples);
}

void OpenCLBackend::update_table_row(const std::vector<std::int64_t>& previous_cost,
                                     const ColumnSet& right, const ColumnSet& left,
                                     std::vector<std::int64_t>& cost,
                                     std::vector<std::int32_t>& argmin) {
  const int column = left.column;
  const std::size_t previous = previous_cost.size();
  const std::size_t current = column > 0 ? left.samples.size() / std::size_t(column) : 0;
  if (right.column != column || right.samples.size() != previous * std::size_t(column)) {
    fail("OpenCL backend: {} right samples of C = {} for {} previous costs and C = {}",
         right.samples.size(), right.column, previous, column);
  }
  cost.assign(current, INT64_MAX);
  argmin.assign(current, -1);
  if (current == 0 || previous == 0) return;

  // Visit candidates by (P[v], v) ascending: the walk can stop at the first P[v] above the
  // best total, and ties meet the lowest v first.
  std::vector<std::int32_t> order(previous);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return previous_cost[a] != previous_cost[b] ? previous_cost[a] < previous_cost[b] : a < b;
  });
  std::vector<std::int64_t> sorted_cost(previous);
  std::vector<std::uint32_t> sorted_right(right.samples.size());
  for (std::size_t r = 0; r < previous; ++r) {
    sorted_cost[r] = previous_cost[order[r]];
    std::copy_n(right.samples.begin() + std::ptrdiff_t(order[r]) * column, column,
                sorted_right.begin() + std::ptrdiff_t(r) * column);
  }
  ColumnSet sorted_set{column, std::move(sorted_right), left.binary_alpha};

  const ColumnStats right_stats = column_stats(sorted_set, previous);
  const ColumnStats left_stats = column_stats(left, current);
  const MaskGroups groups =
      group_by_mask(right_stats, previous, left_stats, current, (std::size_t(column) + 63) / 64);

  const cl::Context& context = context_.context();
  cl::Buffer cost_buffer = input_buffer(context, sorted_cost);
  cl::Buffer order_buffer = input_buffer(context, order);
  cl::Buffer right_buffer = input_buffer(context, sorted_set.samples);
  cl::Buffer right_masks = input_buffer(context, right_stats.masks);
  cl::Buffer right_sums = input_buffer(context, right_stats.sums);
  cl::Buffer group_start = input_buffer(context, groups.start);
  cl::Buffer group_ranks = input_buffer(context, groups.ranks);
  cl::Buffer left_group = input_buffer(context, groups.of_left);
  cl::Buffer left_buffer = input_buffer(context, left.samples);
  cl::Buffer left_masks = input_buffer(context, left_stats.masks);
  cl::Buffer left_sums = input_buffer(context, left_stats.sums);
  cl::Buffer cost_out = output_buffer(context, current * sizeof(cl_long));
  cl::Buffer argmin_out = output_buffer(context, current * sizeof(cl_int));
  cl::Kernel& k = kernel("row_update", "update_table_row");
  set_args(k, cost_buffer, order_buffer, right_buffer, right_masks, right_sums, cl_int(previous),
           group_start, group_ranks, left_buffer, left_masks, left_sums, left_group,
           cl_int(current), cl_int(column), distance_table_, cl_uint(kGamma),
           cl_uint(kOpaqueAlphaMin), cl_int(kMismatchExtra), cl_int(left.binary_alpha ? 1 : 0),
           cost_out, argmin_out);
  launch(k, "update_table_row", current, kRowGroup);
  read_buffer(context_.queue(), cost_out, cost);
  read_buffer(context_.queue(), argmin_out, argmin);
}

std::unique_ptr<Backend> make_opencl_backend(OpenCLContext context) {
  return std::make_unique<OpenCLBackend>(std::move(context));
}

}  // namespace tw::detail
