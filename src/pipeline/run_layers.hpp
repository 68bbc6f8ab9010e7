#pragma once
// The layer rasters of a finished run folder, as the commands that read a run (`export`,
// `view`) find them: an untiled run writes `<layer>.tif` and/or `<layer>.exr`
// (output.formats), a tiled one (output.tiles, docs/tiles.md) the VRT mosaic `<layer>.vrt` of
// its GeoTIFF tiles, which GDAL reads as one raster. Open them with LayerRaster
// (layers/layer_raster.hpp), which reads an EXR too.
#include <filesystem>
#include <optional>
#include <string_view>
#include <vector>

namespace tw {

// True when `run` was run tiled: it holds the height mosaic `height.vrt`.
bool is_tiled_run(const std::filesystem::path& run);

// `run/<layer>.vrt` of a tiled run; `run/<layer>.tif` of an untiled one, else its
// `run/<layer>.exr`; nullopt when the run wrote no such layer (no splat; a tiled run without
// GeoTIFF twins).
std::optional<std::filesystem::path> run_layer_raster(const std::filesystem::path& run,
                                                      std::string_view layer);

// The same, or a tw::Error naming the file the run should have written.
std::filesystem::path required_run_layer_raster(const std::filesystem::path& run,
                                                std::string_view layer);

}  // namespace tw
