// EXR layers through OpenEXR directly: planar bands go in as frame-buffer slices (no copy),
// compression runs on OpenEXR's thread pool.
#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfMatrixAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>
#include <ImfThreading.h>
#include <ImfVecAttribute.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <thread>

#include "core/error.hpp"
#include "layers/write.hpp"

namespace tw {

namespace {

// OpenEXR runs its (de)compression tasks on a global pool that starts with no threads: the
// per-file thread count only sizes the line buffers. Without this, every write is serial.
int exr_threads() {
  static const int threads = [] {
    const int n = int(std::max(1u, std::thread::hardware_concurrency()));
    Imf::setGlobalThreadCount(n);
    return n;
  }();
  return threads;
}

Imf::Compression imf_compression(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::automatic:  // resolved per layer before this; none as a fallback
    case ExrCompression::none:
      return Imf::NO_COMPRESSION;
    case ExrCompression::rle:
      return Imf::RLE_COMPRESSION;
    case ExrCompression::zips:
      return Imf::ZIPS_COMPRESSION;
    case ExrCompression::zip:
      return Imf::ZIP_COMPRESSION;
    case ExrCompression::piz:
      return Imf::PIZ_COMPRESSION;
    case ExrCompression::pxr24:
      return Imf::PXR24_COMPRESSION;
    case ExrCompression::b44:
      return Imf::B44_COMPRESSION;
    case ExrCompression::dwaa:
      return Imf::DWAA_COMPRESSION;
    case ExrCompression::dwab:
      return Imf::DWAB_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

std::string geotransform_string(const GridSpec& grid) {
  const auto gt = grid.geotransform();
  return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", gt[0], gt[1], gt[2], gt[3],
                     gt[4], gt[5]);
}

// GDAL's EXR driver reads the geotransform from a 3x3 matrix (frmts/exr/exrdataset.cpp).
Imath::M33d gdal_geotransform_matrix(const GridSpec& grid) {
  const auto gt = grid.geotransform();
  return Imath::M33d(gt[1], gt[2], gt[0], gt[4], gt[5], gt[3], 0.0, 0.0, 1.0);
}

}  // namespace

std::vector<std::string> exr_channel_names(const Layer& layer) {
  std::vector<std::string> names;
  if (layer.channels.size() == 1) return {"Y"};
  for (std::size_t i = 0; i < layer.channels.size(); ++i) {
    if (layer.name == "splat")
      names.push_back(fmt::format("splat{}.{}", i / 4, "RGBA"[i % 4]));
    else
      names.push_back(layer.channels[i] + ".Y");
  }
  return names;
}

ExrCompression exr_compression_for(const Layer& layer) {
  // Every 64th row is plenty to tell runs from noise, and costs nothing next to the write.
  constexpr int kRowStep = 64;
  std::size_t repeats = 0, sampled = 0;
  for (const Raster<float>& band : layer.bands) {
    for (int row = 0; row < band.height; row += kRowStep) {
      const float* line = band.pixels.data() + std::size_t(row) * band.width;
      for (int c = 1; c < band.width; ++c)
        repeats += std::memcmp(&line[c], &line[c - 1], sizeof(float)) == 0;
      sampled += std::size_t(std::max(0, band.width - 1));
    }
  }
  // Runs (splat weights, masks, capped distances): zlib level 1 packs them 3-6x smaller than
  // rle at about rle's cost. Noise (heights): zlib saves under a tenth for ~10x a raw write.
  return 4 * repeats >= sampled && sampled > 0 ? ExrCompression::zip : ExrCompression::none;
}

void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               int zip_level) {
  write_exr(set, layer, path, ExrCompression::zip, zip_level);
}

const char* to_string(ExrCompression compression) {
  switch (compression) {
    case ExrCompression::automatic:
      return "automatic";
    case ExrCompression::none:
      return "none";
    case ExrCompression::rle:
      return "rle";
    case ExrCompression::zips:
      return "zips";
    case ExrCompression::zip:
      return "zip";
    case ExrCompression::piz:
      return "piz";
    case ExrCompression::pxr24:
      return "pxr24";
    case ExrCompression::b44:
      return "b44";
    case ExrCompression::dwaa:
      return "dwaa";
    case ExrCompression::dwab:
      return "dwab";
  }
  return "?";
}

bool exr_half_for(const Layer& layer, ExrPixels pixels) {
  switch (pixels) {
    case ExrPixels::float32:
      return false;
    case ExrPixels::half:
      return true;
    case ExrPixels::automatic:
      // By the channels, not the name: a tile's splat layer is named splat_x<i>_y<j>.
      return !layer.channels.empty() &&
             std::all_of(layer.channels.begin(), layer.channels.end(),
                         [](const std::string& c) { return c.starts_with("splat."); });
  }
  return false;
}

