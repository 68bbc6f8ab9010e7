#include "layers/detail/band_reader.hpp"

#include <cstring>
#include <limits>

#include "core/error.hpp"
#include "image/image_io.hpp"
#include "layers/detail/gdal_init.hpp"

namespace tw::detail {
namespace {

class GdalBandReader final : public BandReader {
 public:
  explicit GdalBandReader(const std::filesystem::path& path) : path_(path) {
    ensure_gdal_registered();
    dataset_.reset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!dataset_) fail("{}: cannot be opened as a raster", path.string());
    width = dataset_->GetRasterXSize();
    height = dataset_->GetRasterYSize();
    for (int b = 1; b <= dataset_->GetRasterCount(); ++b) {
      const std::string name = dataset_->GetRasterBand(b)->GetDescription();
      bands.push_back(name.empty() ? "band" + std::to_string(b) : name);
    }
  }

  void read_rows(int row, int rows, std::vector<float>& out) override {
    out.resize(std::size_t(bands.size()) * rows * width);
    for (std::size_t b = 0; b < bands.size(); ++b) {
      GDALRasterBand* band = dataset_->GetRasterBand(int(b) + 1);
      float* at = out.data() + b * std::size_t(rows) * width;
      if (band->RasterIO(GF_Read, 0, row, width, rows, at, width, rows, GDT_Float32, 0, 0) !=
          CE_None) {
        fail("{}: cannot read band {} rows {}..{}", path_.string(), b + 1, row, row + rows);
      }
      int has_nodata = 0;
      const double nodata = band->GetNoDataValue(&has_nodata);
      if (!has_nodata) continue;  // nodata values read as NaN, as in terraweave's rasters
      for (std::size_t i = 0; i < std::size_t(rows) * width; ++i)
        if (at[i] == float(nodata)) at[i] = std::numeric_limits<float>::quiet_NaN();
    }
  }

 private:
  std::filesystem::path path_;
  std::unique_ptr<GDALDataset> dataset_;
};

class ImageBandReader final : public BandReader {
 public:
  explicit ImageBandReader(const std::filesystem::path& path)
      : path_(path), image_(open_image_rows(path.string())) {
    width = image_.width;
    height = image_.height;
    bands = image_.channel_names;
  }

  void read_rows(int row, int rows, std::vector<float>& out) override {
    const std::size_t n = bands.size();
    read_image_rows(image_, path_.string(), row, rows, interleaved_);
    out.resize(interleaved_.size());
    const std::size_t pixels = std::size_t(rows) * width;
    for (std::size_t p = 0; p < pixels; ++p)
      for (std::size_t c = 0; c < n; ++c) out[c * pixels + p] = interleaved_[p * n + c];
  }

 private:
  std::filesystem::path path_;
  ImageRows image_;
  std::vector<float> interleaved_;
};

}  // namespace

std::unique_ptr<BandReader> open_band_reader(const std::filesystem::path& path) {
  if (path.extension() == ".exr") return std::make_unique<ImageBandReader>(path);
  return std::make_unique<GdalBandReader>(path);
}

}  // namespace tw::detail
