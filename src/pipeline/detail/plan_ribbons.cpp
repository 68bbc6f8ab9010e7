#include "pipeline/detail/plan_ribbons.hpp"

#include <algorithm>
#include <cstdint>

#include "core/error.hpp"
#include "pipeline/detail/plan_fields.hpp"

namespace tw::detail {

std::string ribbons_to_bytes(const std::vector<std::vector<Ribbon>>& ribbons) {
  BinaryWriter records;
  std::vector<std::uint64_t> offsets;
  for (const auto& class_ribbons : ribbons)
    for (const Ribbon& r : class_ribbons) {
      offsets.push_back(records.bytes.size());
      records.write(r);
    }
  offsets.push_back(records.bytes.size());
  BinaryWriter out;
  out.count(ribbons.size());
  for (const auto& class_ribbons : ribbons) out.count(class_ribbons.size());
  out.write(offsets);
  out.bytes += records.bytes;
  return std::move(out.bytes);
}

void ribbons_from_bytes(std::string_view bytes, std::vector<std::vector<Ribbon>>& ribbons,
                        const std::vector<std::size_t>* only, const std::string& where) {
  BinaryReader in(bytes, where);
  ribbons.assign(in.count(8), {});
  std::size_t total = 0;
  for (auto& class_ribbons : ribbons) {
    class_ribbons.resize(in.count(1));
    total += class_ribbons.size();
  }
  std::vector<std::uint64_t> offsets;
  in.read(offsets);
  const std::size_t start = in.offset();
  if (offsets.size() != total + 1 || !std::is_sorted(offsets.begin(), offsets.end()) ||
      offsets.back() != in.size() - start)
    fail("{}: its offsets do not describe {} ribbons in {} bytes", where, total, in.size() - start);
  std::size_t flat = 0, next = 0;
  for (auto& class_ribbons : ribbons)
    for (Ribbon& r : class_ribbons) {
      const std::size_t i = flat++;
      if (only) {
        if (next == only->size() || (*only)[next] != i) continue;
        ++next;
      }
      in.seek(start + offsets[i]);
      in.read(r);
      if (in.offset() != start + offsets[i + 1])
        fail("{}: ribbon {} is not its {} bytes", where, i, offsets[i + 1] - offsets[i]);
    }
  if (only && next != only->size())
    fail("{}: ribbon {} asked for, {} held", where, (*only)[next], total);
}

}  // namespace tw::detail
