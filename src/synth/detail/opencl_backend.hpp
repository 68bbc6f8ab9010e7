#pragma once
// The OpenCL implementation of the DP stages (kernels/*.cl). Each kernel has exactly one host
// wrapper here and a CPU twin in the CPU backend; tests/synth/test_opencl_*.cpp compare them.
// Backtracking stays on the host (synth/detail/dp.cpp): it follows one argmin per row, a
// strictly sequential chain of N dependent reads with nothing to parallelize, and the argmins
// are already on the host after each row.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "synth/detail/stages.hpp"
#include "synth/opencl_context.hpp"

namespace tw::detail {

// Throws tw::Error "OpenCL: <what> failed: <CL_ERROR_NAME> (<code>)" unless status is CL_SUCCESS.
void check_cl(cl_int status, const char* what);
const char* cl_error_name(cl_int status);

// Device time of one kernel, summed over its launches (from profiling events).
struct KernelTiming {
  double milliseconds = 0;
  std::int64_t launches = 0;
};

class OpenCLBackend final : public Backend {
 public:
  explicit OpenCLBackend(OpenCLContext context);

  std::string name() const override;
  void find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                            const PieceFootprint& piece, std::vector<std::uint8_t>& flags) override;
  void compact_valid_positions(const std::vector<std::uint8_t>& flags,
                               std::vector<std::int32_t>& indices) override;
  void extract_right_columns(const CostTexels& texels, const PositionSpace& space,
                             const PieceFootprint& piece, const std::vector<std::int32_t>& indices,
                             ColumnSet& out) override;
  void extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<std::int32_t>& indices, ColumnSet& out) override;
  void update_table_row(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                        const ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override;

  // Per kernel name, the device time since construction or the last reset_timings().
  const std::map<std::string, KernelTiming>& timings() const { return timings_; }
  void reset_timings() { timings_.clear(); }
  const OpenCLContext& context() const { return context_; }

 private:
  cl::Kernel& kernel(const std::string& family, const std::string& name);
  void launch(cl::Kernel& kernel, const std::string& name, std::size_t items,
              std::size_t local_size);
  cl::Buffer texel_buffer(const CostTexels& texels);

  OpenCLContext context_;
  cl::Buffer distance_table_;  // floor(sqrt(256 d2)) for d2 in [0, 3 * 255^2]
  std::map<std::string, cl::Kernel> kernels_;
  std::map<std::string, KernelTiming> timings_;
};

std::unique_ptr<Backend> make_opencl_backend(OpenCLContext context);

}  // namespace tw::detail
