#pragma once
// Which backend runs the DP (docs/synthesis.md): the CPU reference, OpenCL, or OpenCL where it
// runs on a GPU or accelerator and the CPU otherwise. The same bytes on every backend.
#include <string_view>

namespace tw {

enum class BackendKind { cpu, opencl, automatic };

// "cpu", "opencl" or "auto"; anything else throws tw::Error naming the value.
BackendKind parse_backend_kind(std::string_view name);

}  // namespace tw
