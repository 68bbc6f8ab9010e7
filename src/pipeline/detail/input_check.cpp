#include "pipeline/detail/input_check.hpp"

#include <gdal_priv.h>

#include "core/error.hpp"
#include "ornament/element.hpp"
#include "pipeline/detail/exemplar_memo.hpp"
#include "pipeline/methods/patterns/patterns.hpp"

namespace tw::detail {
namespace {

struct DatasetCloser {
  void operator()(GDALDatasetH dataset) const { GDALClose(dataset); }
};

// The GDAL message of the last failure, or a generic one.
std::string gdal_reason(const char* fallback) {
  const char* message = CPLGetLastErrorMsg();
  return message && *message ? message : fallback;
}

void check_gdal_input(const InputFile& input) {
  const bool raster = input.kind == InputFile::Kind::raster;
  CPLErrorReset();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  const std::unique_ptr<void, DatasetCloser> dataset(
      GDALOpenEx(input.path.c_str(), (raster ? GDAL_OF_RASTER : GDAL_OF_VECTOR) | GDAL_OF_READONLY,
                 nullptr, nullptr, nullptr));
  CPLPopErrorHandler();
  if (!dataset) {
    fail("{}: {}: cannot be opened as {} data: {}", input.named_at, input.path.string(),
         raster ? "raster" : "vector", gdal_reason("no GDAL driver recognizes it"));
  }
}

}  // namespace

void check_inputs(const std::vector<InputFile>& inputs,
                  const std::optional<std::filesystem::path>& cache_dir) {
  GDALAllRegister();
  // Only when an exemplar is remembered now. A folder it cannot write is warned about once by
  // the run's synthesis and tile caches, which use the same folder: not here as well.
  Warnings unwritable;
  std::unique_ptr<CacheFolder> folder;
  for (const InputFile& input : inputs) {
    VSIStatBufL stat;
    if (VSIStatL(input.path.c_str(), &stat) != 0) {
      fail("{}: {}: file does not exist", input.named_at, input.path.string());
    }
    if (input.kind == InputFile::Kind::ornament) {
      try {
        read_element_set(input.path);
      } catch (const Error& e) {
        fail("{}: cannot be used as an element set: {}", input.named_at, e.what());
      }
      continue;
    }
    if (input.kind != InputFile::Kind::exemplar) {
      check_gdal_input(input);
      continue;
    }
    // One validated before with these bytes (and height twin) is not decoded again.
    const std::optional<ContentHash> hash =
        cache_dir ? std::optional(exemplar_file_hash(input.path)) : std::nullopt;
    if (hash && remembered_exemplar(*cache_dir, *hash, input.path)) continue;
    Exemplar exemplar;
    try {
      exemplar = load_exemplar_with_height(input.path, false);
    } catch (const Error& e) {
      fail("{}: cannot be used as an exemplar: {}", input.named_at, e.what());
    }
    if (!hash) continue;
    if (!folder) folder = std::make_unique<CacheFolder>(*cache_dir, unwritable);
    remember_exemplar(*folder, *cache_dir, *hash, exemplar);
  }
}

}  // namespace tw::detail
