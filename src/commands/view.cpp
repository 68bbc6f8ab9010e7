#include "commands/view.hpp"

#include <cpl_minixml.h>
#include <cpl_string.h>
#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "commands/detail/network_page.hpp"
#include "commands/detail/three_js.hpp"
#include "commands/detail/view_page.hpp"
#include "core/atomic_output.hpp"
#include "core/error.hpp"
#include "core/output_guard.hpp"
#include "core/warnings.hpp"
#include "geo/height_sampler.hpp"
#include "geo/heightfield_source.hpp"
#include "layers/export.hpp"
#include "layers/layer_raster.hpp"
#include "layers/write.hpp"
#include "pipeline/json_file.hpp"
#include "pipeline/run_layers.hpp"

namespace tw {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// GDAL's encoder (cpl_string.h), which the project links already.
std::string base64(std::string_view bytes) {
  char* encoded = CPLBase64Encode(int(bytes.size()), reinterpret_cast<const GByte*>(bytes.data()));
  std::string out(encoded);
  CPLFree(encoded);
  return out;
}

// Every band of a layer raster (GeoTIFF, EXR or a tiled run's VRT mosaic) read at w x h (GDAL
// resamples on reading: memory follows the page, not the world); nodata as NaN. Band descriptions
// in `names`.
// A tiled run's mosaic opens its tiles only when read: a missing one is named here, with what
// to do, rather than as GDAL's read failure.
void require_mosaic_tiles(const fs::path& vrt) {
  if (vrt.extension() != ".vrt") return;
  CPLXMLNode* root = CPLParseXMLFile(vrt.c_str());
  if (root == nullptr) fail("{}: not a readable VRT mosaic; run it again", vrt.string());
  std::string missing;
  const std::function<void(const CPLXMLNode*)> walk = [&](const CPLXMLNode* node) {
    for (; node != nullptr && missing.empty(); node = node->psNext) {
      if (node->eType != CXT_Element) continue;
      if (std::string_view(node->pszValue) == "SourceFilename") {
        const char* name = CPLGetXMLValue(node, nullptr, "");
        const bool relative = CPLTestBool(CPLGetXMLValue(node, "relativeToVRT", "0"));
        const fs::path tile = relative ? vrt.parent_path() / name : fs::path(name);
        std::error_code ec;
        if (!fs::is_regular_file(tile, ec)) missing = tile.string();
      }
      walk(node->psChild);
    }
  };
  walk(root);
  CPLDestroyXMLNode(root);
  if (!missing.empty())
    fail(
        "{}: its tile {} is missing; render that tile again (terraweave run, or render-tile "
        "and finish for a plan)",
        vrt.string(), missing);
}

std::vector<std::vector<float>> read_bands(const fs::path& path, int w, int h,
                                           std::vector<std::string>* names = nullptr) {
  require_mosaic_tiles(path);
  const LayerRaster raster(path);
  GDALDataset* ds = &raster.dataset();
  std::vector<std::vector<float>> bands;
  for (int b = 1; b <= ds->GetRasterCount(); ++b) {
    GDALRasterBand* band = ds->GetRasterBand(b);
    std::vector<float>& v = bands.emplace_back(std::size_t(w) * h);
    if (band->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(), ds->GetRasterYSize(), v.data(), w, h,
                       GDT_Float32, 0, 0) != CE_None)
      fail("{}: cannot read band {}", path.string(), b);
    int has_nodata = 0;
    const double nodata = band->GetNoDataValue(&has_nodata);
    if (has_nodata)
      for (float& x : v)
        if (x == float(nodata)) x = NAN;
    if (names) names->push_back(band->GetDescription());
  }
  return bands;
}

std::pair<int, int> fit(int width, int height, int longest) {
  const double f = std::max(1.0, double(std::max(width, height)) / std::max(2, longest));
  return {std::max(2, int(std::lround(width / f))), std::max(2, int(std::lround(height / f)))};
}

