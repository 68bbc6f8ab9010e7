// EXR layers through OpenEXR directly: planar bands go in as frame-buffer slices (no copy),
// ZIP compression runs on OpenEXR's thread pool.
#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
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
    case ExrCompression::zip:
      return Imf::ZIP_COMPRESSION;
  }
  return Imf::ZIP_COMPRESSION;
}

std::string geotransform_string(const GridSpec& grid) {
  const auto gt = grid.geotransform();
  return fmt::format("{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}", gt[0], gt[1], gt[2], gt[3],
                     gt[4], gt[5]);
}

}  // namespace

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
  return 4 * repeats >= sampled && sampled > 0 ? ExrCompression::rle : ExrCompression::none;
}

void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               int zip_level) {
  write_exr(set, layer, path, ExrCompression::zip, zip_level);
}

void write_exr(const LayerSet& set, const Layer& layer, const std::filesystem::path& path,
               ExrCompression compression, int zip_level) {
  const GridSpec& g = set.grid;
  try {
    const int threads = exr_threads();
    Imf::Header header(g.width, g.height);
    header.compression() = imf_compression(
        compression == ExrCompression::automatic ? exr_compression_for(layer) : compression);
    header.zipCompressionLevel() = zip_level;
    header.insert(kExrCrsAttribute, Imf::StringAttribute(set.crs_wkt));
    header.insert(kExrGeotransformAttribute, Imf::StringAttribute(geotransform_string(g)));
    header.insert(kExrOriginAttribute, Imf::V2dAttribute(Imath::V2d(g.origin_x, g.origin_y)));
    header.insert(kExrPixelSizeAttribute,
                  Imf::V2dAttribute(Imath::V2d(g.pixel_width, g.pixel_height)));
    if (set.nodata) header.insert("terraweave:nodata", Imf::DoubleAttribute(*set.nodata));
    Imf::FrameBuffer frame;
    for (std::size_t i = 0; i < layer.bands.size(); ++i) {
      header.channels().insert(layer.channels[i], Imf::Channel(Imf::FLOAT));
      // const_cast: OpenEXR's Slice takes char* for reading and writing alike; it only reads.
      char* base = reinterpret_cast<char*>(const_cast<float*>(layer.bands[i].pixels.data()));
      frame.insert(layer.channels[i], Imf::Slice(Imf::FLOAT, base, sizeof(float),
                                                 sizeof(float) * std::size_t(g.width)));
    }
    Imf::OutputFile file(path.c_str(), header, threads);
    file.setFrameBuffer(frame);
    file.writePixels(g.height);
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
    Imf::FrameBuffer frame;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
      out.channels.push_back(it.name());
      out.bands.emplace_back(out.width, out.height);
    }
    for (std::size_t i = 0; i < out.bands.size(); ++i) {
      char* base =
          reinterpret_cast<char*>(out.bands[i].pixels.data()) -
          (std::ptrdiff_t(dw.min.y) * out.width + dw.min.x) * std::ptrdiff_t(sizeof(float));
      frame.insert(out.channels[i], Imf::Slice(Imf::FLOAT, base, sizeof(float),
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
