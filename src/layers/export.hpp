#pragma once
// Engine exports (docs/exports.md): a run's height and splat layers and its road and river
// centerlines as files that Unreal, Unity and Godot import as they are. Heights are filled
// where nodata (engines have none), resampled onto the engine's heightmap size (the vertices
// span the outer cell centres), and quantized from min -> 0 to max -> 65535; splat weights
// become 8-bit maps summing to 255.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/atomic_output.hpp"
#include "core/vec2.hpp"
#include "layers/layer_set.hpp"

namespace tw {

enum class Engine { unreal, unity, godot, terrain3d };
enum class GodotHeightFormat { exr, r16 };

struct EngineExportOptions {
  Engine engine = Engine::unreal;
  // Heightmap samples per side (engine_takes_size); 0 = the smallest of the engine's sizes
  // holding the world's cells (per axis for Unreal, the longer side for Unity and Godot, whose
  // heightmaps are square; Terrain3D takes the world's cells as they are).
  int size = 0;
  // Non-destructive layers (docs/exports.md): the height delta (result - input) and the
  // weights of the materials the features painted, to apply over an existing terrain. Needs
  // the input heights (export_for_engine's `input_height`).
  bool layers = false;
  // Height written on nodata cells; absent = from the nearest valid cells (GDALFillNodata,
  // inverse-distance weighted over the nearest valid cell in each direction, no smoothing).
  std::optional<double> nodata_height;
  GodotHeightFormat godot_height = GodotHeightFormat::exr;
  // Tiles (Unreal World Partition, Unity Terrain Tools): samples per tile side, an engine size;
  // neighbours share one edge row and column. 0 = one heightmap; absent = tiles when the run is
  // tiled (export_tile_size), else one heightmap. Godot takes one heightmap.
  std::optional<int> tile_size;
};

// A road, river or ridge centerline (world coordinates of the run's grid), for the splines.
struct ExportCurve {
  std::string feature_class;
  std::string kind;  // road, river, ridge
  std::int64_t fid = 0;
  double width = 0.0;  // metres
  std::vector<Vec2> points;
};

// What an export read of the layer files, one RasterIO per window: the largest window bounds
// what it held of them at once (tiled exports: one tile's source window, whatever the world).
struct ExportReads {
  std::int64_t windows = 0;
  std::int64_t largest_cells = 0;
};

struct EngineExportResult {
  std::vector<std::filesystem::path> files;  // final paths, in writing order
  std::vector<std::string> settings;         // "what to type in", one line each (printed)
  ExportReads reads;                         // tiled exports; zero for layers in memory
  std::vector<std::string> warnings;         // printed as warnings (a size not recommended)
};

Engine parse_engine(std::string_view name);  // unreal|unity|godot|terrain3d, else tw::Error
std::string to_string(Engine engine);

// The heightmap sizes the engine takes: Epic's recommended landscape sizes (127 ... 8129) for
// Unreal; 2^n + 1 (33 ... 4097) for Unity and Godot (HTerrain, Terrain3D).
const std::vector<int>& engine_heightmap_sizes(Engine engine);
// The smallest size >= cells (the largest when none is).
int engine_heightmap_size(Engine engine, int cells);
// Whether `size` is a heightmap size the engine imports: Unreal any from 8 to 8129 (it builds
// whole components, padding the rest: the recommended sizes fill them exactly), Unity and
// Godot their 2^n + 1 sizes; Terrain3D takes no size (the world's cells).
bool engine_takes_size(Engine engine, int size);
// What the engine takes, for messages: "8 ... 8129 (Epic's recommended: 127, 253, ...)".
std::string engine_size_text(Engine engine);

// The tile size an export uses for a run tiled at `run_tile_size` (0: untiled): the option's,
// else for a tiled run the smallest engine size holding one run tile and its shared edge (0 for
// Godot, and for untiled runs).
int export_tile_size(const EngineExportOptions& options, int run_tile_size);

// Writes the export of `set` (layers "height", required, and "splat") and `curves` into `dir`,
// every file staged in `stager`. `input_height` (the heights before the run, on set.grid, NaN
// for nodata) is needed by options.layers. Throws tw::Error naming the problem (no height
// layer, a size the engine does not take, nothing but nodata, layers without input heights).
EngineExportResult export_for_engine(const LayerSet& set, const std::vector<ExportCurve>& curves,
                                     const EngineExportOptions& options,
                                     const std::filesystem::path& dir, OutputStager& stager,
                                     const Raster<float>* input_height = nullptr);

// A run's layers on disk: GeoTIFFs, or the VRT mosaics of a tiled run (docs/tiles.md).
struct ExportFiles {
  std::filesystem::path height;
  std::optional<std::filesystem::path> splat;
  // The run's CRS as its plan holds it; empty: as the files give it. A VRT mosaic and a GeoTIFF
  // of the same CRS export different WKT strings, and the sidecars must not differ by that.
  std::string crs_wkt;
};

// The export of `files` in tiles of options.tile_size samples (> 0; Unreal and Unity), named
// `_x<i>_y<j>` (Unreal: i west to east, j north to south) or `_<i>_<k>` (Unity: k south to
// north), neighbours sharing their edge row and column. The vertices of all tiles form one
// grid over the world, so every tile reads a window of the files through GDAL and memory
// follows one tile; heights use the world's min and max (one Z scale for every tile).
EngineExportResult export_tiles_for_engine(const ExportFiles& files,
                                           const std::vector<ExportCurve>& curves,
                                           const EngineExportOptions& options,
                                           const std::filesystem::path& dir, OutputStager& stager);

// The run's centerlines as GeoJSON (features.geojson: LineStrings with class, kind, fid,
// width), in the CRS of `crs_wkt`, and read back.
void write_curves_geojson(const std::vector<ExportCurve>& curves, const std::string& crs_wkt,
                          const std::filesystem::path& path);
std::vector<ExportCurve> read_curves_geojson(const std::filesystem::path& path);

// A GeoTIFF written by write_geotiff read back as a layer (channels = band descriptions;
// the nodata value, if any, becomes NaN), with its grid and CRS into `set` when it has none.
Layer read_geotiff_layer(const std::filesystem::path& path, const std::string& name, LayerSet& set);

}  // namespace tw