// The splat colours, rows south first: each material in its preview colour by its weight, the
// base in an elevation tint (green low, brown high).
std::string splat_rgb(const fs::path& run, int w, int h) {
  std::vector<std::string> names;
  const auto splat = read_bands(required_run_layer_raster(run, "splat"), w, h, &names);
  const auto height = read_bands(required_run_layer_raster(run, "height"), w, h).at(0);
  float lo = INFINITY, hi = -INFINITY;
  for (const float v : height)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  std::vector<Rgb8> colours;
  for (const std::string& name : names) colours.push_back(preview_material_colour(name));
  std::string rgb(std::size_t(w) * h * 3, '\0');
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const std::size_t k = std::size_t(r) * w + c;
      const double t = hi > lo && std::isfinite(height[k]) ? (height[k] - lo) / (hi - lo) : 0.0;
      double colour[3] = {0, 0, 0}, covered = 0;
      for (std::size_t m = 0; m < names.size(); ++m) {
        if (names[m] == "splat.base" || std::isnan(splat[m][k])) continue;
        const double share = std::clamp(double(splat[m][k]), 0.0, 1.0 - covered);
        covered += share;
        for (int i = 0; i < 3; ++i) colour[i] += colours[m][i] * share;
      }
      const double base[3] = {90 + 80 * t, 130 - 30 * t, 60 + 20 * t};
      const std::size_t out = (std::size_t(h - 1 - r) * w + c) * 3;
      for (int i = 0; i < 3; ++i)
        rgb[out + i] = char(std::clamp(colour[i] + base[i] * (1.0 - covered), 0.0, 255.0));
    }
  return rgb;
}

std::string forbidden_mask(const fs::path& run, int w, int h) {
  const auto forbidden = read_bands(required_run_layer_raster(run, "avoidance"), w, h).at(0);
  std::string mask(std::size_t(w) * h, '\0');
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      mask[std::size_t(h - 1 - r) * w + c] = forbidden[std::size_t(r) * w + c] > 0.5f ? 1 : 0;
  return mask;
}

// The run's feature lines (features.geojson): kind and points, checked.
json view_data_features(const fs::path& run) {
  json features = json::array();
  if (fs::exists(run / "features.geojson")) {
    const fs::path path = run / "features.geojson";
    const json lines = parse_json_file(path, "run it again");
    if (!lines.is_object() || !lines.contains("features") || !lines["features"].is_array())
      fail("{}: key features: expected a list of GeoJSON features; run it again", path.string());
    for (const json& f : lines["features"]) {
      const std::string fid = f.is_object() && f.contains("properties") &&
                                      f["properties"].is_object() && f["properties"].contains("fid")
                                  ? f["properties"]["fid"].dump()
                                  : "?";
      if (!f.is_object() || !f.contains("properties") || !f["properties"].is_object() ||
          !f.contains("geometry") || !f["geometry"].is_object() ||
          !f["geometry"].contains("coordinates") || !f["geometry"]["coordinates"].is_array())
        fail(
            "{}: feature {} (FID {}): expected properties and a geometry with coordinates; run "
            "it again",
            path.string(), features.size(), fid);
      features.push_back({{"kind", f["properties"].value("kind", json(nullptr))},
                          {"points", f["geometry"]["coordinates"]}});
    }
  }
  return features;
}

// What both pages show first: the run's name and its grid (without the CRS's WKT), and the
// grid's size.
struct PageHead {
  json data;
  int width = 0, height = 0;
};

PageHead page_head(const fs::path& run) {
  const json report = parse_json_file(run / "report.json", "run it again");
  const json& grid = report.at("grid");
  PageHead head{json::object(), grid.at("width"), grid.at("height")};
  head.data["name"] =
      (run.filename().empty() ? run.parent_path().filename() : run.filename()).string();
  head.data["grid"] = grid;
  head.data["grid"].erase("crs_wkt");
  return head;
}

json view_data(const fs::path& run, const ViewOptions& options) {
  auto [data, width, height] = page_head(run);
  const auto [mw, mh] = fit(width, height, options.mesh_size);
  json heights = json::array();
  const std::vector<float> mesh =
      read_bands(required_run_layer_raster(run, "height"), mw, mh).at(0);
  for (const float v : mesh)
    heights.push_back(std::isfinite(v) ? json(std::round(v * 100.0) / 100.0) : json(nullptr));
  data["mesh"] = {{"width", mw}, {"height", mh}, {"heights", heights}};
  data["exaggeration"] = 1.0;
  const auto [tw, th] = fit(width, height, options.texture_size);
  data["texture"] = {{"width", tw}, {"height", th}, {"rgb", base64(splat_rgb(run, tw, th))}};
  data["avoidance"] = {{"mask", base64(forbidden_mask(run, tw, th))}};
  data["features"] = view_data_features(run);
  return data;
}

}  // namespace

