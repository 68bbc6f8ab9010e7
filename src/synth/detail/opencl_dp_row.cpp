// The resident row pipeline of the OpenCL backend (see opencl_backend.hpp): extraction of a
// row's edges into reused device buffers on the extraction queue, their statistics, and the
// pruned row update (kernels/row_update.cl) on the main queue.
#include <algorithm>
#include <bit>
#include <chrono>
#include <map>
#include <string>

#include "core/error.hpp"
#include "core/log.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/edge_bound.hpp"
#include "synth/detail/mask_groups.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/detail/opencl_resident.hpp"

namespace tw::detail {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::size_t kColumnGroup = 64;  // one work-item per column

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

int mask_words(int column) {
  return (column + 63) / 64;
}

// Adds the wall time since `lap` to host[phase] and restarts `lap` (OpenCLBackend::host_timings).
void add_lap(std::map<std::string, double>& host, const char* phase, Clock::time_point& lap) {
  const Clock::time_point now = Clock::now();
  host[phase] += std::chrono::duration<double, std::milli>(now - lap).count();
  lap = now;
}

}  // namespace

void OpenCLBackend::prepare_row(PreparedRow& prepared, const CostTexels& texels,
                                const PositionSpace& space, const RowEdges& edges) {
  const PieceFootprint& piece = *edges.previous_piece;
  if (piece.right_fx.size() != std::size_t(space.column) ||
      piece.right_fy.size() != std::size_t(space.column) || piece.column != space.column) {
    fail("OpenCL backend: piece footprint has {} / {} right samples for C = {} (space C = {})",
         piece.right_fx.size(), piece.right_fy.size(), piece.column, space.column);
  }
  const cl::Buffer& texel = texel_buffer(texels);
  ResidentRows& r = *resident_;
  prepared.filled = true;
  prepared.runs_found = false;
  prepared.column = space.column;
  prepared.binary_alpha = texels.binary_alpha;
  prepared.texels = r.texel_version;
  prepared.space = space;
  prepared.previous_indices = *edges.previous_indices;
  prepared.indices = *edges.indices;
  prepared.right_fx = piece.right_fx;
  prepared.right_fy = piece.right_fy;
  prepared.ready.clear();
  const cl::Context& context = context_.context();
  const cl::CommandQueue& queue = r.extract_queue;
  const std::size_t C = std::size_t(space.column);

  DeviceColumns& right = prepared.right;
  right.count = int(prepared.previous_indices.size());
  const cl::Buffer& fx = upload(context, queue, prepared.fx, prepared.right_fx);
  const cl::Buffer& fy = upload(context, queue, prepared.fy, prepared.right_fy);
  const cl::Buffer& right_indices =
      upload(context, queue, right.indices, prepared.previous_indices);
  const cl::Buffer& right_samples = right.samples.reserve(context, right.count * C * 4);
  cl::Kernel& extract_right = kernel("columns", "extract_right_columns");
  set_args(extract_right, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column),
           fx, fy, right_indices, cl_int(right.count), right_samples);
  enqueue(queue, extract_right, "extract_right_columns", right.count, kColumnGroup);

  DeviceColumns& left = prepared.left;
  left.count = int(prepared.indices.size());
  const cl::Buffer& left_indices = upload(context, queue, left.indices, prepared.indices);
  const cl::Buffer& left_samples = left.samples.reserve(context, left.count * C * 4);
  cl::Kernel& extract_left = kernel("columns", "extract_left_columns");
  set_args(extract_left, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column),
           left_indices, cl_int(left.count), left_samples);
  enqueue(queue, extract_left, "extract_left_columns", left.count, kColumnGroup);
  enqueue_stats(queue, prepared, {});
  check_cl(queue.flush(), "clFlush (extraction)");
}

void OpenCLBackend::upload_row(PreparedRow& prepared, const ColumnSet& right,
                               const ColumnSet& left) {
  const cl::Context& context = context_.context();
  const cl::CommandQueue& queue = context_.queue();
  prepared.filled = false;  // not the edges of any RowEdges
  prepared.runs_found = false;
  prepared.column = left.column;
  prepared.binary_alpha = left.binary_alpha;
  prepared.ready.clear();
  prepared.right.count = int(right.samples.size() / std::size_t(right.column));
  prepared.left.count = int(left.samples.size() / std::size_t(left.column));
  upload(context, queue, prepared.right.samples, right.samples);
  upload(context, queue, prepared.left.samples, left.samples);
  enqueue_stats(queue, prepared, {});
}

