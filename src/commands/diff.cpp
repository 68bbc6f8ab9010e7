#include "commands/diff.hpp"

#include <ogr_spatialref.h>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.hpp"
#include "pipeline/json_file.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

json read_manifest(const fs::path& run) {
  const fs::path path = run / "report.json";
  std::ifstream in(path);
  if (!in) fail("{}: no report.json: not the output folder of a terraweave run", run.string());
  in.close();
  const json report = parse_json_file(path, "run it again");
  if (!report.is_object() || report.value("format", "") != kReportFormat ||
      !report.contains("version") || report["version"].value("schema", 0) < 2) {
    fail("{}: not a terraweave report of schema 2 or later (run it again with this version)",
         path.string());
  }
  return report;
}

// name -> hash of the file as it is now ("" when it is gone), for the files report.json names.
std::map<std::string, std::string> output_hashes(const fs::path& run) {
  std::map<std::string, std::string> hashes;
  for (const RunFile& f : hash_run_files(run)) hashes[f.name] = f.now ? f.now->xxh3_128 : "";
  return hashes;
}

bool is_raster(const std::string& name) {
  const std::string ext = fs::path(name).extension().string();
  return ext == ".tif" || ext == ".exr";
}

std::string value_text(const json& value) {
  const std::string text = value.dump();
  return text.size() <= 80 ? text : text.substr(0, 77) + "...";
}

// "WGS 84 / UTM zone 33N (EPSG:32633)": a CRS as a person names it ("none" without one).
std::string crs_name(const json& report) {
  if (!report.contains("grid") || !report["grid"].is_object()) return "none";
  const std::string wkt = report["grid"].value("crs_wkt", std::string());
  if (wkt.empty()) return "none";
  OGRSpatialReference srs;
  if (srs.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "unreadable WKT";
  std::string name = srs.GetName() ? srs.GetName() : "unnamed";
  srs.AutoIdentifyEPSG();
  if (const char* code = srs.GetAuthorityCode(nullptr); code && srs.GetAuthorityName(nullptr))
    name += fmt::format(" ({}:{})", srs.GetAuthorityName(nullptr), code);
  return name;
}

// A tiled run's mosaic (LAYER.vrt) and an untiled run's GeoTIFF (LAYER.tif) are the same layer:
// the name of the other run's file for `name` when only that run has it.
std::optional<std::string> layer_twin(const std::string& name,
                                      const std::map<std::string, std::string>& mine,
                                      const std::map<std::string, std::string>& other) {
  const fs::path path(name);
  if (path.has_parent_path() || (path.extension() != ".vrt" && path.extension() != ".tif"))
    return std::nullopt;
  const std::string twin = path.stem().string() + (path.extension() == ".vrt" ? ".tif" : ".vrt");
  if (mine.count(twin) || !other.count(twin)) return std::nullopt;
  return twin;
}

}  // namespace

RunDifference diff_runs(const fs::path& run_a, const fs::path& run_b, bool verify) {
  json a = read_manifest(run_a);
  json b = read_manifest(run_b);
  if (verify) {
    verify_run_files(run_a, "diff");
    verify_run_files(run_b, "diff");
  }
  RunDifference result;
  const auto hashes_a = output_hashes(run_a);
  const auto hashes_b = output_hashes(run_b);
  for (const auto& [name, hash] : hashes_a) {
    const auto other = hashes_b.find(name);
    if (other == hashes_b.end()) {
      const std::optional<std::string> twin = layer_twin(name, hashes_a, hashes_b);
      if (!twin) {
        result.files.push_back(name + ": only in A");
        continue;
      }
      const std::string both = name + " / " + *twin;  // a tiled run's mosaic, an untiled TIFF
      try {
        RasterDifference raster = compare_rasters(run_a / name, run_b / *twin);
        if (!raster.identical()) result.layers.push_back({both, std::move(raster)});
      } catch (const Error& e) {
        result.files.push_back(both + ": contents differ (" + e.what() + ")");
      }
    } else if (other->second != hash || hash.empty()) {
      if (!is_raster(name)) {
        result.files.push_back(name + ": contents differ");
        continue;
      }
      if (hash.empty() || other->second.empty()) {  // gone from a folder (--no-verify)
        result.files.push_back(name + (hash.empty() ? ": missing in A" : ": missing in B"));
        continue;
      }
      RasterDifference raster;
      try {
        raster = compare_rasters(run_a / name, run_b / name);
      } catch (const Error& e) {  // unreadable as it is now (--no-verify): it differs
        result.files.push_back(name + ": contents differ (" + e.what() + ")");
        continue;
      }
      if (!raster.identical()) {
        result.layers.push_back({name, std::move(raster)});
      } else if (other->second != hash) {  // same pixels, other bytes (metadata)
        result.files.push_back(name + ": same pixels, other bytes (metadata)");
      }
    }
  }
  for (const auto& [name, hash] : hashes_b)
    if (!hashes_a.count(name) && !layer_twin(name, hashes_b, hashes_a))
      result.files.push_back(name + ": only in B");
  // Pixels of two CRSs are compared cell by cell: said first, with both CRSs named.
  if (const std::string crs_a = crs_name(a), crs_b = crs_name(b);
      a.contains("grid") && b.contains("grid") && a["grid"].is_object() && b["grid"].is_object() &&
      a["grid"].value("crs_wkt", std::string()) != b["grid"].value("crs_wkt", std::string()))
    result.files.insert(result.files.begin(),
                        fmt::format("the runs' CRSs differ: A is {}, B is {} (pixels are compared "
                                    "cell by cell, not place by place)",
                                    crs_a, crs_b));
  for (json* report : {&a, &b}) {
    report->erase("timings");
    report->erase("outputs");
  }
  for (const json& op : json::diff(a, b)) {
    const std::string path = op.at("path").get<std::string>();
    const std::string kind = op.at("op").get<std::string>();
    const json::json_pointer pointer(path);
    if (kind == "replace") {
      result.manifest.push_back(path + ": " + value_text(a.at(pointer)) + " -> " +
                                value_text(op.at("value")));
    } else if (kind == "add") {
      result.manifest.push_back(path + ": -> " + value_text(op.at("value")));
    } else if (kind == "remove") {
      result.manifest.push_back(path + ": " + value_text(a.at(pointer)) + " ->");
    }
  }
  return result;
}

std::vector<std::string> describe(const RunDifference& d) {
  if (d.identical()) return {"identical"};
  std::vector<std::string> lines;
  for (const LayerFileDifference& layer : d.layers) {
    const RasterDifference& r = layer.raster;
    if (!r.size_mismatch.empty()) lines.push_back(layer.file + ": size " + r.size_mismatch);
    for (const std::string& band : r.only_in_a)
      lines.push_back(layer.file + " " + band + ": only in A");
    for (const std::string& band : r.only_in_b)
      lines.push_back(layer.file + " " + band + ": only in B");
    for (const BandDifference& band : r.bands) {
      if (band.differing == 0) continue;
      std::string line =
          fmt::format("{} {}: {} pixels differ", layer.file, band.band, band.differing);
      if (band.col >= 0) {
        line += fmt::format(", largest {:.9g} at col {} row {} ({:.9g} -> {:.9g})", band.max_abs,
                            band.col, band.row, band.a, band.b);
      }
      if (band.nodata_mismatch > 0)
        line += fmt::format(", {} nodata in one run only", band.nodata_mismatch);
      lines.push_back(line);
    }
  }
  for (const std::string& f : d.files) lines.push_back(f);
  for (const std::string& m : d.manifest) lines.push_back("report.json " + m);
  return lines;
}

}  // namespace tw
