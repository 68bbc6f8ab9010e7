#pragma once
// Internals of the OpenCL backend shared by its two files (opencl_backend.cpp: the stages,
// opencl_dp_row.cpp: the resident row pipeline): buffer helpers and the device state kept
// between rows.
#include <CL/opencl.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "synth/detail/mask_groups.hpp"
#include "synth/detail/opencl_backend.hpp"

namespace tw::detail {

template <class... Args>
void set_args(cl::Kernel& kernel, const Args&... args) {
  cl_uint index = 0;
  (check_cl(kernel.setArg(index++, args), "clSetKernelArg"), ...);
}

inline std::size_t round_up(std::size_t value, std::size_t multiple) {
  return (value + multiple - 1) / multiple * multiple;
}

// A device buffer that is reused and only grows (to 1.5x what was asked, so that rows of
// slowly growing sizes do not reallocate every time).
class DeviceBuffer {
 public:
  const cl::Buffer& reserve(const cl::Context& context, std::size_t bytes) {
    if (bytes > capacity_ || capacity_ == 0) {
      capacity_ = std::max<std::size_t>(64, bytes + bytes / 2);
      cl_int status = CL_SUCCESS;
      buffer_ = cl::Buffer(context, CL_MEM_READ_WRITE, capacity_, nullptr, &status);
      check_cl(status, "clCreateBuffer");
    }
    return buffer_;
  }
  const cl::Buffer& get() const { return buffer_; }

 private:
  cl::Buffer buffer_;
  std::size_t capacity_ = 0;
};

// Non-blocking write of `values` (kept alive by the caller until the queue is past it).
template <class T>
const cl::Buffer& upload(const cl::Context& context, const cl::CommandQueue& queue,
                         DeviceBuffer& buffer, const std::vector<T>& values) {
  const cl::Buffer& b = buffer.reserve(context, values.size() * sizeof(T));
  if (!values.empty())
    check_cl(queue.enqueueWriteBuffer(b, CL_FALSE, 0, values.size() * sizeof(T), values.data()),
             "clEnqueueWriteBuffer");
  return b;
}

// One set of edge columns on the device, with its pruning statistics (kernels/columns.cl,
// edge_stats); the opaque masks are read back for the host's grouping.
struct DeviceColumns {
  int count = 0;
  DeviceBuffer indices, samples, masks, sums, blocks;
  std::vector<cl_ulong> host_masks;
};

// The two edges of one DP row as extracted (or uploaded) into the device, and what they were
// extracted from, to recognize the row when it comes.
struct PreparedRow {
  bool filled = false;
  int column = 0;
  bool binary_alpha = true;
  std::int64_t texels = -1;  // ResidentRows::texel_version extracted from
  PositionSpace space;
  std::vector<std::int32_t> previous_indices, indices, right_fx, right_fy;
  DeviceBuffer fx, fy;
  DeviceColumns right, left;
  std::vector<cl::Event> ready;  // the mask reads, after every kernel of the extraction
  // What the row's visiting order needs from the masks alone (not from the costs): found once
  // the masks are read, while the previous row's kernel runs (OpenCLBackend::find_mask_runs).
  bool runs_found = false;
  MaskRuns right_runs;
  std::vector<std::int32_t> left_run;  // per current position, its run in right_runs or -1

  bool holds(const RowEdges& edges, const PositionSpace& at, std::int64_t version) const {
    return filled && texels == version && space.width == at.width && space.height == at.height &&
           space.column == at.column && *edges.previous_indices == previous_indices &&
           *edges.indices == indices && edges.previous_piece->right_fx == right_fx &&
           edges.previous_piece->right_fy == right_fy;
  }
};

struct ResidentRows {
  cl::CommandQueue extract_queue;  // extraction of the next row, beside the row updates

  DeviceBuffer texels;
  int texel_width = -1, texel_height = -1;
  std::vector<std::uint32_t> texel_copy;  // what `texels` holds
  bool texel_binary_alpha = true;
  DeviceBuffer opacity;  // alpha >= 128, one bit per texel, opacity_words per row
  int opacity_words = 0;
  std::vector<cl_ulong> opacity_copy;
  std::int64_t texel_version = 0;  // counts uploads
  std::size_t local_memory = 0;    // CL_DEVICE_LOCAL_MEM_SIZE
  // The row kernel's launch shape once the device refused a wider one (0: not narrowed).
  int narrowed_group_size = 0, narrowed_per_item = 0;

  PreparedRow prepared[2];
  int current = 0;  // prepared[current]: this row; the other: the next one

  // The row update: the slot order from the host, the cost rows (ping-pong: cost[cost_in]
  // holds `last_cost`, the previous row's output, on the device), the argmins.
  DeviceBuffer slot_position, slot_of, slot_cost, group_begin, group_min, group_masks, left_group,
      bucket_begin, scan_group;
  DeviceBuffer cost[2], argmin;
  int cost_in = 0;
  bool cost_resident = false;
  std::vector<std::int64_t> last_cost;
  std::vector<cl_int> slot_of_host, left_group_host, group_begin_host, slot_position_host,
      bucket_begin_host, scan_group_host;
  std::vector<cl_long> group_min_host;
  std::vector<cl_ulong> group_masks_host;

  std::map<std::string, KernelTiming> timings;
  std::vector<std::pair<std::string, cl::Event>> pending;  // kernels not yet added to timings
  std::map<std::string, double> host_ms;                   // OpenCLBackend::host_timings()

  // Adds the device time of the completed kernels among `pending` (all of them when `wait`).
  void harvest(bool wait) {
    std::vector<std::pair<std::string, cl::Event>> still;
    for (auto& [name, event] : pending) {
      if (!wait && event.getInfo<CL_EVENT_COMMAND_EXECUTION_STATUS>() != CL_COMPLETE) {
        still.emplace_back(name, event);
        continue;
      }
      check_cl(event.wait(), ("waiting for kernel " + name).c_str());
      cl_ulong start = 0, end = 0;
      event.getProfilingInfo(CL_PROFILING_COMMAND_START, &start);
      event.getProfilingInfo(CL_PROFILING_COMMAND_END, &end);
      KernelTiming& timing = timings[name];
      timing.milliseconds += double(end - start) * 1e-6;
      timing.launches += 1;
    }
    pending.swap(still);
  }
};

}  // namespace tw::detail