void OpenCLBackend::enqueue_stats(const cl::CommandQueue& queue, PreparedRow& prepared,
                                  std::vector<cl::Event> extracted) {
  const cl::Context& context = context_.context();
  const int C = prepared.column, words = mask_words(C),
            blocks = (C + kBoundBlock - 1) / kBoundBlock;
  cl::Kernel& stats = kernel("columns", "edge_stats");
  for (DeviceColumns* side : {&prepared.right, &prepared.left}) {
    const std::size_t count = std::size_t(side->count);
    const cl::Buffer& masks = side->masks.reserve(context, count * words * 8);
    set_args(stats, side->samples.get(), cl_int(count), cl_int(C), masks,
             side->sums.reserve(context, count * 16),
             side->blocks.reserve(context, count * blocks * 3 * 4));
    enqueue(queue, stats, "edge_stats", count, kColumnGroup,
            extracted.empty() ? nullptr : &extracted);
    side->host_masks.resize(count * std::size_t(words));
    cl::Event read;
    check_cl(queue.enqueueReadBuffer(masks, CL_FALSE, 0, count * words * 8, side->host_masks.data(),
                                     nullptr, &read),
             "clEnqueueReadBuffer (masks)");
    prepared.ready.push_back(read);
  }
}

void OpenCLBackend::find_mask_runs(PreparedRow& prepared) {
  if (prepared.runs_found) return;
  check_cl(cl::Event::waitForEvents(prepared.ready), "waiting for the row's columns");
  const int words = mask_words(prepared.column);
  prepared.right_runs = mask_runs(prepared.right.host_masks.data(), prepared.right.count, words);
  prepared.left_run.resize(std::size_t(prepared.left.count));
  for (int j = 0; j < prepared.left.count; ++j)
    prepared.left_run[std::size_t(j)] = run_with_mask(
        prepared.right_runs, prepared.left.host_masks.data() + std::size_t(j) * words);
  prepared.runs_found = true;
}

