#pragma once
// Content hashes of bytes in memory: XXH3-128 from libxxhash, written as 32 lowercase hex
// digits in XXH128_canonical_t order (the digits `xxhsum -H2` prints). Plan files are named by
// it (content-addressed) and checked against it when read.
#include <string>
#include <string_view>

namespace tw {

std::string content_hash(std::string_view bytes);

}  // namespace tw
