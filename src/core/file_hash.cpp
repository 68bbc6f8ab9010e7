#include "core/file_hash.hpp"

#include <xxhash.h>

#include <cstdio>
#include <memory>
#include <vector>

#include "core/error.hpp"

namespace tw {

FileDigest file_digest(const std::filesystem::path& path) {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                             &std::fclose);
  if (!file) fail("{}: cannot be read for its hash", path.string());
  const std::unique_ptr<XXH3_state_t, XXH_errorcode (*)(XXH3_state_t*)> state(XXH3_createState(),
                                                                              &XXH3_freeState);
  XXH3_128bits_reset(state.get());
  std::vector<char> chunk(std::size_t(1) << 20);
  FileDigest digest;
  std::size_t n = 0;
  while ((n = std::fread(chunk.data(), 1, chunk.size(), file.get())) > 0) {
    XXH3_128bits_update(state.get(), chunk.data(), n);
    digest.bytes += n;
  }
  if (std::ferror(file.get())) fail("{}: read error while hashing", path.string());
  XXH128_canonical_t canonical;
  XXH128_canonicalFromHash(&canonical, XXH3_128bits_digest(state.get()));
  static constexpr char kHex[] = "0123456789abcdef";
  for (const unsigned char byte : canonical.digest) {
    digest.xxh3_128 += kHex[byte >> 4];
    digest.xxh3_128 += kHex[byte & 15];
  }
  return digest;
}

}  // namespace tw