void OpenCLBackend::run_row(PreparedRow& prepared, const std::vector<std::int64_t>& previous_cost,
                            std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
                            PreparedRow* ahead) {
  ResidentRows& r = *resident_;
  Clock::time_point lap = Clock::now();
  check_cl(cl::Event::waitForEvents(prepared.ready), "waiting for the row's columns");
  add_lap(r.host_ms, "wait for the row's columns", lap);
  const int C = prepared.column, words = mask_words(C);
  const int previous = prepared.right.count, current = prepared.left.count;
  if (std::size_t(previous) != previous_cost.size())
    fail("OpenCL backend: {} previous costs for {} previous positions", previous_cost.size(),
         previous);
  cost.assign(std::size_t(current), INT64_MAX);
  argmin.assign(std::size_t(current), -1);
  if (current == 0 || previous == 0) return;

  // The visiting order (the CPU backend's, synth/detail/mask_groups.hpp).
  find_mask_runs(prepared);
  add_lap(r.host_ms, "mask runs (not overlapped)", lap);
  const MaskGroups groups = group_runs_by_cost(prepared.right_runs, previous_cost);
  r.slot_position_host.assign(groups.position.begin(), groups.position.end());
  r.group_begin_host.assign(groups.group_begin.begin(), groups.group_begin.end());
  r.slot_of_host.resize(std::size_t(previous));
  for (int s = 0; s < previous; ++s) r.slot_of_host[std::size_t(groups.position[s])] = s;
  // The kernel's group scan: groups bucketed by their number of opaque samples (a group whose
  // count differs by d from the left mask's has m >= d), each bucket in increasing lowest P and
  // padded to whole 8-group vectors; masks word-major in that order.
  std::vector<int> by_count(std::size_t(groups.groups())), count_of(by_count.size());
  for (int g = 0; g < groups.groups(); ++g) {
    by_count[std::size_t(g)] = g;
    for (int w = 0; w < words; ++w)
      count_of[std::size_t(g)] += std::popcount(groups.group_masks[std::size_t(g) * words + w]);
  }
  std::stable_sort(by_count.begin(), by_count.end(), [&](int a, int b) {
    return count_of[std::size_t(a)] < count_of[std::size_t(b)];
  });
  r.bucket_begin_host.assign(std::size_t(C) + 2, 0);
  r.scan_group_host.clear();
  for (std::size_t i = 0, c = 0; c <= std::size_t(C); ++c) {
    r.bucket_begin_host[c] = cl_int(r.scan_group_host.size());
    for (; i < by_count.size() && count_of[std::size_t(by_count[i])] == int(c); ++i)
      r.scan_group_host.push_back(by_count[i]);
    while (r.scan_group_host.size() % 8) r.scan_group_host.push_back(-1);
  }
  r.bucket_begin_host[std::size_t(C) + 1] = cl_int(r.scan_group_host.size());
  const int scan_stride = int(r.scan_group_host.size());
  r.group_min_host.assign(std::size_t(scan_stride), INT64_MAX / 4);
  r.group_masks_host.assign(std::size_t(scan_stride) * words, 0);
  for (int i = 0; i < scan_stride; ++i) {
    const int g = r.scan_group_host[std::size_t(i)];
    if (g < 0) continue;
    r.group_min_host[std::size_t(i)] =
        previous_cost[std::size_t(groups.position[groups.group_begin[g]])];
    for (int w = 0; w < words; ++w)
      r.group_masks_host[std::size_t(w) * scan_stride + i] =
          groups.group_masks[std::size_t(g) * words + w];
  }
  r.left_group_host.resize(std::size_t(current));
  for (int j = 0; j < current; ++j) {
    const std::int32_t run = prepared.left_run[std::size_t(j)];
    r.left_group_host[std::size_t(j)] = run < 0 ? -1 : groups.groups_by_mask[std::size_t(run)];
  }
  add_lap(r.host_ms, "visiting order", lap);

  const cl::Context& context = context_.context();
  const cl::CommandQueue& queue = context_.queue();
  // The cost row stays on the device: upload it only when the caller's differs from the
  // last row's output (another synthesis, or a cost term added on the host).
  if (!r.cost_resident || r.last_cost != previous_cost)
    upload(context, queue, r.cost[r.cost_in], previous_cost);
  const cl::Buffer& slot_position = upload(context, queue, r.slot_position, r.slot_position_host);
  const cl::Buffer& slot_cost = r.slot_cost.reserve(context, std::size_t(previous) * 8);
  cl::Kernel& gather = kernel("row_update", "gather_slot_costs");
  set_args(gather, r.cost[r.cost_in].get(), slot_position, cl_int(previous), slot_cost);
  enqueue(queue, gather, "gather_slot_costs", std::size_t(previous), kColumnGroup);

  cl::Kernel& row = kernel("row_update", "update_table_row");
  // The launch shape: the options', or the narrower one the device left us last time; no wider
  // than the kernel's work-group limit on this device, its tile of left columns in local memory.
  int per_item = r.narrowed_per_item ? r.narrowed_per_item : row_options_.per_item;
  int group_size = r.narrowed_group_size ? r.narrowed_group_size : row_options_.group_size;
  group_size = std::min<int>(
      group_size, int(row.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(context_.device())));
  const std::size_t column_bytes = std::size_t(C) * 4;
  while (per_item > 1 && std::size_t(group_size * per_item) * column_bytes > r.local_memory)
    --per_item;
  while (group_size > 1 && std::size_t(group_size) * column_bytes > r.local_memory) --group_size;
  if (column_bytes > r.local_memory)
    fail(
        "OpenCL backend: a column of C = {} samples does not fit in the device's {} bytes of local "
        "memory",
        C, r.local_memory);

  const cl::Buffer& cost_out = r.cost[1 - r.cost_in].reserve(context, std::size_t(current) * 8);
  const cl::Buffer& argmin_out = r.argmin.reserve(context, std::size_t(current) * 4);
  // A shape the device still refuses for its resources (the H200's driver answers
  // CL_OUT_OF_RESOURCES to tiles its queries allow, docs/performance.md) is tried again narrower,
  // and the narrower one kept: every shape gives the same costs and argmins (OpenCLRowOptions).
  for (;;) {
    const std::size_t tile = std::size_t(group_size * per_item);
    const std::size_t work_groups = (std::size_t(current) + tile - 1) / tile;
    set_args(row, slot_cost, slot_position, upload(context, queue, r.slot_of, r.slot_of_host),
             cl_int(previous), upload(context, queue, r.group_begin, r.group_begin_host),
             upload(context, queue, r.bucket_begin, r.bucket_begin_host),
             upload(context, queue, r.scan_group, r.scan_group_host),
             upload(context, queue, r.group_min, r.group_min_host),
             upload(context, queue, r.group_masks, r.group_masks_host), cl_int(scan_stride),
             prepared.right.samples.get(), prepared.right.masks.get(), prepared.right.sums.get(),
             prepared.right.blocks.get(), prepared.left.samples.get(), prepared.left.masks.get(),
             prepared.left.sums.get(), prepared.left.blocks.get(),
             upload(context, queue, r.left_group, r.left_group_host), cl_int(current), cl_int(C),
             cl_int(prepared.binary_alpha ? 1 : 0), cl_int(kGamma),
             cl_long(mismatch_cost(prepared.binary_alpha)),
             cl_long(mismatch_extra(prepared.binary_alpha)), cl_int(per_item),
             cl_int(row_options_.prune ? 1 : 0), cl::Local(tile * column_bytes), cost_out,
             argmin_out);
    const cl_int status =
        try_enqueue(queue, row, "update_table_row", work_groups * std::size_t(group_size),
                    std::size_t(group_size));
    if (status == CL_SUCCESS) break;
    if (status != CL_OUT_OF_RESOURCES || tile == 1)
      check_cl(status, "clEnqueueNDRangeKernel update_table_row");
    if (per_item > 1)
      --per_item;
    else
      group_size = (group_size + 1) / 2;
    r.narrowed_group_size = group_size;
    r.narrowed_per_item = per_item;
    logger().info(
        "OpenCL row kernel refused for resources: narrowed to {} work-items x {} positions",
        group_size, per_item);
  }
  check_cl(queue.enqueueReadBuffer(cost_out, CL_FALSE, 0, std::size_t(current) * 8, cost.data()),
           "clEnqueueReadBuffer (costs)");
  cl::Event results;
  check_cl(queue.enqueueReadBuffer(argmin_out, CL_FALSE, 0, std::size_t(current) * 4, argmin.data(),
                                   nullptr, &results),
           "clEnqueueReadBuffer (argmins)");
  check_cl(queue.flush(), "clFlush (row update)");
  add_lap(r.host_ms, "uploads and launches", lap);
  // The next row's masks are usually read by now (its extraction was enqueued before this
  // row's visiting order was made); when they are not, the next row finds its runs itself
  // rather than this one waiting for them (a CPU device runs both queues on the same cores).
  if (ahead && ahead->filled && !ahead->runs_found &&
      std::all_of(ahead->ready.begin(), ahead->ready.end(), [](const cl::Event& read) {
        return read.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>() == CL_COMPLETE;
      })) {
    find_mask_runs(*ahead);
    add_lap(r.host_ms, "next row's mask runs (overlapped)", lap);
  }
  check_cl(results.wait(), "waiting for the row's costs and argmins");
  add_lap(r.host_ms, "wait for costs and argmins", lap);
  r.last_cost = cost;
  r.cost_in = 1 - r.cost_in;
  r.cost_resident = true;
  add_lap(r.host_ms, "keep the cost row", lap);
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
  ResidentRows& r = *resident_;
  PreparedRow& prepared = r.prepared[r.current];
  upload_row(prepared, right, left);
  run_row(prepared, previous_cost, cost, argmin);
  r.harvest(false);
}

