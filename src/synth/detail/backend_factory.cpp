#include "synth/detail/backend_factory.hpp"

#include "core/error.hpp"
#include "core/log.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/opencl_context.hpp"

namespace tw {

BackendKind parse_backend_kind(std::string_view name) {
  if (name == "cpu") return BackendKind::cpu;
  if (name == "opencl") return BackendKind::opencl;
  if (name == "auto") return BackendKind::automatic;
  fail("unknown synthesis backend '{}' (expected cpu, opencl or auto)", name);
}

}  // namespace tw

namespace tw::detail {

std::unique_ptr<Backend> make_backend(BackendKind kind, OpenCLContext* context) {
  switch (kind) {
    case BackendKind::cpu:
      return make_cpu_backend();
    case BackendKind::opencl:
      return make_opencl_backend(context != nullptr ? *context : OpenCLContext::create());
    case BackendKind::automatic: {
      // OpenCL where it runs on a GPU or accelerator. On a CPU OpenCL device (PoCL) the CPU
      // backend is as fast or faster (0.8-1.5x per DP row, docs/synthesis.md), same bytes.
      std::string why;
      std::optional<OpenCLContext> made;
      if (context != nullptr) {
        made = *context;
      } else {
        made = OpenCLContext::create_default(&why);
      }
      if (made && (made->device().getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_CPU) == 0) {
        return make_opencl_backend(std::move(*made));
      }
      if (made) why = "the OpenCL device '" + made->device_name() + "' is a CPU";
      logger().info("synthesis runs on the CPU backend: {}", why);
      return make_cpu_backend();
    }
  }
  fail("unknown synthesis backend kind {}", int(kind));
}

}  // namespace tw::detail
