#include "core/content_hash.hpp"

// XXH3_state_t is opaque unless static linking-only declarations are asked for.
#define XXH_STATIC_LINKING_ONLY
#include <xxhash.h>

#include <bit>
#include <cmath>
#include <fstream>
#include <limits>

#include "core/error.hpp"

namespace tw {

namespace {

constexpr std::uint64_t kAbsentFile = 0xab5e47f11e000000ull;  // "absent file": never a size

}  // namespace

struct Hasher::State {
  XXH3_state_t xxh;
};

Hasher::Hasher() : state_(std::make_unique<State>()) {
  XXH3_128bits_reset(&state_->xxh);
}
Hasher::~Hasher() = default;
Hasher::Hasher(const Hasher& other) : state_(std::make_unique<State>()) {
  XXH3_copyState(&state_->xxh, &other.state_->xxh);
}
Hasher& Hasher::operator=(const Hasher& other) {
  if (this != &other) XXH3_copyState(&state_->xxh, &other.state_->xxh);
  return *this;
}

void Hasher::raw(const void* data, std::size_t size) {
  XXH3_128bits_update(&state_->xxh, data, size);
}

Hasher& Hasher::u64(std::uint64_t v) {
  unsigned char le[8];
  for (int i = 0; i < 8; ++i) le[i] = static_cast<unsigned char>(v >> (8 * i));
  raw(le, sizeof le);
  return *this;
}

Hasher& Hasher::real(double v) {
  if (v == 0.0) v = 0.0;  // -0 and +0 are one value
  if (std::isnan(v)) v = std::numeric_limits<double>::quiet_NaN();
  return u64(std::bit_cast<std::uint64_t>(v));
}

Hasher& Hasher::bytes(std::span<const std::byte> data) {
  u64(data.size());
  raw(data.data(), data.size());
  return *this;
}

Hasher& Hasher::text(std::string_view s) {
  u64(s.size());
  raw(s.data(), s.size());
  return *this;
}

Hasher& Hasher::points(const std::vector<Vec2>& ps) {
  u64(ps.size());
  for (const Vec2 p : ps) point(p);
  return *this;
}

Hasher& Hasher::file(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return u64(kAbsentFile);
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("cannot read {} (to hash it)", path.string());
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) fail("cannot read {} (to hash it): {}", path.string(), ec.message());
  u64(size);
  std::vector<char> buffer(1 << 16);
  std::uintmax_t read = 0;
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    raw(buffer.data(), std::size_t(in.gcount()));
    read += std::uintmax_t(in.gcount());
  }
  if (read != size) fail("cannot read {} (to hash it): it changed while read", path.string());
  return *this;
}

ContentHash Hasher::digest() const {
  const XXH128_hash_t h = XXH3_128bits_digest(&state_->xxh);
  return {h.high64, h.low64};
}

std::string ContentHash::hex() const {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(32, '0');
  for (int i = 0; i < 16; ++i) {
    out[std::size_t(15 - i)] = kDigits[(high >> (4 * i)) & 0xf];
    out[std::size_t(31 - i)] = kDigits[(low >> (4 * i)) & 0xf];
  }
  return out;
}

ContentHash ContentHash::from_hex(std::string_view hex) {
  if (hex.size() != 32) fail("not a content hash (32 hex digits): '{}'", hex);
  ContentHash h;
  for (std::size_t i = 0; i < 32; ++i) {
    const char c = hex[i];
    const int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (digit < 0) fail("not a content hash (32 hex digits): '{}'", hex);
    std::uint64_t& half = i < 16 ? h.high : h.low;
    half = (half << 4) | std::uint64_t(digit);
  }
  return h;
}

ContentHash hash_bytes(std::span<const std::byte> data) {
  const XXH128_hash_t h = XXH3_128bits(data.data(), data.size());
  return {h.high64, h.low64};
}

std::string content_hash(std::string_view bytes) {
  return hash_bytes(std::as_bytes(std::span(bytes.data(), bytes.size()))).hex();
}

ContentHash hash_file(const std::filesystem::path& path) {
  return Hasher().file(path).digest();
}

}  // namespace tw
