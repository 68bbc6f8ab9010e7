#pragma once
// Every file a run will open, checked before any stage starts: a missing or unreadable one is
// reported at the pipeline key that names it ("file:line:col: key: ..."), by run and validate.
#include <filesystem>
#include <optional>
#include <vector>

#include "pipeline/config.hpp"

namespace tw::detail {

// Throws tw::Error "<file:line:col>: <key>: <path>: <problem>" for the first input that does
// not exist or cannot be opened as what its key expects: raster data (heightfield), vector
// data (sources), an exemplar image (read whole, with its NAME_height.tif twin when present).
// `inputs`: the pipeline's (PipelineConfig::inputs). With a run cache, an exemplar whose bytes
// were validated before is not read again, and one validated now is remembered there
// (detail/exemplar_memo.hpp; a failed write only means it is read again next time).
void check_inputs(const std::vector<InputFile>& inputs,
                  const std::optional<std::filesystem::path>& cache_dir);

}  // namespace tw::detail
