#pragma once
// Reads the bands of a raster file a few rows at a time: GDAL for what it opens, OpenImageIO
// for EXR (GDAL's EXR driver is not in Debian's build).
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace tw::detail {

class BandReader {
 public:
  virtual ~BandReader() = default;
  int width = 0, height = 0;
  std::vector<std::string> bands;  // names: GeoTIFF descriptions, EXR channels
  // Rows [row, row + rows) of every band, as floats: out[(band * rows + r) * width + col].
  virtual void read_rows(int row, int rows, std::vector<float>& out) = 0;
};

// Throws tw::Error naming the file when it cannot be opened.
std::unique_ptr<BandReader> open_band_reader(const std::filesystem::path& path);

}  // namespace tw::detail
