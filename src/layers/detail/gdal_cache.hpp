#pragma once
// GDAL's block cache bounded while an export streams a world through it. By default GDAL keeps
// up to GDAL_CACHEMAX (5 % of RAM: 1.2 GB on a 24 GB machine) of blocks that an export reads
// once per pass: the resident memory then grows with the world, not with the tile being
// written. A user's own GDAL_CACHEMAX (environment or --config) is left as it is.
#include <cpl_conv.h>
#include <gdal.h>

#include <cstdint>

namespace tw::detail {

// Enough for the blocks under one export tile's window of every band it reads in turn, so
// a tile's own reads never evict each other; the next tile rereads its shared edge.
inline constexpr std::int64_t kExportGdalCacheBytes = std::int64_t(64) << 20;

class ScopedGdalCacheMax {
 public:
  explicit ScopedGdalCacheMax(std::int64_t bytes) : previous_(GDALGetCacheMax64()) {
    limited_ = CPLGetConfigOption("GDAL_CACHEMAX", nullptr) == nullptr && bytes < previous_;
    if (limited_) GDALSetCacheMax64(bytes);  // flushes what is cached beyond `bytes`
  }
  ~ScopedGdalCacheMax() {
    if (limited_) GDALSetCacheMax64(previous_);
  }
  ScopedGdalCacheMax(const ScopedGdalCacheMax&) = delete;
  ScopedGdalCacheMax& operator=(const ScopedGdalCacheMax&) = delete;

 private:
  std::int64_t previous_;
  bool limited_ = false;
};

}  // namespace tw::detail
