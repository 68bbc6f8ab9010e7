#pragma once
// A layer file of a run opened as one GDAL raster, whatever its format: a GeoTIFF or a tiled
// run's VRT mosaic through GDAL, an EXR (this GDAL has no EXR driver) read by OpenEXR into an
// in-memory GDAL dataset over its pixels, with its grid, CRS and channel names as band
// descriptions. The commands that read a finished run (`export`, `view`) read through it, so a
// run written with `output.formats: [exr]` serves them as well as one with GeoTIFF twins.
#include <filesystem>
#include <memory>

class GDALDataset;

namespace tw {

struct ExrContents;

class LayerRaster {
 public:
  // Throws tw::Error naming the file when it cannot be opened or read.
  explicit LayerRaster(const std::filesystem::path& path);
  ~LayerRaster();
  LayerRaster(const LayerRaster&) = delete;
  LayerRaster& operator=(const LayerRaster&) = delete;

  GDALDataset& dataset() const { return *dataset_; }

 private:
  std::unique_ptr<ExrContents> exr_;  // the pixels an EXR's in-memory dataset points at
  GDALDataset* dataset_ = nullptr;
};

}  // namespace tw
