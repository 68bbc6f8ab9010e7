#include "layers/detail/engine_raster.hpp"

#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <numeric>

#include "core/error.hpp"
#include "geo/resample.hpp"
#include "layers/detail/gdal_init.hpp"

namespace tw::detail {

namespace {

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

DatasetPtr mem_dataset(int width, int height, int bands, GDALDataType type) {
  ensure_gdal_registered();
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr ds(mem->Create("", width, height, bands, type, nullptr));
  if (!ds)
    fail("cannot create an in-memory raster of {} x {}: {}", width, height, CPLGetLastErrorMsg());
  return ds;
}

void copy_to_png(GDALDataset& source, const std::filesystem::path& path) {
  GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
  if (png == nullptr) fail("GDAL has no PNG driver (writing {})", path.string());
  CPLStringList options;
  options.SetNameValue("ZLEVEL", "6");
  CPLErrorReset();
  DatasetPtr out(png->CreateCopy(path.c_str(), &source, false, options.List(), nullptr, nullptr));
  if (!out) fail("cannot write PNG {}: {}", path.string(), CPLGetLastErrorMsg());
  out.reset();
  if (CPLGetLastErrorType() == CE_Failure)
    fail("cannot finish PNG {}: {}", path.string(), CPLGetLastErrorMsg());
  // The PNG driver leaves a .aux.xml beside it for what PNG cannot hold; engines need none.
  std::filesystem::path aux = path;
  aux += ".aux.xml";
  std::filesystem::remove(aux);
}

}  // namespace

Raster<float> fill_nodata(const Raster<float>& height, std::optional<double> value) {
  Raster<float> out = height;
  const auto nodata =
      std::count_if(out.pixels.begin(), out.pixels.end(), [](float h) { return std::isnan(h); });
  if (nodata == 0) return out;
  if (nodata == std::ptrdiff_t(out.pixels.size())) fail("the height layer is nodata everywhere");
  if (value) {
    for (float& h : out.pixels)
      if (std::isnan(h)) h = float(*value);
    return out;
  }
  DatasetPtr ds = mem_dataset(out.width, out.height, 2, GDT_Float32);
  std::vector<std::uint8_t> mask(out.pixels.size());
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = std::isnan(out.pixels[i]) ? 0 : 255;
  GDALRasterBand* band = ds->GetRasterBand(1);
  if (band->RasterIO(GF_Write, 0, 0, out.width, out.height, out.pixels.data(), out.width,
                     out.height, GDT_Float32, 0, 0) != CE_None ||
      ds->GetRasterBand(2)->RasterIO(GF_Write, 0, 0, out.width, out.height, mask.data(), out.width,
                                     out.height, GDT_Byte, 0, 0) != CE_None)
    fail("cannot fill nodata: {}", CPLGetLastErrorMsg());
  const double distance = double(std::max(out.width, out.height));
  if (GDALFillNodata(band, ds->GetRasterBand(2), distance, 0, 0, nullptr, nullptr, nullptr) !=
          CE_None ||
      band->RasterIO(GF_Read, 0, 0, out.width, out.height, out.pixels.data(), out.width, out.height,
                     GDT_Float32, 0, 0) != CE_None)
    fail("cannot fill nodata: {}", CPLGetLastErrorMsg());
  return out;
}

GridSpec vertex_grid(const GridSpec& grid, int nx, int ny) {
  if (grid.width < 2 || grid.height < 2 || nx < 2 || ny < 2)
    fail("an engine heightmap needs at least 2 x 2 cells (the grid is {} x {})", grid.width,
         grid.height);
  GridSpec out;
  out.width = nx;
  out.height = ny;
  out.pixel_width = (grid.width - 1) * grid.pixel_width / (nx - 1);
  out.pixel_height = (grid.height - 1) * grid.pixel_height / (ny - 1);
  out.origin_x = grid.origin_x + 0.5 * grid.pixel_width - 0.5 * out.pixel_width;
  out.origin_y = grid.origin_y - 0.5 * grid.pixel_height + 0.5 * out.pixel_height;
  return out;
}

GridSpec texel_grid(const GridSpec& grid, int nx, int ny) {
  GridSpec out;
  out.width = nx;
  out.height = ny;
  out.pixel_width = (grid.width - 1) * grid.pixel_width / nx;
  out.pixel_height = (grid.height - 1) * grid.pixel_height / ny;
  out.origin_x = grid.origin_x + 0.5 * grid.pixel_width;
  out.origin_y = grid.origin_y - 0.5 * grid.pixel_height;
  return out;
}

Raster<float> resample_band(const Raster<float>& band, const GridSpec& from, const GridSpec& to) {
  if (to.width == from.width && to.height == from.height &&
      to == vertex_grid(from, to.width, to.height))
    return band;  // the vertices are the cell centres
  return resample_heights(band, from, to, Resampling::bilinear);
}

Heightmap16 quantize_heights(const Raster<float>& heights) {
  const auto [lo, hi] = std::minmax_element(heights.pixels.begin(), heights.pixels.end());
  return quantize_heights(heights, *lo, *hi);
}

Heightmap16 quantize_heights(const Raster<float>& heights, double min, double max) {
  Heightmap16 map;
  map.width = heights.width;
  map.height = heights.height;
  map.min = min;
  map.max = max;
  const double range = map.max - map.min;
  map.pixels.resize(heights.pixels.size());
  for (std::size_t i = 0; i < map.pixels.size(); ++i) {
    const double v = range > 0.0 ? (heights.pixels[i] - map.min) / range * 65535.0 : 0.0;
    map.pixels[i] = std::uint16_t(std::clamp(std::lround(v), 0L, 65535L));
  }
  return map;
}

std::vector<std::vector<std::uint8_t>> quantize_weights(const std::vector<Raster<float>>& weights) {
  const std::size_t n = weights.size();
  if (n == 0) return {};
  const std::size_t pixels = weights.front().pixels.size();
  std::vector<std::vector<std::uint8_t>> out(n, std::vector<std::uint8_t>(pixels));
  std::vector<double> scaled(n);
  std::vector<std::size_t> order(n);
  for (std::size_t p = 0; p < pixels; ++p) {
    double sum = 0.0;
    for (std::size_t m = 0; m < n; ++m) {
      const float w = weights[m].pixels[p];
      scaled[m] = std::isnan(w) || w < 0.0f ? 0.0 : double(w);
      sum += scaled[m];
    }
    if (sum <= 0.0) {
      scaled.assign(n, 0.0);
      scaled[0] = sum = 1.0;
    }
    int given = 0;
    for (std::size_t m = 0; m < n; ++m) {
      scaled[m] = scaled[m] / sum * 255.0;
      const int whole = int(std::floor(scaled[m]));
      out[m][p] = std::uint8_t(whole);
      given += whole;
      scaled[m] -= whole;
    }
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return scaled[a] > scaled[b]; });
    for (int k = 0; given < 255; ++k, ++given) ++out[order[std::size_t(k) % n]][p];
  }
  return out;
}

