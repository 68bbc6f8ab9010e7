#pragma once
// Whether a run reused a cached result (`--cache DIR`, docs/cache.md), and why not.
#include <string>

namespace tw {

struct CacheStatus {
  bool reused = false;
  // Reused: "unchanged", or "avoidance changed, mask the same" / "earlier feature changed, mask
  // the same" (the finer check: the DP would read the same). Rebuilt: "no cache" (run without
  // --cache), "new" (no entry under this key, and none for this feature or tile before), "corrupt
  // entry", or the first part of the key that differs from the last run's: "geometry changed",
  // "config changed", "exemplar changed", "avoidance changed", "earlier feature changed"
  // (features); "heightfield changed", "features changed", "config changed" (tiles).
  std::string why = "no cache";
  std::string key;  // 32 hex digits: the content hash of everything the computation read
};

}  // namespace tw
