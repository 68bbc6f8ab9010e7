// Engine exports in tiles (Unreal World Partition, Unity Terrain Tools) from a run's layer files
// read by windows through GDAL. One grid of vertices spans the world (as one heightmap's
// would); tiles of S samples cut it, tile i starting at vertex i (S - 1), so neighbours share
// their edge row and column and compute them from the same vertices: the same bits. Two
// passes: the first finds the world's height range (one Z scale for every tile), the second
// writes. Memory: one tile and its source window.
#include <cpl_string.h>
#include <fmt/format.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/progress.hpp"
#include "geo/resample.hpp"
#include "layers/detail/engine_exports.hpp"
#include "layers/detail/engine_raster.hpp"
#include "layers/detail/gdal_cache.hpp"
#include "layers/detail/gdal_init.hpp"

namespace tw {

namespace {

namespace fs = std::filesystem;

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(d); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

struct LayerFile {
  DatasetPtr ds;
  GridSpec grid;
  std::string crs_wkt;
  std::vector<std::string> channels;
};

LayerFile open_layer_file(const fs::path& path, bool update = false) {
  detail::ensure_gdal_registered();
  LayerFile f;
  f.ds.reset(GDALDataset::Open(path.c_str(),
                               GDAL_OF_RASTER | (update ? GDAL_OF_UPDATE : GDAL_OF_READONLY)));
  if (!f.ds) fail("cannot open {}: {}", path.string(), CPLGetLastErrorMsg());
  double gt[6];
  if (f.ds->GetGeoTransform(gt) != CE_None || gt[2] != 0.0 || gt[4] != 0.0 || gt[5] >= 0.0)
    fail("{}: not a north-up georeferenced raster", path.string());
  f.grid = {f.ds->GetRasterXSize(), f.ds->GetRasterYSize(), gt[0], gt[3], gt[1], -gt[5]};
  if (const OGRSpatialReference* srs = f.ds->GetSpatialRef()) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    f.crs_wkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  for (int b = 1; b <= f.ds->GetRasterCount(); ++b) {
    const char* d = f.ds->GetRasterBand(b)->GetDescription();
    f.channels.push_back(d && *d ? d : fmt::format("band{}", b));
  }
  return f;
}

// `window` of band `band` (1-based), nodata as NaN.
Raster<float> read_window(const LayerFile& f, int band, const Window& w) {
  GDALRasterBand* b = f.ds->GetRasterBand(band);
  Raster<float> r(w.width, w.height);
  if (b->RasterIO(GF_Read, w.col0, w.row0, w.width, w.height, r.pixels.data(), w.width, w.height,
                  GDT_Float32, 0, 0) != CE_None)
    fail("cannot read {}: {}", f.ds->GetDescription(), CPLGetLastErrorMsg());
  int has_nodata = 0;
  const double nodata = b->GetNoDataValue(&has_nodata);
  if (has_nodata && !std::isnan(nodata))
    for (float& v : r.pixels)
      if (v == float(nodata)) v = std::nanf("");
  return r;
}

// A temporary copy of the height file with its nodata filled by GDALFillNodata as fill_nodata
// fills a whole layer (search distance: the world), worked through a few rows at a time.
struct FilledCopy {
  fs::path path;
  ~FilledCopy() {
    if (!path.empty()) fs::remove(path);
  }
};

void fill_into_copy(const LayerFile& height, FilledCopy& copy) {
  static int counter = 0;
  copy.path = fs::temp_directory_path() /
              fmt::format("terraweave-export-fill-{}-{}.tif", ::getpid(), counter++);
  GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
  CPLStringList options;
  options.SetNameValue("TILED", "YES");
  options.SetNameValue("BIGTIFF", "IF_SAFER");
  DatasetPtr out(gtiff->CreateCopy(copy.path.c_str(), height.ds.get(), false, options.List(),
                                   nullptr, nullptr));
  if (!out) fail("cannot copy the height layer for filling: {}", CPLGetLastErrorMsg());
  GDALRasterBand* band = out->GetRasterBand(1);
  int declared = 0;
  band->GetNoDataValue(&declared);
  if (!declared) band->SetNoDataValue(std::nan(""));  // NaN is nodata, as fill_nodata reads it
  const double distance = double(std::max(height.grid.width, height.grid.height));
  if (GDALFillNodata(band, nullptr, distance, 0, 0, nullptr, nullptr, nullptr) != CE_None)
    fail("cannot fill nodata: {}", CPLGetLastErrorMsg());
}

struct TileLayout {
  int size = 0;        // samples per tile side
  int nx = 0, ny = 0;  // tiles
  // Every tile's vertices: nx (size - 1) + 1 by ny (size - 1) + 1, one spacing on both axes,
  // the world's a window of them at the engine's origin corner, the rest padding.
  detail::EngineVertices vertices;
  Window tile(int i, int j) const { return {i * (size - 1), j * (size - 1), size, size}; }
};

int tiles_over(int vertices, int size) {
  return std::max(1, (vertices - 1 + size - 2) / (size - 1));
}

TileLayout tile_layout(const GridSpec& grid, int size, detail::OriginCorner corner) {
  TileLayout l;
  l.size = size;
  const int kx = tiles_over(grid.width, size), ky = tiles_over(grid.height, size);
  const double spacing = detail::fitting_spacing(grid, kx * (size - 1) + 1, ky * (size - 1) + 1);
  // The axis that does not set the spacing may need fewer tiles at it.
  l.nx = tiles_over(detail::vertices_over((grid.width - 1) * grid.pixel_width, spacing), size);
  l.ny = tiles_over(detail::vertices_over((grid.height - 1) * grid.pixel_height, spacing), size);
  l.vertices =
      detail::engine_vertices(grid, l.nx * (size - 1) + 1, l.ny * (size - 1) + 1, spacing, corner);
  return l;
}

// `tile` (a window of v's samples): its part of the world read through `read` (a window of
// v.data), the padding carrying the nearest world sample on as pad_to_engine does (the same
// samples as the whole heightmap's window).
template <class Read>
Raster<float> tile_samples(const detail::EngineVertices& v, const Window& tile, const Read& read) {
  const Window& w = v.world;
  const auto clamp_col = [&](int c) { return std::clamp(c - w.col0, 0, w.width - 1); };
  const auto clamp_row = [&](int r) { return std::clamp(r - w.row0, 0, w.height - 1); };
  const int c0 = clamp_col(tile.col0), c1 = clamp_col(tile.col0 + tile.width - 1);
  const int r0 = clamp_row(tile.row0), r1 = clamp_row(tile.row0 + tile.height - 1);
  const Raster<float> data = read(Window{c0, r0, c1 - c0 + 1, r1 - r0 + 1});
  if (data.width == tile.width && data.height == tile.height && tile.col0 - w.col0 == c0 &&
      tile.row0 - w.row0 == r0)
    return data;
  Raster<float> out(tile.width, tile.height);
  for (int r = 0; r < tile.height; ++r)
    for (int c = 0; c < tile.width; ++c)
      out.at(c, r) = data.at(clamp_col(tile.col0 + c) - c0, clamp_row(tile.row0 + r) - r0);
  return out;
}

// The layer files read by windows, never whole. Nodata is filled the first time a read meets
// it (no nodata_height given): a copy of the height file, filled over the whole world as the
// untiled export fills, read from then on. The filling only changes nodata cells, so windows
// read before it stay valid.
class TiledSource {
 public:
  TiledSource(const ExportFiles& files, const EngineExportOptions& options)
      : height_(open_layer_file(files.height)), nodata_height_(options.nodata_height) {
    if (files.splat) {
      splat_ = open_layer_file(*files.splat);
      if (!(splat_->grid == height_.grid))
        fail("{}: its grid differs from {}'s", files.splat->string(), files.height.string());
    }
    if (!files.crs_wkt.empty()) height_.crs_wkt = files.crs_wkt;
  }
  const GridSpec& grid() const { return height_.grid; }
  const std::string& crs_wkt() const { return height_.crs_wkt; }
  const LayerFile* splat() const { return splat_ ? &*splat_ : nullptr; }
  const ExportReads& reads() const { return reads_; }

