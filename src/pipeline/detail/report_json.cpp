#include "pipeline/detail/report_json.hpp"

#include <fmt/format.h>
#include <gdal.h>
#include <ogr_spatialref.h>

#include "pipeline/synthesis_method.hpp"
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
  for (const FeatureClassReport& c : report.classes)
    classes.push_back({{"name", c.name}, {"ingest_seconds", c.ingest_seconds}});
  json tiles = json::array();
  for (const TileReport& t : report.tiles.tiles)
    tiles.push_back({{"index", t.index}, {"seconds", t.seconds}});
  return {{"started_utc", report.started_utc},
          {"total_seconds", report.total_seconds},
          {"stages", stages},
          {"classes", classes},
          {"tiles", tiles}};
}

}  // namespace

nlohmann::json report_to_json(const RunReport& report, const PipelineConfig& config,
                              const std::vector<const SynthesisMethod*>& methods) {
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
      features.push_back(feature);
      total_length += f.length_m;
    }
    json entry = {{"name", c.name},           {"kind", std::string(to_string(c.kind))},
                  {"source", c.source},       {"delta_m", c.delta_m},
                  {"length_m", total_length}, {"features", features}};
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
      {"synthesis_order", synthesis_order(config)},
      {"classes", classes},
      {"warning_count", report.warnings.size()},
      {"warnings", warnings},
      {"timings", timings_json(report)},
  };
  // The methods' parts in their places (their classes, features and keys; another method's
  // own object under `methods.<name>`), written by each method (SynthesisMethod::report_json).
  for (const SynthesisMethod* method : methods) method->report_json(report, config, j);
  return j;
}

}  // namespace tw::detail
