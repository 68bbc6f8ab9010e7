#include "pipeline/detail/repair_cache.hpp"

#include "core/error.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_stage_cache.hpp"

namespace tw::detail {

TW_PLAN_FIELDS(LineRepairCounts);
TW_PLAN_FIELDS(RepairedPiece);
TW_DEFINE_PLAN_FIELDS(LineRepairCounts, TW_FIELD(duplicates) TW_FIELD(spikes) TW_FIELD(loops)
                                            TW_FIELD(zero_length_parts) TW_FIELD(self_crossings))
TW_DEFINE_PLAN_FIELDS(RepairedPiece, TW_FIELD(points) TW_FIELD(counts))

namespace fs = std::filesystem;

namespace {

std::string repair_entry_key(const ContentHash& piece) {
  return plan_stage_hasher("repair").hash(piece).digest().hex();
}

}  // namespace

RepairCache::RepairCache(const fs::path& dir, Warnings& warnings)
    : dir_(dir), warnings_(warnings), folder_(dir, warnings) {}

LineRepairMemo RepairCache::memo() {
  LineRepairMemo memo;
  memo.lookup = [this](const ContentHash& piece) -> std::optional<RepairedPiece> {
    const std::string key = repair_entry_key(piece);
    return read_plan_value<RepairedPiece>(dir_ / "plan" / "repair" / (key + ".twc"), key, "repair",
                                          warnings_);
  };
  memo.store = [this](const ContentHash& piece, const RepairedPiece& repaired) {
    const std::string key = repair_entry_key(piece);
    ++pieces_repaired_;
    folder_.write(dir_ / "plan" / "repair" / (key + ".twc"),
                  {{"key", key}, {"value", to_bytes(repaired)}});
  };
  return memo;
}

}  // namespace tw::detail
