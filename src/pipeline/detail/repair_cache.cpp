#include "pipeline/detail/repair_cache.hpp"

#include <fmt/format.h>

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
    const fs::path path = dir_ / "plan" / "repair" / (key + ".twc");
    CacheRead read = read_cache_entry(path);
    if (read.state == CacheRead::State::ok) {
      try {
        if (read.sections["key"] != key) fail("key mismatch");
        RepairedPiece found;
        from_bytes(read.sections["value"], found, path.string());
        touch_cache_entry(path);  // used now: pruning by age keeps it
        return found;
      } catch (const Error& e) {
        read.state = CacheRead::State::corrupt;
        read.problem = e.what();
      }
    }
    if (read.state == CacheRead::State::corrupt) {
      warnings_.add(
          "cache_corrupt", "plan.repair", std::nullopt,
          fmt::format("cache entry {} is corrupt ({}): rebuilt", path.string(), read.problem));
    }
    return std::nullopt;
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
