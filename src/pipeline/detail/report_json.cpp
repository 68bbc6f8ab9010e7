#include "pipeline/detail/report_json.hpp"

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include "pipeline/version.hpp"

namespace tw::detail {

namespace {

using nlohmann::json;

// "EPSG:32632" when the CRS carries an authority code (a UTM zone, EPSG:2169...); else null.
json crs_code(const std::string& wkt) {
  OGRSpatialReference srs;
  if (wkt.empty() || srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return nullptr;
  const char* name = srs.GetAuthorityName(nullptr);
  const char* code = srs.GetAuthorityCode(nullptr);
  if (name == nullptr || code == nullptr) return nullptr;
  return fmt::format("{}:{}", name, code);
}

json files_json(const std::vector<FileRecord>& files) {
  json list = json::array();
  for (const FileRecord& f : files) {
    json entry = {{"path", f.path}, {"bytes", f.bytes}, {"xxh3_128", f.xxh3_128}};
    if (f.role != f.path) entry["role"] = f.role;
    if (f.xxh3_128.empty()) entry["xxh3_128"] = nullptr;  // a URL, not read here
    list.push_back(std::move(entry));
  }
  return list;
}

json range_json(const HeightRange& range) {
  if (!range) return nullptr;
  return {(*range)[0], (*range)[1]};
}

json overrides_json(const PipelineConfig& config) {
  json list = json::array();
  for (const Override& o : config.overrides) list.push_back(o.key_path + "=" + o.value);
  return list;
}

// Everything that changes from one run of the same inputs to the next, in one place, so that
// two reports minus `timings` compare equal (terraweave diff does that).
json timings_json(const RunReport& report) {
  json stages = json::array();
  for (const StageTiming& s : report.stages)
    stages.push_back({{"stage", s.stage}, {"seconds", s.seconds}});
  json classes = json::array();
  json synthesis = json::array();
  for (const FeatureClassReport& c : report.classes) {
    classes.push_back({{"name", c.name}, {"ingest_seconds", c.ingest_seconds}});
    for (const FeatureReport& f : c.features) {
      if (!f.synthesis) continue;
      synthesis.push_back({{"class", c.name},
                           {"fid", f.fid},
                           {"avoidance", f.synthesis->avoidance_seconds},
                           {"synthesis", f.synthesis->synthesis_seconds},
                           {"render", f.synthesis->render_seconds}});
    }
  }
  json tiles = json::array();
  for (const TileReport& t : report.tiles.tiles)
    tiles.push_back({{"index", t.index}, {"seconds", t.seconds}});
  return {{"started_utc", report.started_utc},
          {"total_seconds", report.total_seconds},
          {"stages", stages},
          {"classes", classes},
          {"synthesis", synthesis},
          {"tiles", tiles}};
}

// `kind: area` classes: per polygon, what was placed and what was left out, and why.
nlohmann::json areas_json(const RunReport& report) {
  using nlohmann::json;
  json areas = json::array();
  for (const AreaClassReport& a : report.areas) {
    json features = json::array();
    int shapes = 0;
    std::int64_t touched = 0;
    for (const AreaFeatureReport& f : a.features) {
      features.push_back(
          {{"fid", f.fid},
           {"area_m2", f.area_m2},
           {"lead_bearing_deg", f.lead_bearing_deg},
           {"seed", f.seed},
           {"shapes", f.shapes},
           {"strokes", f.strokes},
           {"left_out",
            {{"outside", f.outside}, {"forbidden", f.forbidden}, {"overlapping", f.overlapping}}},
           {"forbidden_touched", f.forbidden_touched},
           {"on_nodata", f.on_nodata},
           {"canvas_cells", f.canvas_cells}});
      shapes += f.shapes;
      touched += f.forbidden_touched;
    }
    areas.push_back({{"name", a.name},
                     {"source", a.source},
                     {"sketch", a.sketch},
                     {"lead", a.lead},
                     {"shapes", shapes},
                     {"forbidden_touched", touched},
                     {"features", features}});
  }
  return areas;
}

}  // namespace

nlohmann::json report_to_json(const RunReport& report, const PipelineConfig& config) {
  using nlohmann::json;
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
                      {"fill_max_m", f.fill_max_m},
                      {"grade_max", f.grade_max}};
      if (f.structure != Structure::ground) {
        feature["structure"] = std::string(to_string(f.structure));
        feature["layer"] = f.layer;
        if (f.deck_m) feature["deck_m"] = {(*f.deck_m)[0], (*f.deck_m)[1]};
      }
      if (f.synthesis) {
        const FeatureSynthesisReport& s = *f.synthesis;
        feature["synthesis"] = {
            {"exemplar", s.exemplar},
            {"seed", s.seed},
            {"backend", s.backend},
            {"mean_valid_positions", s.mean_valid_positions},
            {"omega", s.omega},
            {"mean_seam_cost", s.mean_seam_cost},
            {"mean_seam_cost_stitched", s.mean_seam_cost_stitched},
            {"objective", s.objective},
            {"min_coverage", s.min_coverage},
            {"min_coverage_from", s.min_coverage_from_exemplar ? "exemplar" : "pipeline"},
            {"coverage_ratio", s.coverage_ratio},
            {"mean_coverage", s.mean_coverage},
            {"natural_coverage", s.natural_coverage},
            {"parametric_seam_cost", s.parametric_seam_cost},
            {"width_m", s.width_m},
            {"width_from", s.width_from},
            {"delta_m", s.delta_m},
            {"delta_from", s.delta_from},
            {"empty_pieces", s.empty_pieces},
            {"violations", s.violations},
            {"canvas", {s.canvas_width, s.canvas_height}},
            {"placements", s.placements}};
        if (!s.mix_exemplars.empty()) {  // choose: mix
          feature["synthesis"]["mix"] = {{"exemplars", s.mix_exemplars},
                                         {"pieces_per_exemplar", s.pieces_per_exemplar},
                                         {"switches", s.exemplar_switches},
                                         {"switch_cost", s.switch_cost}};
        }
      }
      if (f.cache) {
        feature["cache"] = {{"status", f.cache->reused ? "reused" : "rebuilt"},
                            {"why", f.cache->why},
                            {"key", f.cache->key}};
      }
      features.push_back(feature);
      total_length += f.length_m;
    }
    json entry = {{"name", c.name},           {"kind", std::string(to_string(c.kind))},
                  {"source", c.source},       {"delta_m", c.delta_m},
                  {"length_m", total_length}, {"features", features}};
    if (c.grow) {
      const GrowthReport& g = *c.grow;
      entry["grown_kind"] = g.kind;  // `kind` stays the terrain profile's
      entry["grow"] = {{"element", g.element},
                       {"ornaments", g.ornaments},
                       {"elements", g.elements},
                       {"lines", g.lines},
                       {"rejected",
                        {{"crossing", g.rejected_crossing},
                         {"forbidden", g.rejected_forbidden},
                         {"untraceable", g.rejected_untraceable},
                         {"footprint", g.rejected_footprint}}},
                       {"crossings",
                        {{"grown", g.crossings.grown},
                         {"feature", g.crossings.feature},
                         {"forbidden", g.crossings.forbidden}}},
                       {"coverage", g.coverage},
                       {"coverage_radius_m", g.coverage_radius_m},
                       {"mesh", {g.mesh_width, g.mesh_height}},
                       {"short_lines", g.short_lines},
                       {"layer", "ornaments.gpkg:" + c.name}};
      if (g.synthesis)
        entry["grow"]["synthesis"] = {{"dressed", g.synthesis->dressed},
                                      {"no_room", g.synthesis->no_room}};
    }
    if (c.network) {
      const NetworkClassReport& n = *c.network;
      entry["network"] = {{"exemplar", n.exemplar},
                          {"exemplar_edges", n.exemplar_edges},
                          {"lines", n.lines},
                          {"kept", n.kept},
                          {"placed", n.placed},
                          {"snapped", n.snapped},
                          {"t_junctions", n.t_junctions},
                          {"boundary_ends", n.boundary_ends},
                          {"pruned", n.pruned},
                          {"rejected",
                           {{"crossing", n.rejected_crossing},
                            {"region", n.rejected_region},
                            {"forbidden", n.rejected_forbidden}}}};
    }
    classes.push_back(std::move(entry));
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
    json tile = {{"index", t.index},
                 {"ix", t.ix},
                 {"iy", t.iy},
                 {"window", window_json(t.window)},
                 {"halo_window", window_json(t.halo_window)},
                 {"xxh64", fmt::format("{:016x}", t.xxh64)}};
    if (t.cache) {
      tile["cache"] = {{"status", t.cache->reused ? "reused" : "rebuilt"},
                       {"why", t.cache->why},
                       {"key", t.cache->key}};
    }
    tiles.push_back(std::move(tile));
  }
  const GridSpec& g = report.grid;
  json j = {
      {"format", kReportFormat},
      {"version", {{"schema", kReportSchemaVersion}, {"terraweave", kTerraweaveVersion}}},
      {"versions", library_versions()},
      {"tiles",
       {{"size", report.tiles.size},
        {"overlap", report.tiles.overlap},
        {"count", report.tiles.tiles.size()},
        {"tiles", tiles}}},
      {"pipeline", config.file.string()},
      {"config", json::parse(config.resolved_json.empty() ? "{}" : config.resolved_json)},
      {"overrides", overrides_json(config)},
      {"inputs", files_json(report.inputs)},
      {"outputs", files_json(report.output_files)},
      {"height_range",
       {{"input", range_json(report.input_height)}, {"output", range_json(report.output_height)}}},
      {"seed", report.seed},
      {"backend", config.backend},
      {"heightfield", report.heightfield},
      {"grid",
       {{"width", g.width},
        {"height", g.height},
        {"origin", {g.origin_x, g.origin_y}},
        {"pixel_size", {g.pixel_width, g.pixel_height}},
        {"crs", crs_code(report.crs_wkt)},
        {"crs_wkt", report.crs_wkt}}},
      {"forbidden_pixels", report.forbidden_pixels},
      {"synthesis_resolution", config.synthesis_resolution},
      {"synthesis_order", config.synthesis_order},
      {"pattern_violations", report.pattern_violations},
      {"grown_crossings", report.grown_crossings},
      {"classes", classes},
      {"areas", areas_json(report)},
      {"warning_count", report.warnings.size()},
      {"warnings", warnings},
      {"timings", timings_json(report)},
  };
  // A method's own part, under its name (SynthesisMethod::report); none for the built-in ones.
  for (const MethodReport& m : report.method_reports)
    j["methods"][m.method] = nlohmann::json::parse(m.json);
  return j;
}

}  // namespace tw::detail
