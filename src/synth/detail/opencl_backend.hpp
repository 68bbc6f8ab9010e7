#pragma once
// The OpenCL implementation of the DP stages (kernels/*.cl). Each kernel has exactly one host
// wrapper here and a CPU twin in the CPU backend; tests/synth/test_opencl_*.cpp compare them.
//
// Within a synthesis the data stays on the device (synth/detail/opencl_dp_row.cpp): the
// exemplar is uploaded once, each row's columns are extracted into buffers that are reused
// from row to row (they only grow), and the cost row of one update is the input of the next;
// the host sends only the visiting order of the pruned walk (synth/detail/mask_groups.hpp)
// and reads back the costs (to sort them) and the argmins. The columns of row i + 1 are
// extracted on a second queue while row i's update runs, and the host groups their masks
// (mask_runs) while row i's kernel runs: only the sort by cost waits for row i's costs.
// Backtracking stays on the host (synth/detail/dp.cpp): it follows one argmin per row, a
// strictly sequential chain of N dependent reads with nothing to parallelize.
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

// How the row kernel splits the work; results are the same bytes for every choice.
struct OpenCLRowOptions {
  int group_size = 16;  // work-items per work-group (small groups balance the pruned walks)
  // Consecutive current positions per work-item (neighbour guesses); 0: the device's, 4 on a
  // CPU device (PoCL's threads gain from the guesses), 1 on a GPU (an H200: a braid row 18 → 11
  // ms, docs/synthesis.md "On a GPU").
  int per_item = 0;
  bool prune = true;  // false: every pair, every sample (the definition, for tests)
};

struct ResidentRows;  // synth/detail/opencl_resident.hpp
struct PreparedRow;

class OpenCLBackend final : public Backend {
 public:
  explicit OpenCLBackend(OpenCLContext context, OpenCLRowOptions row = {});
  ~OpenCLBackend() override;

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
  // Uploads the columns (they come from the host), then runs the same row as dp_row.
  void update_table_row(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                        const ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override;
  void dp_row(const CostTexels& texels, const PositionSpace& space, const RowEdges& row,
              const RowEdges* next, const std::vector<std::int64_t>& previous_cost,
              std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
              RowTimes& times) override;

  // Per kernel name, the device time since construction or the last reset_timings().
  const std::map<std::string, KernelTiming>& timings() const;
  // Per phase of the row pipeline, the host's wall time in milliseconds (since construction or
  // the last reset_timings()): what a row costs besides its kernels' device time.
  const std::map<std::string, double>& host_timings() const;
  void reset_timings();
  const OpenCLContext& context() const { return context_; }
  // The row kernel's split as asked, with the device's positions per work-item filled in.
  const OpenCLRowOptions& row_options() const { return row_options_; }

 private:
  cl::Kernel& kernel(const std::string& family, const std::string& name);
  // Enqueues `items` work-items (rounded up to local_size) after `wait`; the device time is
  // added to timings() once the event completes.
  cl::Event enqueue(const cl::CommandQueue& queue, cl::Kernel& kernel, const std::string& name,
                    std::size_t items, std::size_t local_size,
                    const std::vector<cl::Event>* wait = nullptr);
  // The same, returning the status of clEnqueueNDRangeKernel instead of failing on it.
  cl_int try_enqueue(const cl::CommandQueue& queue, cl::Kernel& kernel, const std::string& name,
                     std::size_t items, std::size_t local_size,
                     const std::vector<cl::Event>* wait = nullptr);
  void launch(cl::Kernel& kernel, const std::string& name, std::size_t items,
              std::size_t local_size);
  // The exemplar on the device, uploaded only when it differs from the last one.
  const cl::Buffer& texel_buffer(const CostTexels& texels);
  // synth/detail/opencl_dp_row.cpp: enqueue the extraction of a row's edges (on the
  // extraction queue) or the upload of given columns, then their statistics and mask reads.
  void prepare_row(PreparedRow& prepared, const CostTexels& texels, const PositionSpace& space,
                   const RowEdges& edges);
  void upload_row(PreparedRow& prepared, const ColumnSet& right, const ColumnSet& left);
  void enqueue_stats(const cl::CommandQueue& queue, PreparedRow& prepared,
                     std::vector<cl::Event> extracted);
  // The row update on prepared edges: the slot order, the kernel, the costs and argmins. While
  // the kernel runs, the host finds the mask runs of `ahead` (the next row's prepared edges).
  void run_row(PreparedRow& prepared, const std::vector<std::int64_t>& previous_cost,
               std::vector<std::int64_t>& cost, std::vector<std::int32_t>& argmin,
               PreparedRow* ahead = nullptr);
  // The cost-independent half of a row's visiting order, once its masks are read.
  void find_mask_runs(PreparedRow& prepared);

  OpenCLContext context_;
  OpenCLRowOptions row_options_;
  std::unique_ptr<ResidentRows> resident_;
  std::map<std::string, cl::Kernel> kernels_;
};

std::unique_ptr<Backend> make_opencl_backend(OpenCLContext context, OpenCLRowOptions row = {});

}  // namespace tw::detail
