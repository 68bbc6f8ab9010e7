#pragma once
// The layer rasters of a finished run folder, as the commands that read a run (`export`,
// `view`) find them: an untiled run writes `<layer>.tif` and/or `<layer>.exr`
// (output.formats), a tiled one (output.tiles, docs/tiles.md) the VRT mosaic `<layer>.vrt` of
// its GeoTIFF tiles, which GDAL reads as one raster. Open them with LayerRaster
// (layers/layer_raster.hpp), which reads an EXR too.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/file_hash.hpp"

namespace tw {

// report.json's `format` and `version.schema`: the schema changes its number when a key
// changes meaning or place (2: manifest keys, timings under `timings`).
inline constexpr const char* kReportFormat = "terraweave-report";
inline constexpr int kReportSchemaVersion = 2;

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

// A file that report.json's `outputs` names: as the run recorded it and as it is now.
struct RunFile {
  std::string name;  // relative to the run folder, e.g. height.tif, tiles/height_x0_y1.tif
  FileDigest recorded;
  std::optional<FileDigest> now;  // absent: the file is gone
  bool matches() const {
    return now && now->bytes == recorded.bytes && now->xxh3_128 == recorded.xxh3_128;
  }
};

// Every file report.json's `outputs` names, hashed now (XXH3-128, streamed: core/file_hash).
// Throws tw::Error naming report.json when it is missing, not JSON, or names a path outside
// the run.
std::vector<RunFile> hash_run_files(const std::filesystem::path& run);

// Checks the run's files against report.json before `command` (diff, export, view) reads them
// (issue #24: flipped bytes in a run's height.tif gave heights of 2.25e35 m). Throws tw::Error
// naming the first file that is gone or changed, and what to do: run again, or `command
// --no-verify` to read the files as they are.
void verify_run_files(const std::filesystem::path& run, std::string_view command);

}  // namespace tw
