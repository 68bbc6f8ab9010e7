#include "synth/detail/opencl_backend.hpp"

#include <algorithm>
#include <string>

#include "core/error.hpp"
#include "synth/detail/cost.hpp"
#include "synth/detail/opaque_count.hpp"
#include "synth/detail/opencl_resident.hpp"

namespace tw::detail {

namespace {

constexpr std::size_t kScanGroup = 256;   // work-group size of the compaction scan
constexpr std::size_t kColumnGroup = 64;  // one work-item per column
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

OpenCLBackend::OpenCLBackend(OpenCLContext context, OpenCLRowOptions row)
    : context_(std::move(context)), row_options_(row), resident_(std::make_unique<ResidentRows>()) {
  if (row_options_.group_size < 1 || row_options_.per_item < 0)
    fail("OpenCL backend: row work-group size {} must be >= 1 and positions per work-item {} >= 0",
         row_options_.group_size, row_options_.per_item);
  if (row_options_.per_item == 0)
    row_options_.per_item =
        context_.device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU ? 1 : 4;
  cl_int status = CL_SUCCESS;
  resident_->extract_queue =
      cl::CommandQueue(context_.context(), context_.device(), CL_QUEUE_PROFILING_ENABLE, &status);
  check_cl(status, "clCreateCommandQueue (extraction)");
  resident_->local_memory = context_.device().getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
}

OpenCLBackend::~OpenCLBackend() = default;

const std::map<std::string, KernelTiming>& OpenCLBackend::timings() const {
  resident_->harvest(true);
  return resident_->timings;
}

const std::map<std::string, double>& OpenCLBackend::host_timings() const {
  return resident_->host_ms;
}

void OpenCLBackend::reset_timings() {
  resident_->harvest(true);
  resident_->timings.clear();
  resident_->host_ms.clear();
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

cl_int OpenCLBackend::try_enqueue(const cl::CommandQueue& queue, cl::Kernel& kernel,
                                  const std::string& name, std::size_t items,
                                  std::size_t local_size, const std::vector<cl::Event>* wait) {
  cl::Event done;
  const cl_int status =
      queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(round_up(items, local_size)),
                                 cl::NDRange(local_size), wait, &done);
  if (status == CL_SUCCESS) resident_->pending.emplace_back(name, done);
  return status;
}

cl::Event OpenCLBackend::enqueue(const cl::CommandQueue& queue, cl::Kernel& kernel,
                                 const std::string& name, std::size_t items, std::size_t local_size,
                                 const std::vector<cl::Event>* wait) {
  check_cl(try_enqueue(queue, kernel, name, items, local_size, wait),
           ("clEnqueueNDRangeKernel " + name).c_str());
  return resident_->pending.back().second;
}

void OpenCLBackend::launch(cl::Kernel& kernel, const std::string& name, std::size_t items,
                           std::size_t local_size) {
  if (items == 0) return;
  enqueue(context_.queue(), kernel, name, items, local_size);
  resident_->harvest(true);
}

const cl::Buffer& OpenCLBackend::texel_buffer(const CostTexels& texels) {
  if (texels.rgba.size() != std::size_t(texels.width) * std::size_t(texels.height)) {
    fail("OpenCL backend: exemplar texels hold {} values, expected {} x {}", texels.rgba.size(),
         texels.width, texels.height);
  }
  ResidentRows& r = *resident_;
  if (r.texel_width != texels.width || r.texel_height != texels.height ||
      r.texel_binary_alpha != texels.binary_alpha || r.texel_copy != texels.rgba) {
    ++r.texel_version;
    r.texel_binary_alpha = texels.binary_alpha;
    r.texel_copy = texels.rgba;
    r.texel_width = texels.width;
    r.texel_height = texels.height;
    upload(context_.context(), context_.queue(), r.texels, r.texel_copy);
    // The opacity bit plane of find_valid_positions, one bit per texel.
    r.opacity_words = (texels.width + 63) / 64;
    r.opacity_copy.assign(std::size_t(r.opacity_words) * std::size_t(texels.height), 0);
    for (int y = 0; y < texels.height; ++y)
      for (int x = 0; x < texels.width; ++x)
        if (is_opaque(texels.rgba[std::size_t(y) * texels.width + x]))
          r.opacity_copy[std::size_t(y) * r.opacity_words + x / 64] |= cl_ulong(1) << (x % 64);
    upload(context_.context(), context_.queue(), r.opacity, r.opacity_copy);
    check_cl(context_.queue().finish(), "clFinish (exemplar upload)");
  }
  return r.texels.get();
}

void OpenCLBackend::find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                                         const PieceFootprint& piece,
                                         std::vector<std::uint8_t>& flags) {
  const std::size_t count = std::size_t(space.count());
  flags.assign(count, 0);
  if (count == 0) return;
  if (space.width != texels.width || space.height != texels.height)
    fail("OpenCL backend: position space {} x {} for an exemplar of {} x {}", space.width,
         space.height, texels.width, texels.height);
  const cl::Context& context = context_.context();
  texel_buffer(texels);
  ResidentRows& r = *resident_;
  cl::Buffer clear = input_buffer(context, piece.must_be_clear);
  cl::Buffer interior = input_buffer(context, piece.interior);
  // The coverage floor counts by row runs (dy, first dx, last dx, unused).
  std::vector<cl_int4> runs;
  for (const TexelRun& run : row_runs(piece.interior))
    runs.push_back({{run.fixed, run.first, run.last, 0}});
  const cl_int run_count = cl_int(runs.size());
  if (runs.empty()) runs.push_back({{0, 0, -1, 0}});  // no zero-sized buffer
  cl::Buffer interior_runs = input_buffer(context, runs);
  cl::Buffer out = output_buffer(context, count);
  cl::Kernel& k = kernel("valid_positions", "find_valid_positions");
  set_args(k, r.opacity.get(), cl_int(r.opacity_words), cl_int(space.width), cl_int(space.height),
           cl_int(space.column), clear, cl_int(piece.must_be_clear.size()), interior,
           cl_int(piece.interior.size()), interior_runs, run_count, cl_int(piece.min_opaque), out);
  const std::size_t blocks = (std::size_t(space.width) + 63) / 64;
  launch(k, "find_valid_positions", blocks * std::size_t(space.height + space.column),
         kColumnGroup);
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
  const cl::Buffer& texel = texel_buffer(texels);
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
  const cl::Buffer& texel = texel_buffer(texels);
  cl::Buffer index_buffer = input_buffer(context, indices);
  cl::Buffer samples = output_buffer(context, out.samples.size() * sizeof(cl_uint));
  cl::Kernel& k = kernel("columns", "extract_left_columns");
  set_args(k, texel, cl_int(space.width), cl_int(space.height), cl_int(space.column), index_buffer,
           cl_int(indices.size()), samples);
  launch(k, "extract_left_columns", indices.size(), kColumnGroup);
  read_buffer(context_.queue(), samples, out.samples);
}

std::unique_ptr<Backend> make_opencl_backend(OpenCLContext context, OpenCLRowOptions row) {
  return std::make_unique<OpenCLBackend>(std::move(context), row);
}

}  // namespace tw::detail