void write_png(const std::filesystem::path& path, int width, int height,
               const std::vector<const std::uint8_t*>& bands) {
  DatasetPtr ds = mem_dataset(width, height, int(bands.size()), GDT_Byte);
  for (std::size_t b = 0; b < bands.size(); ++b)
    if (ds->GetRasterBand(int(b) + 1)
            ->RasterIO(GF_Write, 0, 0, width, height, const_cast<std::uint8_t*>(bands[b]), width,
                       height, GDT_Byte, 0, 0) != CE_None)
      fail("cannot write {}: {}", path.string(), CPLGetLastErrorMsg());
  if (bands.size() == 4)
    for (int b = 0; b < 4; ++b)
      ds->GetRasterBand(b + 1)->SetColorInterpretation(GDALColorInterp(GCI_RedBand + b));
  copy_to_png(*ds, path);
}

void write_png16(const std::filesystem::path& path, const Heightmap16& map) {
  DatasetPtr ds = mem_dataset(map.width, map.height, 1, GDT_UInt16);
  if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, map.width, map.height,
                                     const_cast<std::uint16_t*>(map.pixels.data()), map.width,
                                     map.height, GDT_UInt16, 0, 0) != CE_None)
    fail("cannot write {}: {}", path.string(), CPLGetLastErrorMsg());
  copy_to_png(*ds, path);
}

void write_raw16(const std::filesystem::path& path, const Heightmap16& map, bool bottom_up) {
  std::ofstream out(path, std::ios::binary);
  std::vector<unsigned char> row(std::size_t(map.width) * 2);
  for (int r = 0; r < map.height; ++r) {
    const std::uint16_t* src =
        map.pixels.data() + std::size_t(bottom_up ? map.height - 1 - r : r) * map.width;
    for (int c = 0; c < map.width; ++c) {
      row[std::size_t(c) * 2] = std::uint8_t(src[c] & 0xff);
      row[std::size_t(c) * 2 + 1] = std::uint8_t(src[c] >> 8);
    }
    out.write(reinterpret_cast<const char*>(row.data()), std::streamsize(row.size()));
  }
  out.close();
  if (!out) fail("cannot write {}", path.string());
}

}  // namespace tw::detail