void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               ExrCompression compression, int zip_level, ExrPixels pixels) {
  const GridSpec& g = set.grid;
  const bool half = exr_half_for(layer, pixels);
  const std::vector<std::string> names = exr_channel_names(layer);
  try {
    const int threads = exr_threads();
    Imf::Header header(g.width, g.height);
    header.compression() = imf_compression(
        compression == ExrCompression::automatic ? exr_compression_for(layer) : compression);
    header.zipCompressionLevel() = zip_level;
    if (!set.crs_wkt.empty())
      header.insert(kExrGdalCrsAttribute, Imf::StringAttribute(set.crs_wkt));
    header.insert(kExrGdalGeotransformAttribute, Imf::M33dAttribute(gdal_geotransform_matrix(g)));
    header.insert(kExrLayerAttribute, Imf::StringAttribute(layer.name));
    header.insert(kExrChannelsAttribute, Imf::StringVectorAttribute(layer.channels));
    header.insert(kExrCrsAttribute, Imf::StringAttribute(set.crs_wkt));
    header.insert(kExrGeotransformAttribute, Imf::StringAttribute(geotransform_string(g)));
    header.insert(kExrOriginAttribute, Imf::V2dAttribute(Imath::V2d(g.origin_x, g.origin_y)));
    header.insert(kExrPixelSizeAttribute,
                  Imf::V2dAttribute(Imath::V2d(g.pixel_width, g.pixel_height)));
    if (set.nodata) header.insert("terraweave:nodata", Imf::DoubleAttribute(*set.nodata));
    for (std::size_t i = 0; i < layer.bands.size(); ++i)
      header.channels().insert(names[i], Imf::Channel(half ? Imf::HALF : Imf::FLOAT));
    Imf::OutputFile file(path.c_str(), header, threads);
    if (!half) {
      Imf::FrameBuffer frame;
      for (std::size_t i = 0; i < layer.bands.size(); ++i) {
        // const_cast: OpenEXR's Slice takes char* for reading and writing alike; it only reads.
        char* base = reinterpret_cast<char*>(const_cast<float*>(layer.bands[i].pixels.data()));
        frame.insert(names[i], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                          sizeof(float) * std::size_t(g.width)));
      }
      file.setFrameBuffer(frame);
      file.writePixels(g.height);
      return;
    }
    // OpenEXR does not convert on output: half copies of a band of rows at a time.
    constexpr int kRowsPerChunk = 256;
    std::vector<std::vector<Imath::half>> chunks(layer.bands.size());
    for (int row = 0; row < g.height; row += kRowsPerChunk) {
      const int rows = std::min(kRowsPerChunk, g.height - row);
      const std::size_t offset = std::size_t(row) * g.width;
      Imf::FrameBuffer frame;
      for (std::size_t i = 0; i < layer.bands.size(); ++i) {
        const float* src = layer.bands[i].pixels.data() + offset;
        chunks[i].assign(src, src + std::size_t(rows) * g.width);
        char* base = reinterpret_cast<char*>(chunks[i].data()) -
                     std::ptrdiff_t(offset) * std::ptrdiff_t(sizeof(Imath::half));
        frame.insert(names[i], Imf::Slice(Imf::HALF, base, sizeof(Imath::half),
                                          sizeof(Imath::half) * std::size_t(g.width)));
      }
      file.setFrameBuffer(frame);
      file.writePixels(rows);
    }
  } catch (const std::exception& e) {
    fail("cannot write layer '{}' to {}: {}", layer.name, path.string(), e.what());
  }
}

ExrContents read_exr(const std::filesystem::path& path) {
  ExrContents out;
  try {
    Imf::InputFile file(path.c_str(), exr_threads());
    const Imf::Header& header = file.header();
    const auto dw = header.dataWindow();
    out.width = dw.max.x - dw.min.x + 1;
    out.height = dw.max.y - dw.min.y + 1;
    if (const auto* a = header.findTypedAttribute<Imf::StringAttribute>(kExrCrsAttribute))
      out.crs_wkt = a->value();
    if (const auto* a = header.findTypedAttribute<Imf::StringAttribute>(kExrGeotransformAttribute))
      out.geotransform = a->value();
    if (const auto* a = header.findTypedAttribute<Imf::V2dAttribute>(kExrOriginAttribute))
      out.origin = {a->value().x, a->value().y};
    if (const auto* a = header.findTypedAttribute<Imf::V2dAttribute>(kExrPixelSizeAttribute))
      out.pixel_size = {a->value().x, a->value().y};
    // Bands in the layer's order under its names when terraweave wrote the file, else the
    // file's channels as they are (alphabetical).
    Layer layer;
    if (const auto* a = header.findTypedAttribute<Imf::StringAttribute>(kExrLayerAttribute))
      layer.name = a->value();
    if (const auto* a =
            header.findTypedAttribute<Imf::StringVectorAttribute>(kExrChannelsAttribute))
      layer.channels = a->value();
    if (!layer.channels.empty()) {
      out.channels = layer.channels;
      out.exr_channels = exr_channel_names(layer);
      for (const std::string& name : out.exr_channels)
        if (header.channels().findChannel(name) == nullptr)
          fail("EXR {} lists channel '{}' but does not hold it", path.string(), name);
    } else {
      for (auto it = header.channels().begin(); it != header.channels().end(); ++it)
        out.exr_channels.push_back(it.name());
      out.channels = out.exr_channels;
    }
    Imf::FrameBuffer frame;
    for (std::size_t i = 0; i < out.exr_channels.size(); ++i)
      out.bands.emplace_back(out.width, out.height);
    for (std::size_t i = 0; i < out.bands.size(); ++i) {
      char* base =
          reinterpret_cast<char*>(out.bands[i].pixels.data()) -
          (std::ptrdiff_t(dw.min.y) * out.width + dw.min.x) * std::ptrdiff_t(sizeof(float));
      frame.insert(out.exr_channels[i], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                   sizeof(float) * std::size_t(out.width)));
    }
    file.setFrameBuffer(frame);
    file.readPixels(dw.min.y, dw.max.y);
  } catch (const std::exception& e) {
    fail("cannot read EXR {}: {}", path.string(), e.what());
  }
  return out;
}

}  // namespace tw
