#include "pipeline/detail/plan_objects.hpp"

#include <cstdint>
#include <cstring>
#include <system_error>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_io.hpp"
#include "pipeline/plan_io.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;

json PlanObjects::put(const std::string& bytes, const std::string& extension) const {
  const std::string hash = content_hash(bytes);
  const std::string name = "objects/" + hash + extension;
  std::error_code ec;
  // Same name, same bytes: an object an earlier plan wrote is kept (if it is intact).
  if (fs::file_size(dir_ / name, ec) != bytes.size() || ec ||
      content_hash(read_file_bytes(dir_ / name)) != hash) {
    write_file_atomic(dir_ / name, bytes);
  }
  return {{"file", name}, {"xxh3_128", hash}, {"bytes", bytes.size()}};
}

json PlanObjects::put_cbor(const json& value) const {
  const std::vector<std::uint8_t> cbor = json::to_cbor(value);
  return put(std::string(cbor.begin(), cbor.end()), ".cbor");
}

namespace {
constexpr std::string_view kBinaryMagic = "twplan.b";
constexpr std::size_t kBinaryHeader = kBinaryMagic.size() + sizeof(std::uint32_t);
}  // namespace

json PlanObjects::put_binary(std::string_view body) const {
  std::string bytes;
  bytes.reserve(kBinaryHeader + body.size());
  bytes.append(kBinaryMagic);
  const std::uint32_t version = kPlanVersion;
  bytes.append(reinterpret_cast<const char*>(&version), sizeof version);
  bytes.append(body);
  return put(bytes, ".bin");
}

std::string_view PlanObjects::Binary::body() const {
  return file.bytes().substr(kBinaryHeader);
}

namespace {

// The checks of an entry before its file is read: its fields, and a name under objects/.
std::string plan_object_file(const json& entry, const std::string& where) {
  if (!entry.is_object() || !entry.contains("file") || !entry.contains("xxh3_128"))
    fail("{}: expected {{file, xxh3_128}}", where);
  const std::string file = entry["file"].get<std::string>();
  if (file.find("..") != std::string::npos || !file.starts_with("objects/"))
    fail("{}: file {} is not under objects/", where, file);
  return file;
}

void check_plan_object_hash(std::string_view bytes, const json& entry, const fs::path& path,
                            const std::string& where) {
  if (content_hash(bytes) != entry["xxh3_128"].get<std::string>())
    fail("{}: {} does not match its content hash (corrupt, or changed after planning)", where,
         path.string());
}

}  // namespace

PlanObjects::Binary PlanObjects::get_binary(const json& entry, const std::string& key) const {
  const std::string where = fmt::format("plan {}: {}", dir_.string(), key);
  const fs::path path = dir_ / plan_object_file(entry, where);
  Binary object{MappedFile(path)};
  const std::string_view bytes = object.file.bytes();
  check_plan_object_hash(bytes, entry, path, where);
  std::uint32_t version = 0;
  if (bytes.size() >= kBinaryHeader)
    std::memcpy(&version, bytes.data() + kBinaryMagic.size(), sizeof version);
  if (bytes.size() < kBinaryHeader || !bytes.starts_with(kBinaryMagic) ||
      version != std::uint32_t(kPlanVersion))
    fail("plan {}: {}: {} is not a version {} binary object (plan again)", dir_.string(), key,
         entry["file"].get<std::string>(), kPlanVersion);
  return object;
}

std::string PlanObjects::get(const json& entry, const std::string& key) const {
  const std::string where = fmt::format("plan {}: {}", dir_.string(), key);
  const fs::path path = dir_ / plan_object_file(entry, where);
  std::string bytes = read_file_bytes(path);
  check_plan_object_hash(bytes, entry, path, where);
  return bytes;
}

json PlanObjects::get_cbor(const json& entry, const std::string& key) const {
  const std::string bytes = get(entry, key);
  try {
    return json::from_cbor(bytes);
  } catch (const json::exception& e) {
    fail("plan {}: {}: not CBOR ({})", dir_.string(), key, e.what());
  }
}

}  // namespace tw::detail
