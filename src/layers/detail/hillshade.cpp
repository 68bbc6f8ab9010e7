#include "layers/detail/hillshade.hpp"

#include <gdal_priv.h>
#include <gdal_utils.h>

#include <cmath>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "layers/detail/gdal_init.hpp"

namespace tw::detail {

namespace {

struct DemOptionsDeleter {
  void operator()(GDALDEMProcessingOptions* o) const { GDALDEMProcessingOptionsFree(o); }
};

}  // namespace

Raster<float> hillshade(const Raster<float>& heights, double cell_x, double cell_y) {
  ensure_gdal_registered();
  const int w = heights.width, h = heights.height;
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  if (mem == nullptr) fail("GDAL lacks the MEM driver (hillshade)");
  std::unique_ptr<GDALDataset> dem(mem->Create("", w, h, 1, GDT_Float32, nullptr));
  // Infinities are nodata as NaN is: GDAL's nodata test knows NaN only.
  std::vector<float> values(heights.pixels);
  for (float& v : values)
    if (!std::isfinite(v)) v = std::numeric_limits<float>::quiet_NaN();
  GDALRasterBand* band = dem->GetRasterBand(1);
  band->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
  double transform[6] = {0.0, cell_x, 0.0, 0.0, 0.0, -cell_y};
  dem->SetGeoTransform(transform);
  CPLErrorReset();
  if (band->RasterIO(GF_Write, 0, 0, w, h, values.data(), w, h, GDT_Float32, 0, 0) != CE_None)
    fail("hillshade: {}", CPLGetLastErrorMsg());

  const char* const args[] = {"-of", "MEM",  "-alg", "ZevenbergenThorne", "-z", "2",    "-az",
                              "315", "-alt", "45",   "-compute_edges",    "-q", nullptr};
  const std::unique_ptr<GDALDEMProcessingOptions, DemOptionsDeleter> options(
      GDALDEMProcessingOptionsNew(const_cast<char**>(args), nullptr));
  int usage_error = FALSE;
  std::unique_ptr<GDALDataset> shaded(GDALDataset::FromHandle(GDALDEMProcessing(
      "", GDALDataset::ToHandle(dem.get()), "hillshade", nullptr, options.get(), &usage_error)));
  if (!shaded) fail("hillshade: GDALDEMProcessing: {}", CPLGetLastErrorMsg());
  std::vector<std::uint8_t> bytes(std::size_t(w) * h);
  if (shaded->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, bytes.data(), w, h, GDT_Byte, 0, 0) !=
      CE_None)
    fail("hillshade: {}", CPLGetLastErrorMsg());

  // GDAL writes 1 + 254 cos(angle), 1 in the shadow, 0 (its nodata) where the centre is nodata
  // or its cosine is NaN (a slope overflowed).
  Raster<float> light(w, h, std::numeric_limits<float>::quiet_NaN());
  for (std::size_t k = 0; k < bytes.size(); ++k) {
    if (std::isnan(values[k])) continue;
    light.pixels[k] = bytes[k] == 0 ? 1.0f : float(bytes[k] - 1) / 254.0f;
  }
  return light;
}

}  // namespace tw::detail
