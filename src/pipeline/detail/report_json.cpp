#include "pipeline/detail/report_json.hpp"

#include <fmt/format.h>
#include <gdal.h>

#include "pipeline/version.hpp"

namespace tw::detail {

nlohmann::json report_to_json(const RunReport& report, const PipelineConfig& config) {
  using nlohmann::json;
  json stages = json::array();
  for (const StageTiming& s : report.stages)
    stages.push_back({{"stage", s.stage}, {"seconds", s.seconds}});
  json classes = json::array();
  for (const FeatureClassReport& c : report.classes) {
    json features = json::array();
    double total_length = 0.0;
    for (const FeatureReport& f : c.features) {
      json feature = {{"fid", f.fid},
                      {"length_m", f.length_m},
                      {"width_m", f.width_m},
                      {"pieces", f.pieces},
                      {"moved_max_m", f.moved_max_m},
                      {"moved_mean_m", f.moved_mean_m},
                      {"cut_max_m", f.cut_max_m},
                      {"fill_max_m", f.fill_max_m}};
      if (f.structure != Structure::ground) {
        feature["structure"] = std::string(to_string(f.structure));
        feature["layer"] = f.layer;
        if (f.deck_m) feature["deck_m"] = {(*f.deck_m)[0], (*f.deck_m)[1]};
      }
      if (f.synthesis) {
        const FeatureSynthesisReport& s = *f.synthesis;
        feature["synthesis"] = {{"exemplar", s.exemplar},
                                {"seed", s.seed},
                                {"backend", s.backend},
                                {"mean_valid_positions", s.mean_valid_positions},
                                {"omega", s.omega},
                                {"mean_seam_cost", s.mean_seam_cost},
                                {"mean_seam_cost_stitched", s.mean_seam_cost_stitched},
                                {"empty_pieces", s.empty_pieces},
                                {"violations", s.violations},
                                {"canvas", {s.canvas_width, s.canvas_height}},
                                {"placements", s.placements},
                                {"seconds",
                                 {{"avoidance", s.avoidance_seconds},
                                  {"synthesis", s.synthesis_seconds},
                                  {"render", s.render_seconds}}}};
      }
      features.push_back(feature);
      total_length += f.length_m;
    }
    classes.push_back({{"name", c.name},
                       {"kind", std::string(to_string(c.kind))},
                       {"source", c.source},
                       {"delta_m", c.delta_m},
                       {"length_m", total_length},
                       {"ingest_seconds", c.ingest_seconds},
                       {"features", features}});
  }
  json warnings = json::array();
  for (const Warning& w : report.warnings) {
    json entry = {{"code", w.code}, {"subject", w.subject}, {"message", w.message}};
    if (w.fid) entry["fid"] = *w.fid;
    warnings.push_back(std::move(entry));
  }
  json tiles = json::array();
  const auto window_json = [](const Window& w) { return json{w.col0, w.row0, w.width, w.height}; };
  for (const TileReport& t : report.tiles.tiles) {
    tiles.push_back({{"index", t.index},
                     {"ix", t.ix},
                     {"iy", t.iy},
                     {"window", window_json(t.window)},
                     {"halo_window", window_json(t.halo_window)},
                     {"seconds", t.seconds},
                     {"xxh64", fmt::format("{:016x}", t.xxh64)}});
  }
  const GridSpec& g = report.grid;
  return {
      {"tiles",
       {{"size", report.tiles.size},
        {"overlap", report.tiles.overlap},
        {"count", report.tiles.tiles.size()},
        {"tiles", tiles}}},
      {"terraweave", kTerraweaveVersion},
      {"versions", version_line()},
      {"pipeline", config.file.string()},
      {"seed", report.seed},
      {"backend", config.backend},
      {"heightfield", report.heightfield},
      {"grid",
       {{"width", g.width},
        {"height", g.height},
        {"origin", {g.origin_x, g.origin_y}},
        {"pixel_size", {g.pixel_width, g.pixel_height}},
        {"crs_wkt", report.crs_wkt}}},
      {"stages", stages},
      {"total_seconds", report.total_seconds},
      {"forbidden_pixels", report.forbidden_pixels},
      {"synthesis_resolution", config.synthesis_resolution},
      {"synthesis_order", config.synthesis_order},
      {"pattern_violations", report.pattern_violations},
      {"classes", classes},
      {"warning_count", report.warnings.size()},
      {"warnings", warnings},
  };
}

}  // namespace tw::detail