  // Heights at the cells of `window` of `to` (vertices or texels over the world).
  Raster<float> heights(const GridSpec& to, const Window& window) {
    return resampled(to, window, [this](const Window& w) { return read_heights(w); });
  }
  // Splat band `band` (0-based) at the cells of `window` of `to`; nodata weighs nothing.
  Raster<float> weights(int band, const GridSpec& to, const Window& window) {
    return resampled(to, window, [this, band](const Window& w) {
      Raster<float> r = read(*splat_, band + 1, w);
      for (float& v : r.pixels)
        if (std::isnan(v)) v = 0.0f;
      return r;
    });
  }
  double height_at(Vec2 p) {
    const Vec2 px = grid().world_to_pixel(p);
    const int c0 = std::clamp(int(std::floor(px.x)) - 2, 0, std::max(0, grid().width - 4));
    const int r0 = std::clamp(int(std::floor(px.y)) - 2, 0, std::max(0, grid().height - 4));
    const Window w{c0, r0, std::min(4, grid().width), std::min(4, grid().height)};
    GridSpec sub = grid();
    sub.width = w.width;
    sub.height = w.height;
    sub.origin_x += c0 * sub.pixel_width;
    sub.origin_y -= r0 * sub.pixel_height;
    return sample_height_bilinear(read_heights(w), sub, p);
  }

