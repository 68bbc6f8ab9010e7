#include "pipeline/plan_io.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <system_error>
#include <utility>

#include "core/content_hash.hpp"
#include "core/error.hpp"
#include "core/file_hash.hpp"
#include "core/file_io.hpp"
#include "geo/heightfield_source.hpp"
#include "pipeline/detail/job_files.hpp"
#include "pipeline/detail/plan_fields.hpp"
#include "pipeline/detail/plan_objects.hpp"
#include "pipeline/detail/plan_ribbons.hpp"
#include "pipeline/json_file.hpp"
#include "pipeline/synthesis_method.hpp"
#include "raster/footprint.hpp"
#include "raster/window_index.hpp"

namespace tw {

namespace fs = std::filesystem;
using detail::decode;
using detail::encode;
using nlohmann::json;

namespace {

const json& file_entry(const detail::PlanObjects& objects, const json& files,
                       const std::string& key) {
  if (!files.contains(key)) fail("plan {}: files.{}: missing", objects.dir().string(), key);
  return files[key];
}

// A binary object of plan.json's `files`, checked against its hash and version.
detail::PlanObjects::Binary get_binary(const detail::PlanObjects& objects, const json& files,
                                       const std::string& key) {
  return objects.get_binary(file_entry(objects, files, key), "files." + key);
}

template <class T>
void get_value(const detail::PlanObjects& objects, const json& files, const std::string& key,
               T& value) {
  detail::from_bytes(get_binary(objects, files, key).body(), value,
                     fmt::format("plan {}: {}", objects.dir().string(), key));
}

// The report's timings move out of its object into plan.json, outside the plan's hash: two plans
// of the same inputs are the same plan, with the same object names. The methods' parts are
// stored by their methods (encode_report), their timings taken out by them too.
json take_timings(RunReport& report) {
  json classes = json::array();
  for (FeatureClassReport& c : report.classes)
    classes.push_back({{"ingest", std::exchange(c.ingest_seconds, 0.0)}});
  json timings = {{"stages", encode(report.stages)},
                  {"total", std::exchange(report.total_seconds, 0.0)},
                  {"classes", classes}};
  report.stages.clear();
  return timings;
}

void restore_timings(const json& timings, RunReport& report, const std::string& where) {
  decode(timings.at("stages"), report.stages, where + ": timings.stages");
  report.total_seconds = timings.at("total").get<double>();
  const json& classes = timings.at("classes");
  for (std::size_t c = 0; c < report.classes.size() && c < classes.size(); ++c)
    report.classes[c].ingest_seconds = classes[c].at("ingest").get<double>();
}

// The method of a part of the run's report, among the plan's entries.
const SynthesisMethod& report_part_method(const WorldPlan& plan, const MethodReportPart& part) {
  const MethodPlan* entry = find_method_plan(plan, part.method);
  if (!entry)
    fail("plan: the report has a part of method '{}', which the plan has no entry of", part.method);
  return *entry->method;
}

// The DEM a plan names, refused when its bytes are not the ones planned (hashing streams the
// file in 1 MiB chunks: no memory, about a second per GB). Its warnings were the plan's.
std::shared_ptr<const HeightfieldSource> open_planned_heightfield(const HeightfieldFile& file,
                                                                  const std::string& where) {
  const FileDigest digest = file_digest(file.path);
  if (digest.xxh3_128 != file.xxh3_128 || digest.bytes != file.bytes)
    fail("{}: heights.file {} changed after planning (xxh3_128 {}, planned {}); plan again", where,
         file.path, digest.xxh3_128, file.xxh3_128);
  Warnings planned;
  return open_heightfield(file.path, file.options, planned);
}

json tasks_json(const WorldPlan& plan, const std::string& hash) {
  json tiles = json::array();
  for (const TileSpec& tile : plan.tiles) tiles.push_back(encode(tile));
  return {{"format", kTasksFormat}, {"version", kPlanVersion}, {"plan", hash}, {"tiles", tiles}};
}

}  // namespace

nlohmann::json read_plan_file(const fs::path& path, const char* format) {
  using nlohmann::json;
  const json j = parse_json_file(path, "plan again (terraweave plan PIPELINE --out DIR)");
  if (!j.is_object() || j.value("format", "") != format)
    fail("{}: not a {} file", path.string(), format);
  if (j.value("version", 0) != kPlanVersion)
    fail("{}: version {} (this terraweave reads version {})", path.string(), j.value("version", 0),
         kPlanVersion);
  return j;
}

namespace detail {

StagedPlan stage_plan(const WorldPlan& plan, const fs::path& dir) {
  detail::PlanObjects store(dir);
  json files;
  // Numbers that may be NaN or infinite stay out of the text of plan.json.
  // Binary objects (plan_binary.hpp): read straight into the values, without a JSON document.
  {
    detail::BinaryWriter settings;  // numbers that may be NaN or infinite stay out of plan.json
    settings.write(plan.nodata);
    settings.write(plan.render);
    files["settings"] = store.put_binary(settings.bytes);
  }
  files["lines"] = store.put_binary(detail::to_bytes(plan.lines));
  files["ribbons"] = store.put_binary(detail::ribbons_to_bytes(plan.ribbons));
  files["junction_discs"] = store.put_binary(detail::to_bytes(plan.junction_discs));
  files["synthesis_junction_discs"] =
      store.put_binary(detail::to_bytes(plan.synthesis_junction_discs));
  files["synthesis_junctions"] = store.put_binary(detail::to_bytes(plan.synthesis_junctions));
  files["existing"] = store.put_binary(detail::to_bytes(plan.existing));
  files["terrain_features"] = store.put_binary(detail::to_bytes(plan.terrain_features));
  files["terrain_params"] = store.put_binary(detail::to_bytes(plan.terrain_params));
  files["terrain"] = store.put_binary(detail::to_bytes(plan.terrain));
  {
    detail::BinaryWriter index;
    index.write(plan.feature_index);
    index.write(plan.ribbon_index);
    files["index"] = store.put_binary(index.bytes);
  }
  RunReport report = plan.report;
  json timings = take_timings(report);
  // Every method's part of the report, stored by the method (its timings apart, by name).
  std::map<std::string, json> report_parts;
  for (MethodReportPart& part : report.method_parts) {
    const SynthesisMethod& method = report_part_method(plan, part);
    if (json seconds = method.take_report_timings(*part.part); !seconds.is_null())
      timings["methods"][part.method] = std::move(seconds);
    report_parts[part.method] = method.encode_report(*part.part, store);
  }
  report.method_parts.clear();
  files["report"] = store.put_binary(detail::to_bytes(report));
  // Every method's entry, in the methods' order: its name, its index, what it encodes and its
  // part of the report (null: none).
  json methods = json::array();
  for (const MethodPlan& entry : plan.methods) {
    const auto part = report_parts.find(entry.method->name());
    methods.push_back({{"name", entry.method->name()},
                       {"index", store.put_binary(detail::to_bytes(entry.index))},
                       {"entry", entry.method->encode(entry, store)},
                       {"report", part != report_parts.end() ? part->second : json()}});
  }
  // A DEM file travels as its path, options and the hash of its bytes (render-tile reads its
  // windows from it; the hash keeps the plan content-addressed); a generated world as its
  // parameters; heights held in memory (a plan made by hand) as a raster on the plan's grid.
  std::optional<HeightfieldFile> file = plan.heights.file;
  if (file) {
    const FileDigest digest = file_digest(file->path);
    file->xxh3_128 = digest.xxh3_128;
    file->bytes = digest.bytes;
  }
  const std::shared_ptr<const Raster<float>>& raster = plan.heights.heights;
  if (!raster && !plan.heights.generated && !file)
    fail("plan: the heights of {} have no source a plan can name", plan.heights.source);
  json heights = {{"source", plan.heights.source},
                  {"generated", encode(plan.heights.generated)},
                  {"file", encode(file)},
                  {"raster", raster ? store.put_binary(detail::to_bytes(raster)) : json()}};

  json doc = {{"format", kPlanFormat},
              {"version", kPlanVersion},
              {"grid", encode(plan.grid)},
              {"output_window", encode(plan.output_window)},
              {"crs_wkt", plan.crs_wkt},
              {"heights", heights},
              {"class_names", plan.class_names},
              {"splat_materials", plan.splat_materials},
              {"tiles", {{"size", plan.tile_size}, {"overlap", plan.tile_overlap}}},
              {"files", files},
              {"methods", methods}};
  // The plan's hash covers every value above; objects enter through their hashes.
  const std::string hash = content_hash(doc.dump() + tasks_json(plan, "").dump());
  doc["plan"] = hash;
  StagedPlan staged;
  staged.hash = hash;
  staged.tasks_json = tasks_json(plan, hash).dump(1) + "\n";
  // tasks.json is checked against this when loaded; like the timings, outside the plan's hash
  // (which covers tasks.json's values already).
  doc["tasks_xxh3_128"] = content_hash(staged.tasks_json);
  doc["timings"] = timings;
  staged.plan_json = doc.dump(1) + "\n";
  return staged;
}

std::set<std::string> plan_objects(const json& doc) {
  std::set<std::string> names;
  const auto visit = [&names](const auto& self, const json& j) -> void {
    if (j.is_object()) {
      if (j.contains("file") && j["file"].is_string() &&
          j["file"].get<std::string>().starts_with("objects/"))
        names.insert(j["file"].get<std::string>().substr(8));
      for (const auto& [key, value] : j.items()) self(self, value);
    } else if (j.is_array()) {
      for (const json& item : j) self(self, item);
    }
  };
  visit(visit, doc);
  return names;
}

void delete_unused_objects(const fs::path& dir, const std::set<std::string>& used) {
  std::error_code ec;
  for (auto it = fs::directory_iterator(dir / "objects", ec); !ec && it != fs::directory_iterator();
       it.increment(ec)) {
    if (!used.contains(it->path().filename().string())) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

}  // namespace detail

std::string save_plan(const WorldPlan& plan, const fs::path& dir) {
  const detail::StagedPlan staged = detail::stage_plan(plan, dir);
  write_file_atomic(dir / "tasks.json", staged.tasks_json);
  write_file_atomic(dir / "plan.json", staged.plan_json);
  detail::delete_unused_objects(dir, detail::plan_objects(json::parse(staged.plan_json)));
  return staged.hash;
}

std::string plan_hash(const fs::path& dir) {
  return read_plan_file(dir / "plan.json", kPlanFormat).value("plan", "");
}

namespace {

// load_plan, and with `tile` load_plan_for_tile.
WorldPlan read_plan(const fs::path& dir, const std::vector<const SynthesisMethod*>& methods,
                    std::optional<int> tile) {
  const json doc = read_plan_file(dir / "plan.json", kPlanFormat);
  std::error_code ec;
  if (!fs::is_regular_file(dir / "tasks.json", ec))
    fail("{}: missing; plan again ({})", (dir / "tasks.json").string(), detail::plan_again(dir));
  const json tasks = read_plan_file(dir / "tasks.json", kTasksFormat);
  const std::string where = "plan " + (dir / "plan.json").string();
  if (tasks.value("plan", "") != doc.value("plan", ""))
    fail("{}: tasks.json belongs to plan {}, plan.json is {}; plan again ({})", where,
         tasks.value("plan", ""), doc.value("plan", ""), detail::plan_again(dir));
  // Like the objects, the plan's own files are checked against their hashes (issue #24: an
  // edited tile window committed wrong rasters): tasks.json's bytes against plan.json's record,
  // then plan.json's fields and tasks.json's values against the plan's hash.
  if (content_hash(read_file_bytes(dir / "tasks.json")) != doc.value("tasks_xxh3_128", ""))
    fail(
        "{}: does not match its hash in plan.json (edited or corrupt after planning); plan "
        "again ({})",
        (dir / "tasks.json").string(), detail::plan_again(dir));
  {
    json fields = doc;
    for (const char* outside : {"plan", "timings", "tasks_xxh3_128"}) fields.erase(outside);
    json values = tasks;
    values["plan"] = "";
    if (content_hash(fields.dump() + values.dump()) != doc.value("plan", ""))
      fail(
          "{}: its fields do not match the plan's hash {} (edited or corrupt after planning); "
          "plan again ({})",
          (dir / "plan.json").string(), doc.value("plan", ""), detail::plan_again(dir));
  }
  WorldPlan plan;
  detail::PlanObjects objects(dir);
  try {
    detail::JsonReader reader(doc, where);
    reader("grid", plan.grid);
    reader("output_window", plan.output_window);
    reader("crs_wkt", plan.crs_wkt);
    reader("class_names", plan.class_names);
    reader("splat_materials", plan.splat_materials);
    decode(doc.at("tiles").at("size"), plan.tile_size, where + ": tiles.size");
    decode(doc.at("tiles").at("overlap"), plan.tile_overlap, where + ": tiles.overlap");
    decode(tasks.at("tiles"), plan.tiles, "tasks.json: tiles");
    const json& heights = doc.at("heights");
    decode(heights.at("source"), plan.heights.source, where + ": heights.source");
    decode(heights.at("generated"), plan.heights.generated, where + ": heights.generated");
    decode(heights.at("file"), plan.heights.file, where + ": heights.file");
    if (!heights.at("raster").is_null()) {
      const json wrapper = {{"raster", heights["raster"]}};
      get_value(objects, wrapper, "raster", plan.heights.heights);
    }
    if (plan.heights.file)
      plan.heights.reader = open_planned_heightfield(*plan.heights.file, where);
    // A generated world's CRS is the plan's own (plan.crs_wkt came from it when planning).
    if (plan.heights.generated)
      plan.heights.reader = plan.crs_wkt.empty()
                                ? open_generated_heightfield(*plan.heights.generated)
                                : open_generated_heightfield(*plan.heights.generated, plan.crs_wkt);
    if (tile && (*tile < 0 || std::size_t(*tile) >= plan.tiles.size()))
      fail("--tile {}: the plan has {} tiles (0 to {})", *tile, plan.tiles.size(),
           int(plan.tiles.size()) - 1);
    const json& files = doc.at("files");
    {
      const auto settings = get_binary(objects, files, "settings");
      detail::BinaryReader reader(settings.body(), where + ": settings");
      reader.read(plan.nodata);
      reader.read(plan.render);
      reader.finish();
    }
    {
      const auto index = get_binary(objects, files, "index");
      detail::BinaryReader reader(index.body(), where + ": index");
      reader.read(plan.feature_index);
      reader.read(plan.ribbon_index);
      reader.finish();
    }
    get_value(objects, files, "lines", plan.lines);
    {
      // A tile's render reads the ribbons that can reach its halo window (render_tile's
      // avoidance, the tile cache's key): the others stay empty.
      std::optional<std::vector<std::size_t>> only;
      if (tile)
        only =
            items_meeting(plan.ribbon_index, grow_window(plan.tiles[std::size_t(*tile)].halo_window,
                                                         avoidance_halo_pixels(plan), plan.grid));
      detail::ribbons_from_bytes(get_binary(objects, files, "ribbons").body(), plan.ribbons,
                                 only ? &*only : nullptr, where + ": ribbons");
    }
    get_value(objects, files, "junction_discs", plan.junction_discs);
    get_value(objects, files, "existing", plan.existing);
    get_value(objects, files, "terrain_features", plan.terrain_features);
    get_value(objects, files, "terrain_params", plan.terrain_params);
    get_value(objects, files, "terrain", plan.terrain);
    // What syntheses read and what the run reports: not a tile's render (left unread for one).
    if (!tile) {
      get_value(objects, files, "synthesis_junction_discs", plan.synthesis_junction_discs);
      get_value(objects, files, "synthesis_junctions", plan.synthesis_junctions);
      get_value(objects, files, "report", plan.report);
    }
    if (!tile && doc.contains("timings")) restore_timings(doc["timings"], plan.report, where);
    const std::vector<const SynthesisMethod*>& known = methods_or_builtin(methods);
    const json& entries = doc.at("methods");
    for (std::size_t i = 0; i < entries.size(); ++i) {
      const std::string key = fmt::format("methods[{}]", i);
      const std::string name = entries[i].at("name").get<std::string>();
      const auto method = std::find_if(known.begin(), known.end(),
                                       [&](const SynthesisMethod* m) { return m->name() == name; });
      if (method == known.end())
        fail("{}: {}: method '{}' is not one this terraweave knows; plan again ({})", where, key,
             name, detail::plan_again(dir));
      MethodPlan& entry = plan.methods.emplace_back(*method, (*method)->empty_payload());
      detail::from_bytes(objects.get_binary(entries[i].at("index"), key + ".index").body(),
                         entry.index, where + ": " + key + ".index");
      (*method)->decode(entries[i].at("entry"), objects, entry);
      const json& part = entries[i].at("report");
      if (tile || part.is_null()) continue;  // a tile's render reads no report
      std::unique_ptr<MethodPayload> decoded = (*method)->decode_report(part, objects);
      const json* seconds = doc.contains("timings") ? &doc["timings"] : nullptr;
      if (seconds && seconds->contains("methods") && (*seconds)["methods"].contains(name))
        (*method)->restore_report_timings((*seconds)["methods"][name], *decoded);
      plan.report.method_parts.emplace_back(name, std::move(decoded));
    }
  } catch (const json::exception& e) {
    fail("{}: {}", where, e.what());
  }
  return plan;
}

}  // namespace

WorldPlan load_plan(const fs::path& dir, const std::vector<const SynthesisMethod*>& methods) {
  return read_plan(dir, methods, std::nullopt);
}

WorldPlan load_plan_for_tile(const fs::path& dir, int tile,
                             const std::vector<const SynthesisMethod*>& methods) {
  return read_plan(dir, methods, tile);
}

}  // namespace tw
