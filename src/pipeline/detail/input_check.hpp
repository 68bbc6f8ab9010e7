#pragma once
// Every file a run will open, checked before any stage starts: a missing or unreadable one is
// reported at the pipeline key that names it ("file:line:col: key: ..."), by run and validate.
// The pipeline checks that each exists and opens raster and vector data; a method checks its
// own inputs (SynthesisMethod::check_input: the patterns' exemplars, grown's element sets).
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/warnings.hpp"
#include "pipeline/config.hpp"
#include "pipeline/detail/cache_entry.hpp"

namespace tw {
class SynthesisMethod;
}

namespace tw::detail {

// What the methods' checks share over one check_inputs.
class InputCheck {
 public:
  explicit InputCheck(std::optional<std::filesystem::path> cache_dir)
      : cache_dir_(std::move(cache_dir)) {}
  // The run cache, where an input validated before may be remembered; none: no cache.
  const std::optional<std::filesystem::path>& cache_dir() const { return cache_dir_; }
  // The cache folder, opened when an input is first remembered and held until the check ends.
  CacheFolder& cache_folder();

 private:
  std::optional<std::filesystem::path> cache_dir_;
  // A folder it cannot write is warned about once by the run's synthesis and tile caches, which
  // use the same folder: not here as well.
  Warnings unwritable_;
  std::unique_ptr<CacheFolder> folder_;
};

// Throws tw::Error "<file:line:col>: <key>: <path>: <problem>" for the first input that does
// not exist or cannot be opened as what its key expects: raster data (heightfield), vector
// data (sources), or what the method that owns it checks (SynthesisMethod::check_input).
// `inputs`: the pipeline's (PipelineConfig::inputs); `methods`: empty: the built-in ones;
// `cache_dir`: the run cache, which a method may remember its validated inputs in.
void check_inputs(const std::vector<InputFile>& inputs,
                  const std::optional<std::filesystem::path>& cache_dir,
                  const std::vector<const SynthesisMethod*>& methods = {});

}  // namespace tw::detail