 private:
  Raster<float> read(const LayerFile& f, int band, const Window& w) {
    ++reads_.windows;
    reads_.largest_cells = std::max(reads_.largest_cells, std::int64_t(w.width) * w.height);
    return read_window(f, band, w);
  }
  // `w` of the height file, nodata-free.
  Raster<float> read_heights(const Window& w) {
    Raster<float> r = read(height_, 1, w);
    if (std::none_of(r.pixels.begin(), r.pixels.end(), [](float v) { return std::isnan(v); }))
      return r;
    if (nodata_height_) {
      for (float& v : r.pixels)
        if (std::isnan(v)) v = float(*nodata_height_);
      return r;
    }
    if (!filled_.path.empty()) fail("{}: nodata left after filling", height_.ds->GetDescription());
    std::string crs = height_.crs_wkt;
    fill_into_copy(height_, filled_);
    height_ = open_layer_file(filled_.path);
    height_.crs_wkt = std::move(crs);
    return read_heights(w);
  }
  template <class Read>
  Raster<float> resampled(const GridSpec& to, const Window& window, const Read& read) {
    const GridSpec& from = height_.grid;
    if (to == from || to == detail::vertex_grid(from, from.width, from.height))
      return read(window);  // the vertices are the cell centres
    const Window source = resample_source_window(from, to, window);
    return resample_heights_window(read(source), source, from, to, window, Resampling::bilinear);
  }