void OpenCLBackend::dp_row(const CostTexels& texels, const PositionSpace& space,
                           const RowEdges& row, const RowEdges* next,
                           const std::vector<std::int64_t>& previous_cost,
                           std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
                           RowTimes& times) {
  const auto start = Clock::now();
  ResidentRows& r = *resident_;
  texel_buffer(texels);  // a new exemplar invalidates what was extracted from the last one
  PreparedRow& current = r.prepared[r.current];
  if (!current.holds(row, space, r.texel_version)) prepare_row(current, texels, space, row);
  check_cl(cl::Event::waitForEvents(current.ready), "waiting for the row's columns");
  times.extract_ms = ms_since(start);
  const auto update_start = Clock::now();
  // The next row's columns are extracted on the other queue while this row's update runs
  // (its buffers were last read by the previous row's update, which has completed).
  PreparedRow& following = r.prepared[1 - r.current];
  Clock::time_point lap = update_start;
  if (next)
    prepare_row(following, texels, space, *next);
  else
    following.filled = false;
  add_lap(r.host_ms, "enqueue the next row's extraction", lap);
  run_row(current, previous_cost, cost, argmin, next ? &following : nullptr);
  r.current = 1 - r.current;
  lap = Clock::now();
  r.harvest(false);
  add_lap(r.host_ms, "profiling events", lap);
  times.update_ms = ms_since(update_start);
}

}  // namespace tw::detail
