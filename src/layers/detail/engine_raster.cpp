#include "layers/detail/engine_raster.hpp"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
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

double fitting_spacing(const GridSpec& world, int nx, int ny) {
  if (world.width < 2 || world.height < 2 || nx < 2 || ny < 2)
    fail("an engine heightmap needs at least 2 x 2 cells (the grid is {} x {})", world.width,
         world.height);
  // n == cells: the cell size itself, not (cells - 1) x cell / (cells - 1) with its rounding.
  const double sx =
      nx == world.width ? world.pixel_width : (world.width - 1) * world.pixel_width / (nx - 1);
  const double sy =
      ny == world.height ? world.pixel_height : (world.height - 1) * world.pixel_height / (ny - 1);
  return std::max(sx, sy);
}

int vertices_over(double span, double spacing) {
  // The tolerance keeps a span of exactly n spacings (up to rounding) at n + 1 vertices.
  return int(std::floor(span / spacing * (1.0 + 1e-12) + 1e-9)) + 1;
}

namespace {

// The world's samples at `corner` of a width x height raster.
Window world_window(int width, int height, int data_width, int data_height, OriginCorner corner) {
  data_width = std::clamp(data_width, 1, width);
  data_height = std::clamp(data_height, 1, height);
  return {0, corner == OriginCorner::north_west ? 0 : height - data_height, data_width,
          data_height};
}

}  // namespace

EngineVertices engine_vertices(const GridSpec& world, int width, int height, double spacing,
                               OriginCorner corner) {
  EngineVertices v{width, height, spacing, {}, {}};
  const int mx = vertices_over((world.width - 1) * world.pixel_width, spacing);
  const int my = vertices_over((world.height - 1) * world.pixel_height, spacing);
  v.world = world_window(width, height, mx, my, corner);
  if (spacing == world.pixel_width && spacing == world.pixel_height &&
      v.world.width == world.width && v.world.height == world.height) {
    v.data = world;  // the vertices are the cell centres
    return v;
  }
  const double west = world.origin_x + 0.5 * world.pixel_width;
  const double north = world.origin_y - 0.5 * world.pixel_height;
  const double south = world.origin_y - (world.height - 0.5) * world.pixel_height;
  v.data.width = v.world.width;
  v.data.height = v.world.height;
  v.data.pixel_width = v.data.pixel_height = spacing;
  v.data.origin_x = west - 0.5 * spacing;
  v.data.origin_y = corner == OriginCorner::north_west
                        ? north + 0.5 * spacing
                        : south + (v.world.height - 1) * spacing + 0.5 * spacing;
  return v;
}

EngineVertices engine_texels(const GridSpec& world, int width, int height, double spacing,
                             OriginCorner corner) {
  EngineVertices v{width, height, spacing, {}, {}};
  const auto texels = [spacing](double span) {
    return std::max(1, int(std::floor(span / spacing * (1.0 + 1e-12) + 1e-9)));
  };
  v.world = world_window(width, height, texels((world.width - 1) * world.pixel_width),
                         texels((world.height - 1) * world.pixel_height), corner);
  const double west = world.origin_x + 0.5 * world.pixel_width;
  const double north = world.origin_y - 0.5 * world.pixel_height;
  const double south = world.origin_y - (world.height - 0.5) * world.pixel_height;
  v.data.width = v.world.width;
  v.data.height = v.world.height;
  v.data.pixel_width = v.data.pixel_height = spacing;
  v.data.origin_x = west;
  v.data.origin_y = corner == OriginCorner::north_west ? north : south + v.world.height * spacing;
  return v;
}

Raster<float> pad_to_engine(const Raster<float>& data, const EngineVertices& v,
                            std::optional<float> fill) {
  const Window& w = v.world;
  if (data.width != w.width || data.height != w.height)
    fail("padding {} x {} samples into a window of {} x {}", data.width, data.height, w.width,
         w.height);
  if (!v.padded()) return data;
  Raster<float> out(v.width, v.height);
  for (int r = 0; r < v.height; ++r) {
    const int dr = std::clamp(r - w.row0, 0, w.height - 1);
    const bool row_inside = r >= w.row0 && r < w.row0 + w.height;
    for (int c = 0; c < v.width; ++c) {
      const bool inside = row_inside && c >= w.col0 && c < w.col0 + w.width;
      const int dc = std::clamp(c - w.col0, 0, w.width - 1);
      out.at(c, r) = inside || !fill ? data.at(dc, dr) : *fill;
    }
  }
  return out;
}

std::vector<std::uint8_t> world_mask(const EngineVertices& v) {
  std::vector<std::uint8_t> mask(std::size_t(v.width) * v.height, 0);
  for (int r = v.world.row0; r < v.world.row0 + v.world.height; ++r)
    std::fill_n(mask.begin() + std::ptrdiff_t(std::size_t(r) * v.width + v.world.col0),
                v.world.width, std::uint8_t(255));
  return mask;
}

Raster<float> resample_band(const Raster<float>& band, const GridSpec& from, const GridSpec& to) {
  if (to == from) return band;  // the vertices are the cell centres
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

void write_float_exr(const std::filesystem::path& path, int width, int height,
                     const float* pixels) {
  // Through OpenEXR itself: OpenImageIO's writer stamps a capDate of the current time, and an
  // export must be the same bytes on every run.
  try {
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header);
    Imf::FrameBuffer frame;
    // const_cast: OpenEXR's Slice takes char* for reading and writing alike; it only reads.
    char* base = reinterpret_cast<char*>(const_cast<float*>(pixels));
    frame.insert("R",
                 Imf::Slice(Imf::FLOAT, base, sizeof(float), sizeof(float) * std::size_t(width)));
    file.setFrameBuffer(frame);
    file.writePixels(height);
  } catch (const std::exception& e) {
    fail("cannot write {}: {}", path.string(), e.what());
  }
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
