#pragma once
// Exemplars the run cache has seen (docs/cache.md): DIR/exemplars/<hash>.twc, keyed by the
// bytes of the image and of its NAME_height.tif twin, holds what a run needs of an exemplar
// that is valid without reading it again: its size and channel names. An exemplar whose bytes
// hash to a remembered value was validated before (the input check skips it) and, while every
// synthesis using it comes from the cache, its texels are never read (no image decoded, the
// image module not loaded: issue #23 item 2).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/content_hash.hpp"
#include "pipeline/detail/cache_entry.hpp"
#include "synth/exemplar.hpp"

namespace tw::detail {

// The exemplar's identity in every cache key: its image and the height twin beside it.
ContentHash exemplar_file_hash(const std::filesystem::path& path);

// The remembered exemplar under `hash` in the cache `dir`, as an Exemplar without texels (size,
// channel names, `path`); nullopt when absent or unreadable (then it is read and checked anew).
std::optional<Exemplar> remembered_exemplar(const std::filesystem::path& dir,
                                            const ContentHash& hash,
                                            const std::filesystem::path& path);

// Remembers a validated exemplar (through `folder`: a failed write is its warning).
void remember_exemplar(CacheFolder& folder, const std::filesystem::path& dir,
                       const ContentHash& hash, const Exemplar& exemplar);

}  // namespace tw::detail