std::string network_page(const ViewOptions& options, const std::string& save_path) {
  if (options.verify) verify_run_files(options.run_dir, "view");
  const fs::path& run = options.run_dir;
  auto [data, width, height] = page_head(run);
  const auto [tw, th] = fit(width, height, options.texture_size);
  std::string rgb = splat_rgb(run, tw, th);  // rows south first: the canvas wants north first
  std::string north_first(rgb.size(), '\0');
  const std::size_t row = std::size_t(tw) * 3;
  for (int r = 0; r < th; ++r)
    north_first.replace(std::size_t(r) * row, row, rgb, std::size_t(th - 1 - r) * row, row);
  data["image"] = {{"width", tw}, {"height", th}, {"rgb", base64(north_first)}};
  json features = json::array();
  for (const json& f : view_data_features(run)) features.push_back(f["points"]);
  data["features"] = features;
  data["save_path"] = save_path;
  std::string text = data.dump();
  for (std::size_t at = 0; (at = text.find("</", at)) != std::string::npos; at += 3)
    text.replace(at, 2, "<\\/");
  std::string page = detail::kNetworkPage;
  page.replace(page.find("@DATA@"), 6, text);
  return page;
}

ForbiddenMask run_forbidden_mask(const fs::path& run_dir) {
  const json report = parse_json_file(run_dir / "report.json", "run it again");
  const json& grid = report.at("grid");
  // At most 4096 cells a side (GDAL resamples on reading): memory follows the page, not the world.
  const int width = grid.at("width"), height = grid.at("height");
  const auto [w, h] = fit(width, height, 4096);
  ForbiddenMask mask;
  mask.grid.width = w;
  mask.grid.height = h;
  mask.grid.origin_x = grid.at("origin").at(0);
  mask.grid.origin_y = grid.at("origin").at(1);
  mask.grid.pixel_width = grid.at("pixel_size").at(0).get<double>() * width / w;
  mask.grid.pixel_height = grid.at("pixel_size").at(1).get<double>() * height / h;
  const std::vector<float> avoidance =
      read_bands(required_run_layer_raster(run_dir, "avoidance"), mask.grid.width, mask.grid.height)
          .at(0);
  mask.cells = Raster<std::uint8_t>(mask.grid.width, mask.grid.height);
  for (std::size_t k = 0; k < avoidance.size(); ++k) mask.cells.pixels[k] = avoidance[k] > 0.5f;
  return mask;
}

std::string run_crs_wkt(const fs::path& run_dir) {
  const json report = parse_json_file(run_dir / "report.json", "run it again");
  const json& grid = report.at("grid");
  return grid.contains("crs_wkt") && grid["crs_wkt"].is_string()
             ? grid["crs_wkt"].get<std::string>()
             : std::string();
}

LeadAngle run_lead_angle(const fs::path& run_dir, Lead lead, double bearing_deg,
                         const std::vector<Polygon>& region) {
  const Polygon& polygon = lead_polygon(region);
  std::vector<LineFeature> road_features;
  if (lead == Lead::nearest_road && fs::exists(run_dir / "features.geojson"))
    for (ExportCurve& curve : read_curves_geojson(run_dir / "features.geojson"))
      if (curve.kind == "road")
        road_features.push_back({.fid = curve.fid,
                                 .points = std::move(curve.points),
                                 .width = curve.width,
                                 .source = (run_dir / "features.geojson").string()});
  std::vector<const LineFeature*> roads;
  for (const LineFeature& road : road_features) roads.push_back(&road);
  // Opened, not read: only `contours` reads pixels (a 32 x 32 lattice over the polygon).
  Warnings warnings;
  const std::unique_ptr<HeightfieldSource> source =
      open_heightfield(required_run_layer_raster(run_dir, "height").string(), {}, warnings);
  HeightSampler heights(*source);
  return lead_angle(lead, bearing_deg, polygon, roads, heights);
}

fs::path write_view(const ViewOptions& options) {
  // Checked first: the page is built from the whole run, which takes seconds.
  const fs::path out = options.out.empty() ? options.run_dir / "view.html" : options.out;
  require_safe_output(out, false,
                      {.command = "view",
                       .option = "--out",
                       .inputs = {options.run_dir},
                       .allowed = options.run_dir / "view.html"});
  if (detail::kThreeJs.empty())
    fail(
        "view: this terraweave was built without three.js (npm was missing): build it with npm "
        "installed");
  if (options.verify) verify_run_files(options.run_dir, "view");
  // "</" never appears in the JSON as written (a string holding it is escaped), so the script
  // element cannot end early.
  std::string data = view_data(options.run_dir, options).dump();
  for (std::size_t at = 0; (at = data.find("</", at)) != std::string::npos; at += 3)
    data.replace(at, 2, "<\\/");
  std::string page = detail::kViewPage;
  page.replace(page.find("@THREE@"), 7, base64(detail::kThreeJs));
  page.replace(page.find("@DATA@"), 6, data);
  OutputTransaction transaction;
  std::ofstream stream(transaction.stage(out), std::ios::binary);
  stream << page;
  stream.close();
  if (!stream) fail("cannot write {}", out.string());
  transaction.commit();
  return out;
}

}  // namespace tw
