#pragma once
// Content hashes (XXH3-128, xxHash): the one way terraweave names what a computation read, so
// that a rerun can tell whether it may reuse an earlier result (docs/cache.md). A Hasher takes
// a canonical encoding of values: fixed-width little-endian integers, doubles by their bits
// (-0 as 0, every NaN as one NaN), strings and byte runs prefixed by their length, so two
// different sequences of values never feed the same bytes. Not a cryptographic hash: it guards
// against change and corruption, not against an adversary.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec2.hpp"

namespace tw {

struct ContentHash {
  std::uint64_t high = 0, low = 0;

  // 32 lowercase hex digits (a file name for content-addressed entries).
  std::string hex() const;
  // Parses hex(); throws tw::Error on anything else.
  static ContentHash from_hex(std::string_view hex);
  friend constexpr bool operator==(const ContentHash&, const ContentHash&) = default;
  friend constexpr auto operator<=>(const ContentHash&, const ContentHash&) = default;
};

class Hasher {
 public:
  Hasher();
  ~Hasher();
  Hasher(const Hasher& other);
  Hasher& operator=(const Hasher& other);

  Hasher& bytes(std::span<const std::byte> data);  // length-prefixed
  Hasher& text(std::string_view s);                // length-prefixed
  Hasher& u64(std::uint64_t v);
  Hasher& i64(std::int64_t v) { return u64(std::uint64_t(v)); }
  Hasher& boolean(bool v) { return u64(v ? 1 : 0); }
  Hasher& real(double v);
  Hasher& point(Vec2 p) { return real(p.x).real(p.y); }
  Hasher& points(const std::vector<Vec2>& ps);  // count-prefixed
  Hasher& hash(const ContentHash& h) { return u64(h.high).u64(h.low); }
  // A file's size and bytes, streamed; an absent file hashes as a distinct marker (so a file
  // that appears or disappears changes the hash). Throws tw::Error naming an unreadable file.
  Hasher& file(const std::filesystem::path& path);

  ContentHash digest() const;  // the hash so far (the Hasher may go on)

 private:
  void raw(const void* data, std::size_t size);
  struct State;
  std::unique_ptr<State> state_;
};

// The hash of a run of bytes alone (the checksum of a cache entry's payload).
ContentHash hash_bytes(std::span<const std::byte> data);
ContentHash hash_file(const std::filesystem::path& path);
// hash_bytes(bytes).hex(): the 32 digits `xxhsum -H2` prints (plan files are named by it).
std::string content_hash(std::string_view bytes);

}  // namespace tw
