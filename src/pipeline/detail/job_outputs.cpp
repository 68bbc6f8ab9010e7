#include "pipeline/detail/job_outputs.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "layers/vrt.hpp"
#include "pipeline/detail/area_method.hpp"
#include "pipeline/detail/area_output.hpp"
#include "pipeline/detail/grow_region.hpp"
#include "pipeline/detail/grown_method.hpp"
#include "pipeline/detail/pattern_method.hpp"
#include "pipeline/detail/report_json.hpp"
#include "synth/placements_io.hpp"

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

void write_placements(const WorldPlan& plan, const fs::path& out, OutputFolder& transaction,
                      RunReport& report) {
  // placements/<class>_<fid>.json (a multi-part FID adds _<part>). The backend field is left
  // out so that every backend writes the same bytes.
  const PatternsPlan* patterns = patterns_plan(plan);
  if (!patterns) return;
  std::map<std::string, int> parts;
  for (const PlannedPattern& p : patterns->patterns) {
    std::string name = fmt::format("{}_{}", plan.class_names[p.class_index],
                                   plan.lines[p.class_index][p.feature_index].fid);
    if (const int part = parts[name]++; part > 0) name += fmt::format("_{}", part);
    const std::string file = "placements/" + name + ".json";
    Synthesis saved = p.synthesis;
    saved.backend.clear();
    save_placements(saved, patterns->exemplars[p.exemplar_index].path,
                    transaction.stage(out / file).string());
    auto& synthesis = report.classes[p.class_index].features[p.feature_index].synthesis;
    if (synthesis) synthesis->placements = file;
  }
}

void write_area_outputs(const WorldPlan& plan, const InstanceHeights& heights, const fs::path& out,
                        OutputFolder& transaction) {
  const AreasPlan* areas = areas_plan(plan);
  if (!areas || areas->names.empty()) return;
  std::vector<AreaResult> results;
  for (std::size_t i = 0; i < areas->areas.size(); ++i) {
    const PlannedArea& a = areas->areas[i];
    results.push_back({areas->names.at(a.area_class), a.fid, a.pattern, heights.at(i)});
  }
  write_area_geopackage(transaction.stage(out / "areas.gpkg"), plan.crs_wkt, results);
  write_instances_csv(transaction.stage(out / "instances.csv"), results);
  write_instances_json(transaction.stage(out / "instances.json"), results);
}

void write_ornament_outputs(const WorldPlan& plan, const fs::path& out, OutputFolder& transaction) {
  const GrownPlan* grown = grown_plan(plan);
  if (!grown || grown->classes.empty()) return;
  std::vector<OrnamentLayer> layers;
  for (const GrownClass& g : grown->classes)
    layers.push_back({plan.class_names.at(g.class_index), g.kind, g.height_m, &g.lines, {}});
  write_ornament_geopackage(transaction.stage(out / "ornaments.gpkg"), plan.crs_wkt, layers);
}

RunReport write_job_outputs(const WorldPlan& plan, const PipelineConfig& /*config*/,
                            const std::vector<RenderedTile>& tiles, const fs::path& out,
                            OutputFolder& transaction) {
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
  write_placements(plan, out, transaction, report);
  InstanceHeights heights = unknown_instance_heights(plan);
  for (const RenderedTile& t : tiles)
    add_instance_heights(t.instance_heights, fmt::format("tile {}", t.tile.index), heights);
  write_area_outputs(plan, heights, out, transaction);
  write_ornament_outputs(plan, out, transaction);
  return report;
}

void write_job_report(const RunReport& report, const PipelineConfig& config, const fs::path& out,
                      OutputFolder& transaction) {
  const fs::path path = transaction.stage(out / "report.json");
  std::ofstream file(path);
  file << report_to_json(report, config).dump(2) << '\n';
  file.close();
  if (!file) fail("cannot write {}", path.string());
}

}  // namespace tw::detail
