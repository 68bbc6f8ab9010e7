#include "pipeline/detail/input_check.hpp"

#include <gdal_priv.h>

#include <algorithm>

#include "core/error.hpp"
#include "pipeline/synthesis_method.hpp"

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

CacheFolder& InputCheck::cache_folder() {
  if (!folder_) folder_ = std::make_unique<CacheFolder>(*cache_dir_, unwritable_);
  return *folder_;
}

void check_inputs(const std::vector<InputFile>& inputs,
                  const std::optional<std::filesystem::path>& cache_dir,
                  const std::vector<const SynthesisMethod*>& methods) {
  GDALAllRegister();
  InputCheck check(cache_dir);
  const std::vector<const SynthesisMethod*>& all = methods_or_builtin(methods);
  for (const InputFile& input : inputs) {
    VSIStatBufL stat;
    if (VSIStatL(input.path.c_str(), &stat) != 0) {
      fail("{}: {}: file does not exist", input.named_at, input.path.string());
    }
    if (std::any_of(all.begin(), all.end(),
                    [&](const SynthesisMethod* m) { return m->check_input(input, check); }))
      continue;
    // A method's input that no method given checks (a list without it) only has to exist.
    if (input.kind != InputFile::Kind::method) check_gdal_input(input);
  }
}

}  // namespace tw::detail
