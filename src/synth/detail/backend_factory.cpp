#include "synth/detail/backend_factory.hpp"

#include "core/error.hpp"
#include "core/log.hpp"
#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/opencl_backend.hpp"
#include "synth/opencl_context.hpp"

namespace tw::detail {

BackendKind parse_backend_kind(std::string_view name) {
  if (name == "cpu") return BackendKind::cpu;
  if (name == "opencl") return BackendKind::opencl;
  if (name == "auto") return BackendKind::automatic;
  fail("unknown synthesis backend '{}' (expected cpu, opencl or auto)", name);
}

std::unique_ptr<Backend> make_backend(BackendKind kind, OpenCLContext* context) {
  switch (kind) {
    case BackendKind::cpu:
      return make_cpu_backend();
    case BackendKind::opencl:
      return make_opencl_backend(context != nullptr ? *context : OpenCLContext::create());
    case BackendKind::automatic: {
      if (context != nullptr) return make_opencl_backend(*context);
      std::string why;
      if (std::optional<OpenCLContext> made = OpenCLContext::create_default(&why)) {
        return make_opencl_backend(std::move(*made));
      }
      logger().info("synthesis falls back to the CPU backend: {}", why);
      return make_cpu_backend();
    }
  }
  fail("unknown synthesis backend kind {}", int(kind));
}

}  // namespace tw::detail
