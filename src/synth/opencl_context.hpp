#pragma once
// An explicit OpenCL context: platform, device, context, in-order queue (with profiling) and
// the cache of built kernel programs. Never a global: the caller creates one and passes it to
// the OpenCL backend. Copies share the same device objects and program cache.
#include <CL/opencl.hpp>

#include <memory>
#include <optional>
#include <string>

namespace tw {

struct OpenCLOptions {
  // The device: its index among all devices of all platforms (in platform order), or a
  // case-insensitive substring of "<platform> <device>". Empty: the environment variable
  // TERRAWEAVE_OPENCL_DEVICE, else the first device.
  std::string device;
  // The folder of the kernels/*.cl files. Empty: the environment variable
  // TERRAWEAVE_KERNEL_DIR, else the one beside the program (core/resources.hpp, kernel_dir).
  std::string kernel_dir;
};

class OpenCLContext {
 public:
  // Throws tw::Error naming what is missing (no platform, no matching device, ...).
  static OpenCLContext create(const OpenCLOptions& options = {});
  // The same with default options; nullopt (and the reason in *why) when no device is usable.
  static std::optional<OpenCLContext> create_default(std::string* why = nullptr);

  const cl::Device& device() const { return device_; }
  const cl::Context& context() const { return context_; }
  const cl::CommandQueue& queue() const { return queue_; }
  const std::string& device_name() const { return device_name_; }
  const std::string& kernel_dir() const { return kernel_dir_; }

  // The program of <kernel_dir>/<family>.cl, built on first use and cached. A build failure
  // throws tw::Error with the file name and the compiler's build log. Thread-safe.
  cl::Program program(const std::string& family) const;

 private:
  struct ProgramCache;
  OpenCLContext() = default;

  cl::Device device_;
  cl::Context context_;
  cl::CommandQueue queue_;
  std::string device_name_;
  std::string kernel_dir_;
  std::shared_ptr<ProgramCache> programs_;
};

}  // namespace tw
