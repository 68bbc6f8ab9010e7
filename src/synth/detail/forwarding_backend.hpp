#pragma once
// A backend that hands every stage to another one (the CPU backend by default), so that a test
// or a benchmark overrides only the stage it replaces or watches (exhaustive rows, recorded
// rows). dp_row is the base class's default: it calls this backend's own stages.
#include <memory>
#include <string>
#include <utility>

#include "synth/detail/cpu_backend.hpp"
#include "synth/detail/stages.hpp"

namespace tw::detail {

class ForwardingBackend : public Backend {
 public:
  explicit ForwardingBackend(std::unique_ptr<Backend> inner = make_cpu_backend())
      : inner_(std::move(inner)) {}

  std::string name() const override { return inner_->name(); }
  void find_valid_positions(const CostTexels& texels, const PositionSpace& space,
                            const PieceFootprint& piece,
                            std::vector<std::uint8_t>& flags) override {
    inner_->find_valid_positions(texels, space, piece, flags);
  }
  void compact_valid_positions(const std::vector<std::uint8_t>& flags,
                               std::vector<std::int32_t>& indices) override {
    inner_->compact_valid_positions(flags, indices);
  }
  void extract_right_columns(const CostTexels& texels, const PositionSpace& space,
                             const PieceFootprint& piece, const std::vector<std::int32_t>& indices,
                             ColumnSet& out) override {
    inner_->extract_right_columns(texels, space, piece, indices, out);
  }
  void extract_left_columns(const CostTexels& texels, const PositionSpace& space,
                            const std::vector<std::int32_t>& indices, ColumnSet& out) override {
    inner_->extract_left_columns(texels, space, indices, out);
  }
  void update_table_row(const std::vector<std::int64_t>& previous_cost, const ColumnSet& right,
                        const ColumnSet& left, std::vector<std::int64_t>& cost,
                        std::vector<std::int32_t>& argmin) override {
    inner_->update_table_row(previous_cost, right, left, cost, argmin);
  }

 private:
  std::unique_ptr<Backend> inner_;
};

}  // namespace tw::detail
