#pragma once
// Picks the backend that runs the DP stages. Owned by the OpenCL work; the CPU backend is
// made by make_cpu_backend (synth/detail/cpu_backend.hpp).
#include <memory>
#include <string_view>

#include "synth/backend_kind.hpp"
#include "synth/detail/stages.hpp"

namespace tw {
class OpenCLContext;  // synth/opencl_context.hpp: an explicit object, never a global
}

namespace tw::detail {

// cpu: the reference. opencl: the OpenCL backend on `context` (throws tw::Error when no
// platform is usable). automatic: OpenCL when a platform is usable, else CPU with one log line.
// `context` may be null: an OpenCL backend then creates its own default context.
std::unique_ptr<Backend> make_backend(BackendKind kind, OpenCLContext* context);

}  // namespace tw::detail