  LayerFile height_;
  std::optional<LayerFile> splat_;
  std::optional<double> nodata_height_;
  FilledCopy filled_;
  ExportReads reads_;
};

// What one engine writes per tile, and its sidecar.
struct TileWriter {
  std::string suffix(int i, int j) const {
    return engine == Engine::unreal ? fmt::format("_x{}_y{}", i, j)
                                    : fmt::format("_{}_{}", i, layout.ny - 1 - j);
  }
  Engine engine;
  TileLayout layout;
};

}  // namespace

EngineExportResult export_tiles_for_engine(const ExportFiles& files,
                                           const std::vector<ExportCurve>& curves,
                                           const EngineExportOptions& options,
                                           const std::filesystem::path& dir, OutputStager& stager) {
  const std::string engine = to_string(options.engine);
  const int size = options.tile_size.value_or(0);
  const std::vector<int>& sizes = engine_heightmap_sizes(options.engine);
  if (options.engine == Engine::godot || options.engine == Engine::terrain3d)
    fail("export {}: Godot takes one heightmap, not tiles", engine);
  if (options.layers)
    fail("export {}: layers are written with one heightmap (tile_size 0), not with tiles", engine);
  if (!std::binary_search(sizes.begin(), sizes.end(), size))
    fail("export {}: tile size {} is not one the engine takes ({} ... {})", engine, size,
         sizes.front(), sizes.back());
  // A bounded block cache: GDAL's default would keep every block read (up to 5 % of RAM).
  const detail::ScopedGdalCacheMax cache(detail::kExportGdalCacheBytes);
  TiledSource source(files, options);
  const GridSpec& grid = source.grid();
  const bool unreal = options.engine == Engine::unreal;
  const detail::OriginCorner corner =
      unreal ? detail::OriginCorner::north_west : detail::OriginCorner::south_west;
  const TileLayout layout = tile_layout(grid, size, corner);
  const TileWriter names{options.engine, layout};
  const detail::EngineVertices& vertices = layout.vertices;
  const auto heights_of = [&](const Window& tile) {
    return tile_samples(vertices, tile,
                        [&](const Window& w) { return source.heights(vertices.data, w); });
  };

  double min = std::numeric_limits<double>::infinity(), max = -min;
  for (int j = 0; j < layout.ny; ++j)
    for (int i = 0; i < layout.nx; ++i) {
      const Raster<float> h = heights_of(layout.tile(i, j));
      const auto [lo, hi] = std::minmax_element(h.pixels.begin(), h.pixels.end());
      min = std::min(min, double(*lo));
      max = std::max(max, double(*hi));
    }

  const int alpha = size - 1;  // Unity's control maps: 2^n texels per tile
  const detail::EngineVertices texels =
      detail::engine_texels(grid, layout.nx * alpha, layout.ny * alpha, vertices.spacing, corner);
  const std::vector<std::string> materials = source.splat()
                                                 ? detail::material_names(source.splat()->channels)
                                                 : std::vector<std::string>{};
  EngineExportResult result;
  // The tiles' size decides the samples: a --size / size: given too changed nothing, silently
  // (issue #24 item 2); it is said.
  if (options.size != 0)
    result.warnings.push_back(fmt::format(
        "export {}: size {} is unused with tiles of {} (give tile_size 0, --tile-size 0, for one "
        "heightmap of that size)",
        engine, options.size, size));
  nlohmann::json tiles = nlohmann::json::array();
  // The writing pass: the range pass before it reads heights alone, a fraction of the time.
  Progress progress("export " + engine, std::int64_t(layout.nx) * layout.ny, "tile");
  for (int j = 0; j < layout.ny; ++j)
    for (int i = 0; i < layout.nx; ++i) {
      const std::string suffix = names.suffix(i, j);
      const Window window = layout.tile(i, j);
      const detail::Heightmap16 map = detail::quantize_heights(heights_of(window), min, max);
      const std::string height_file = "heightmap" + suffix + (unreal ? ".png" : ".raw");
      result.files.push_back(dir / height_file);
      if (unreal)
        detail::write_png16(stager.stage(result.files.back()), map);
      else
        detail::write_raw16(stager.stage(result.files.back()), map, true);
      nlohmann::json weight_files = nlohmann::json::array();
      if (source.splat()) {
        const detail::EngineVertices& on = unreal ? vertices : texels;
        const Window w = unreal ? window : Window{i * alpha, j * alpha, alpha, alpha};
        std::vector<Raster<float>> bands;
        for (std::size_t m = 0; m < materials.size(); ++m)
          bands.push_back(tile_samples(on, w, [&](const Window& data_window) {
            return source.weights(int(m), on.data, data_window);
          }));
        const auto weights = detail::quantize_weights(bands);
        const std::vector<std::uint8_t> zero(std::size_t(w.width) * w.height, 0);
        const std::size_t per_file = unreal ? 1 : 4;
        for (std::size_t first = 0; first < weights.size(); first += per_file) {
          const std::string file = unreal ? "weightmap_" + materials[first] + suffix + ".png"
                                          : fmt::format("splatmap_{}{}.png", first / 4, suffix);
          std::vector<const std::uint8_t*> channels;
          for (std::size_t m = first; m < first + per_file; ++m)
            channels.push_back(m < weights.size() ? weights[m].data() : zero.data());
          result.files.push_back(dir / file);
          detail::write_png(stager.stage(result.files.back()), w.width, w.height, channels);
          weight_files.push_back(file);
        }
      }
      const double tile_x = i * (size - 1) * vertices.spacing;
      const double tile_z = (layout.ny - 1 - j) * (size - 1) * vertices.spacing;
      tiles.push_back({{"x", i},
                       {unreal ? "y" : "z", unreal ? j : layout.ny - 1 - j},
                       {"heightmap", height_file},
                       {unreal ? "weightmaps" : "splatmaps", weight_files}});
      if (!unreal) tiles.back()["position"] = {tile_x, min, tile_z};
      progress.advance();
    }
  const double vx = vertices.spacing, vz = vertices.spacing;
  const detail::EngineFrame frame = detail::engine_frame(options.engine, grid);
  nlohmann::json sidecar = {{"engine", engine},
                            {"tile_size", size},
                            {"tiles_x", layout.nx},
                            {"tiles_y", layout.ny},
                            {"size", {vertices.width, vertices.height}},
                            {"padding", detail::padding_json(vertices)},
                            {"height_min_m", min},
                            {"height_max_m", max},
                            {"height_step_m", (max - min) / 65535.0},
                            {"world_origin", frame.origin},
                            {"crs_wkt", source.crs_wkt()},
                            {"materials", materials},
                            {"tiles", tiles}};
  if (unreal) {
    const detail::UnrealZ z = detail::unreal_z(min, max);
    sidecar["location_cm"] = {0.0, 0.0, z.location_cm};
    sidecar["scale"] = {vx * 100.0, vz * 100.0, z.scale};
  } else {
    // The untiled unity.json's layer table: material i is channel RGBA[i % 4] of every tile's
    // splatmap_<i / 4>_<x>_<z>.png.
    nlohmann::json layers = nlohmann::json::array();
    for (std::size_t m = 0; m < materials.size(); ++m)
      layers.push_back({{"material", materials[m]},
                        {"control", fmt::format("splatmap_{}", m / 4)},
                        {"channel", std::string(1, "RGBA"[m % 4])}});
    sidecar["layers"] = layers;
    sidecar["heightmap_resolution"] = size;
    sidecar["alphamap_resolution"] = alpha;
    sidecar["depth"] = 16;
    sidecar["byte_order"] = "little-endian (Windows)";
    sidecar["flip_vertically"] = false;
    sidecar["terrain_size"] = {(size - 1) * vx, max - min, (size - 1) * vz};
  }
  result.files.push_back(dir / (engine + ".json"));
  detail::write_json(result.files.back(), sidecar.dump(2) + "\n", stager);
  for (const auto& p : detail::write_splines(
           curves, [&source](Vec2 p) { return source.height_at(p); }, frame, dir, stager))
    result.files.push_back(p);

  result.reads = source.reads();
  result.settings.push_back(fmt::format(
      "{}: {} x {} tiles of {} x {} ({}), heights {:.3f} .. {:.3f} m", engine, layout.nx, layout.ny,
      size, size, (dir / (unreal ? "heightmap_x0_y0.png" : "heightmap_0_0.raw")).string(), min,
      max));
  if (unreal) {
    const detail::UnrealZ z = detail::unreal_z(min, max);
    result.settings.push_back(fmt::format("unreal: Location X 0 Y 0 Z {:.3f}", z.location_cm));
    result.settings.push_back(
        fmt::format("unreal: Scale X {:.4f} Y {:.4f} Z {:.4f}", vx * 100.0, vz * 100.0, z.scale));
  } else {
    result.settings.push_back(
        fmt::format("unity: each terrain Width {:.3f} Length {:.3f} Height {:.3f}; tile (x, z) at "
                    "(x (W), {:.3f}, z (L)); Control Texture Resolution {}",
                    (size - 1) * vx, (size - 1) * vz, max - min, min, alpha));
  }
  return result;
}

}  // namespace tw
