#include "pipeline/detail/job_outputs.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/vrt.hpp"
#include "pipeline/detail/report_json.hpp"
#include "pipeline/detail/tile_stats.hpp"

namespace tw::detail {

namespace fs = std::filesystem;
using nlohmann::json;

std::vector<fs::path> write_tile_files(LayerSet& layers, const TileSpec& tile, const fs::path& dir,
                                       OutputStager& stager, const WriteOptions& options) {
  // The files terraweave run writes for a tile (pipeline/run.cpp), named by the tile.
  for (Layer& layer : layers.layers) layer.name = tile_file_stem(layer.name, tile);
  WriteOptions tile_options = options;
  tile_options.preview = false;
  return write_layer_set(layers, dir / "tiles", stager, tile_options);
}

std::map<std::string, std::string> method_tile_facts(const WorldPlan& plan,
                                                     const Raster<float>& height,
                                                     const TileSpec& tile) {
  std::map<std::string, std::string> facts;
  for (const MethodPlan& entry : plan.methods)
    if (const std::string key = entry.method->tile_fact_key(); !key.empty())
      facts[key] = entry.method->tile_fact(plan, entry, height, tile.halo_window, tile.window);
  return facts;
}

std::map<std::string, std::string> tile_facts(const WorldPlan& plan, const LayerSet& layers,
                                              const TileSpec& tile) {
  const Raster<float>& height = find_layer(layers, "height")->bands[0];
  std::map<std::string, std::string> facts = method_tile_facts(plan, height, tile);
  facts["forbidden_pixels"] = std::to_string(forbidden_in(layers, tile.halo_window, tile.window));
  facts["xxh64"] = std::to_string(layer_bytes_hash(layers));
  facts["input_height"] =
      range_fact(core_range(read_height_window(plan.heights, plan.grid, tile.halo_window),
                            tile.halo_window, tile.window));
  facts["output_height"] = range_fact(core_range(height, tile.halo_window, tile.window));
  return facts;
}

void add_method_facts(const WorldPlan& plan, const std::map<std::string, std::string>& facts,
                      const std::string& where, MethodTileFacts& out) {
  out.resize(plan.methods.size());
  for (std::size_t m = 0; m < plan.methods.size(); ++m)
    if (const std::string key = plan.methods[m].method->tile_fact_key(); !key.empty())
      out[m].push_back({where, facts.at(key)});
}

void write_method_outputs(const WorldPlan& plan, MethodTileFacts facts, const fs::path& out,
                          OutputFolder& transaction, RunReport& report, StageClock* clock) {
  facts.resize(plan.methods.size());
  for (std::size_t m = 0; m < plan.methods.size(); ++m) {
    const MethodPlan& entry = plan.methods[m];
    const std::string stage = entry.method->outputs_stage(plan, entry);
    if (stage.empty()) continue;
    if (clock) clock->start(stage);
    MethodOutputs outputs{out, transaction, report, std::move(facts[m])};
    entry.method->write_outputs(plan, entry, outputs);
    if (clock) clock->stop();
  }
}

RunReport write_job_outputs(const WorldPlan& plan, const std::vector<RenderedTile>& tiles,
                            const fs::path& out, OutputFolder& transaction) {
  RunReport report = plan.report;
  report.forbidden_pixels = 0;
  report.tiles.size = plan.tile_size;
  report.tiles.overlap = plan.tile_overlap;
  std::map<std::string, std::vector<fs::path>> tifs;  // per layer, staged, for the mosaics
  for (const RenderedTile& t : tiles) {
    report.forbidden_pixels += t.forbidden_pixels;
    report.tiles.tiles.push_back({t.tile.index, t.tile.ix, t.tile.iy, t.tile.window,
                                  t.tile.halo_window, t.seconds, t.xxh64, t.cache});
    for (const TileFile& f : t.files) {
      if (f.file.extension() != ".tif") continue;
      const std::string stem = f.file.stem().string();
      tifs[stem.substr(0, stem.rfind("_x"))].push_back(f.staged);
    }
  }
  // As terraweave run writes a tiled world: the mosaics, no preview.
  for (const auto& [layer, sources] : tifs)
    write_vrt_mosaic(transaction.stage(out / (layer + ".vrt")), sources);
  MethodTileFacts facts;
  for (const RenderedTile& t : tiles)
    add_method_facts(plan, t.method_facts, fmt::format("tile {}", t.tile.index), facts);
  write_method_outputs(plan, std::move(facts), out, transaction, report, nullptr);
  return report;
}

void write_job_report(const WorldPlan& plan, const RunReport& report, const PipelineConfig& config,
                      const fs::path& out, OutputFolder& transaction) {
  const fs::path path = transaction.stage(out / "report.json");
  std::ofstream file(path);
  file << report_to_json(report, config, methods_in(plan)).dump(2) << '\n';
  file.close();
  if (!file) fail("cannot write {}", path.string());
}

}  // namespace tw::detail
