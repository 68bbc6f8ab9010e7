#include "synth/opencl_context.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <vector>

#include "core/error.hpp"
#include "core/log.hpp"
#include "core/resources.hpp"
#include "synth/detail/opencl_backend.hpp"

namespace tw {

struct OpenCLContext::ProgramCache {
  std::mutex mutex;
  std::map<std::string, cl::Program> programs;
};

namespace {

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return text;
}

std::string env_or(const char* name, const std::string& fallback) {
  const char* value = std::getenv(name);
  return value != nullptr && *value != '\0' ? std::string(value) : fallback;
}

struct DeviceEntry {
  cl::Platform platform;
  cl::Device device;
  std::string label;  // "<platform> <device>"
};

std::vector<DeviceEntry> list_devices() {
  std::vector<cl::Platform> platforms;
  cl_int status = cl::Platform::get(&platforms);
  if (status == CL_PLATFORM_NOT_FOUND_KHR || (status == CL_SUCCESS && platforms.empty())) {
    fail("OpenCL: no platform found (is an ICD such as PoCL installed? see clinfo -l)");
  }
  detail::check_cl(status, "clGetPlatformIDs");
  std::vector<DeviceEntry> entries;
  for (const cl::Platform& platform : platforms) {
    std::vector<cl::Device> devices;
    if (platform.getDevices(CL_DEVICE_TYPE_ALL, &devices) != CL_SUCCESS) continue;
    for (const cl::Device& device : devices) {
      entries.push_back(
          {platform, device,
           platform.getInfo<CL_PLATFORM_NAME>() + " " + device.getInfo<CL_DEVICE_NAME>()});
    }
  }
  if (entries.empty()) fail("OpenCL: {} platform(s) but no device", platforms.size());
  return entries;
}

const DeviceEntry& select_device(const std::vector<DeviceEntry>& entries,
                                 const std::string& wanted) {
  if (wanted.empty()) return entries.front();
  if (std::all_of(wanted.begin(), wanted.end(), [](unsigned char c) { return std::isdigit(c); })) {
    std::size_t index = std::stoul(wanted);
    if (index >= entries.size()) {
      fail("OpenCL: device index {} (TERRAWEAVE_OPENCL_DEVICE) out of range: {} device(s)", index,
           entries.size());
    }
    return entries[index];
  }
  for (const DeviceEntry& entry : entries) {
    if (lowercase(entry.label).find(lowercase(wanted)) != std::string::npos) return entry;
  }
  std::string names;
  for (const DeviceEntry& entry : entries) names += "\n  " + entry.label;
  fail("OpenCL: no device matches '{}' (TERRAWEAVE_OPENCL_DEVICE); devices:{}", wanted, names);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("OpenCL: cannot read kernel file {} (set TERRAWEAVE_KERNEL_DIR)", path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

OpenCLContext OpenCLContext::create(const OpenCLOptions& options) {
  std::vector<DeviceEntry> entries = list_devices();
  const DeviceEntry& chosen = select_device(
      entries, options.device.empty() ? env_or("TERRAWEAVE_OPENCL_DEVICE", "") : options.device);
  OpenCLContext result;
  cl_int status = CL_SUCCESS;
  result.device_ = chosen.device;
  result.device_name_ = chosen.label;
  result.context_ = cl::Context(chosen.device, nullptr, nullptr, nullptr, &status);
  detail::check_cl(status, "clCreateContext");
  result.queue_ =
      cl::CommandQueue(result.context_, chosen.device, CL_QUEUE_PROFILING_ENABLE, &status);
  detail::check_cl(status, "clCreateCommandQueue");
  result.kernel_dir_ = options.kernel_dir.empty() ? tw::kernel_dir().string() : options.kernel_dir;
  result.programs_ = std::make_shared<ProgramCache>();
  return result;
}

std::optional<OpenCLContext> OpenCLContext::create_default(std::string* why) {
  try {
    return create();
  } catch (const Error& error) {
    if (why != nullptr) *why = error.what();
    return std::nullopt;
  }
}

cl::Program OpenCLContext::program(const std::string& family) const {
  std::lock_guard lock(programs_->mutex);
  auto found = programs_->programs.find(family);
  if (found != programs_->programs.end()) return found->second;

  const std::string path = kernel_dir_ + "/" + family + ".cl";
  cl_int status = CL_SUCCESS;
  cl::Program program(context_, read_text(path), false, &status);
  detail::check_cl(status, "clCreateProgramWithSource");
  status = program.build(std::vector<cl::Device>{device_}, "-cl-std=CL1.2");
  if (status != CL_SUCCESS) {
    std::string log;
    program.getBuildInfo(device_, CL_PROGRAM_BUILD_LOG, &log);
    fail("OpenCL: kernel file {} failed to build on {} ({}):\n{}", path, device_name_,
         detail::cl_error_name(status), log);
  }
  logger().debug("OpenCL: built {} for {}", path, device_name_);
  programs_->programs.emplace(family, program);
  return program;
}

}  // namespace tw
