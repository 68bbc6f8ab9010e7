#include "pipeline/detail/job_outputs.hpp"

#include <gdal_priv.h>
#include <gdal_utils.h>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "core/log.hpp"
#include "pipeline/detail/report_json.hpp"
#include "synth/placements_io.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The layers of a tile as they were rendered, read back from its staged files (EXR when
// written, else the GeoTIFF through GDAL).
std::vector<Layer> read_tile_layers(const RenderedTile& tile, bool exr) {
  std::vector<Layer> layers;
  for (const TileFile& f : tile.files) {
    if (f.file.extension() != (exr ? ".exr" : ".tif")) continue;
    const std::string stem = f.file.stem().string();
    Layer& layer = layers.emplace_back();
    layer.name = stem.substr(0, stem.rfind("_x"));
    if (exr) {
      ExrContents contents = read_exr(f.staged);
      layer.channels = std::move(contents.channels);
      layer.bands = std::move(contents.bands);
      continue;
    }
    GDALAllRegister();
    GDALDatasetUniquePtr ds(GDALDataset::Open(f.staged.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) fail("cannot read {}", f.staged.string());
    for (int b = 1; b <= ds->GetRasterCount(); ++b) {
      GDALRasterBand* band = ds->GetRasterBand(b);
      layer.channels.push_back(band->GetDescription());
      Raster<float>& r = layer.bands.emplace_back(ds->GetRasterXSize(), ds->GetRasterYSize());
      if (band->RasterIO(GF_Read, 0, 0, r.width, r.height, r.pixels.data(), r.width, r.height,
                         GDT_Float32, 0, 0) != CE_None)
        fail("cannot read {}", f.staged.string());
    }
  }
  return layers;
}

// The world's layers pasted together from the tiles' cores (for the preview).
LayerSet assemble_world(const WorldPlan& plan, const std::vector<RenderedTile>& tiles, bool exr) {
  LayerSet world;
  world.grid = plan.grid;
  world.crs_wkt = plan.crs_wkt;
  world.nodata = plan.nodata;
  for (const RenderedTile& tile : tiles) {
    for (Layer& layer : read_tile_layers(tile, exr)) {
      Layer* target = nullptr;
      for (Layer& w : world.layers)
        if (w.name == layer.name) target = &w;
      if (!target) {
        target = &world.layers.emplace_back();
        target->name = layer.name;
        target->channels = layer.channels;
        for (std::size_t b = 0; b < layer.bands.size(); ++b)
          target->bands.emplace_back(plan.grid.width, plan.grid.height);
      }
      const Window& core = tile.tile.window;
      const Window& halo = tile.tile.halo_window;
      for (std::size_t b = 0; b < layer.bands.size() && b < target->bands.size(); ++b)
        for (int row = core.row0; row < core.row_end(); ++row)
          for (int col = core.col0; col < core.col_end(); ++col)
            target->bands[b].at(col, row) = layer.bands[b].at(col - halo.col0, row - halo.row0);
    }
  }
  return world;
}

// <out>/<layer>.vrt over the tiles' GeoTIFFs (paths relative to the VRT).
void write_mosaics(const std::vector<RenderedTile>& tiles, const fs::path& out,
                   OutputFolder& transaction) {
  GDALAllRegister();
  std::map<std::string, std::vector<std::string>> sources;  // layer -> staged tile GeoTIFFs
  for (const RenderedTile& tile : tiles)
    for (const TileFile& f : tile.files)
      if (f.file.extension() == ".tif") {
        const std::string stem = f.file.stem().string();
        sources[stem.substr(0, stem.rfind("_x"))].push_back(f.staged.string());
      }
  for (const auto& [layer, files] : sources) {
    const fs::path staged = transaction.stage(out / (layer + ".vrt"));
    // GDAL resolves the sources from the VRT's folder: build it where they are (staged).
    std::vector<const char*> names;
    for (const std::string& f : files) names.push_back(f.c_str());
    int usage_error = 0;
    GDALDatasetH vrt = GDALBuildVRT(staged.c_str(), int(names.size()), nullptr, names.data(),
                                    nullptr, &usage_error);
    if (!vrt || usage_error) fail("cannot write {}", (out / (layer + ".vrt")).string());
    GDALClose(vrt);
  }
}

}  // namespace

std::vector<fs::path> write_tile_files(LayerSet& layers, const TileSpec& tile, const fs::path& dir,
                                       OutputStager& stager, const WriteOptions& options) {
  for (Layer& layer : layers.layers) layer.name = tile_file_stem(layer.name, tile);
  WriteOptions tile_options = options;
  tile_options.preview = false;
  return write_layer_set(layers, dir / "tiles", stager, tile_options);
}

RunReport write_job_outputs(const WorldPlan& plan, const PipelineConfig& config,
                            const std::vector<RenderedTile>& tiles, const fs::path& out,
                            OutputFolder& transaction) {
  RunReport report = plan.report;
  report.forbidden_pixels = 0;
  for (const RenderedTile& t : tiles) report.forbidden_pixels += t.forbidden_pixels;
  if (config.output.geotiff) write_mosaics(tiles, out, transaction);
  if (config.output.preview) {
    const LayerSet world = assemble_world(plan, tiles, config.output.exr);
    std::vector<std::vector<Vec2>> centerlines;
    for (const TerrainFeature& f : plan.terrain_features)
      centerlines.push_back(f.centerline.points);
    write_preview_png(world, transaction.stage(out / "preview.png"), centerlines);
  }
  // placements/<class>_<fid>.json (a multi-part FID adds _<part>), as terraweave run names them.
  std::map<std::string, int> parts;
  for (const PlannedPattern& p : plan.patterns) {
    std::string name = fmt::format("{}_{}", plan.class_names[p.class_index],
                                   plan.lines[p.class_index][p.feature_index].fid);
    if (const int part = parts[name]++; part > 0) name += fmt::format("_{}", part);
    const std::string file = "placements/" + name + ".json";
    Synthesis saved = p.synthesis;
    saved.backend.clear();
    save_placements(saved, plan.exemplars[p.exemplar_index].path,
                    transaction.stage(out / file).string());
    auto& synthesis = report.classes[p.class_index].features[p.feature_index].synthesis;
    if (synthesis) synthesis->placements = file;
  }
  return report;
}

void write_job_report(const RunReport& report, const PipelineConfig& config,
                      const std::vector<RenderedTile>& tiles, const fs::path& out,
                      OutputFolder& transaction) {
  json doc = report_to_json(report, config);
  json list = json::array();
  for (const RenderedTile& t : tiles) {
    json files = json::array();
    for (const TileFile& f : t.files)
      files.push_back(
          {{"file", f.file.generic_string()}, {"bytes", f.bytes}, {"xxh3_128", f.xxh3_128}});
    const Window& w = t.tile.window;
    const Window& h = t.tile.halo_window;
    list.push_back({{"index", t.tile.index},
                    {"x", t.tile.ix},
                    {"y", t.tile.iy},
                    {"window", {w.col0, w.row0, w.width, w.height}},
                    {"halo_window", {h.col0, h.row0, h.width, h.height}},
                    {"files", files},
                    {"seconds", t.seconds}});
  }
  doc["tiles"] = {
      {"size", config.output.tiles.size}, {"overlap", config.output.tiles.overlap}, {"list", list}};
  const fs::path path = transaction.stage(out / "report.json");
  std::ofstream file(path);
  file << doc.dump(2) << '\n';
  file.close();
  if (!file) fail("cannot write {}", path.string());
}

}  // namespace tw::detail
