#include "cli/view_server.hpp"

#include <httplib.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands/network_command.hpp"
#include "commands/view.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/output_guard.hpp"
#include "core/warnings.hpp"
#include "network/exemplar.hpp"
#include "network/growth.hpp"

namespace tw {

namespace {

using nlohmann::json;

std::vector<Vec2> points_of(const json& line, const std::string& what) {
  if (!line.is_array()) fail("{}: expected a list of [x, y] points", what);
  std::vector<Vec2> points;
  for (const json& p : line) {
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      fail("{}: expected a list of [x, y] points", what);
    points.push_back({p[0].get<double>(), p[1].get<double>()});
  }
  return points;
}

std::vector<std::vector<Vec2>> lines_of(const json& body) {
  if (!body.contains("lines") || !body["lines"].is_array()) fail("key lines: expected a list");
  std::vector<std::vector<Vec2>> lines;
  for (std::size_t i = 0; i < body["lines"].size(); ++i)
    lines.push_back(points_of(body["lines"][i], fmt::format("line {}", i + 1)));
  return lines;
}

// The request's `method` (absent: automatic), named as `network complete --method` names them.
NetworkMethod method_of(const json& body) {
  const json name = body.value("method", json("automatic"));
  const auto& names = kNetworkMethodNames;
  const auto known = name.is_string()
                         ? std::find(names.begin(), names.end(), name.get<std::string>())
                         : names.end();
  if (known == names.end()) {
    std::string listed;
    for (std::string_view known_name : names)
      listed += (listed.empty() ? "" : ", ") + std::string(known_name);
    fail("key method: {} is none of {}", name.dump(), listed);
  }
  return NetworkMethod(known - names.begin());
}

// The request's `lead` (absent or null: none), written as a network class's `lead:` is:
// "long_axis", "nearest_road", "contours" or {"bearing": DEG}.
struct RequestedLead {
  Lead lead = Lead::bearing;
  double bearing_deg = 0.0;
};
std::optional<RequestedLead> lead_of(const json& body) {
  if (!body.contains("lead") || body["lead"].is_null()) return std::nullopt;
  const json& lead = body["lead"];
  if (lead.is_object() && lead.size() == 1 && lead.contains("bearing")) {
    const json& bearing = lead["bearing"];
    if (!bearing.is_number() || !std::isfinite(bearing.get<double>()))
      fail("key lead.bearing: {} is not a finite angle in degrees", bearing.dump());
    return RequestedLead{Lead::bearing, bearing.get<double>()};
  }
  for (Lead named : {Lead::long_axis, Lead::nearest_road, Lead::contours})
    if (lead.is_string() && lead.get<std::string>() == lead_name(named))
      return RequestedLead{named, 0.0};
  fail("key lead: {} is none of long_axis, nearest_road, contours or {{\"bearing\": DEG}}",
       lead.dump());
}

json to_json(const std::vector<std::vector<Vec2>>& lines) {
  json out = json::array();
  for (const auto& line : lines) {
    json points = json::array();
    for (Vec2 p : line) points.push_back({p.x, p.y});
    out.push_back(points);
  }
  return out;
}

// Answers with the handler's JSON, or 400 and {"error": one line} when it throws.
template <typename Handler>
void answer(const httplib::Request& request, httplib::Response& response, Handler handler) {
  try {
    const json body = json::parse(request.body);
    response.set_content(handler(body).dump(), "application/json");
  } catch (const std::exception& e) {
    response.status = 400;
    response.set_content(json{{"error", single_line(e.what())}}.dump(), "application/json");
  }
}

}  // namespace

void serve_view(const ViewOptions& view, const ViewServeOptions& o) {
  httplib::Server server;
  const std::filesystem::path folder = std::filesystem::absolute(o.page).parent_path();
  if (!server.set_mount_point("/", folder.string()))
    fail("--serve: cannot serve {}", folder.string());
  std::string landing = o.page.filename().string();
  std::optional<Network> exemplar;
  std::string crs_wkt, page;
  ForbiddenMask forbidden;
  std::mutex one_at_a_time;  // growth and the GeoPackage writer: one request at a time
  if (!o.exemplar.empty()) {
    require_safe_output(o.save, false,
                        {.command = "view",
                         .option = "--save",
                         .inputs = {view.run_dir, split_source(o.exemplar).first}});
    crs_wkt = run_crs_wkt(view.run_dir);
    OGRSpatialReference srs;
    if (crs_wkt.empty() || srs.importFromWkt(crs_wkt.c_str()) != OGRERR_NONE || !srs.IsProjected())
      fail("view --exemplar: {}: the run's CRS is not projected (drawing grows networks in metres)",
           view.run_dir.string());
    Warnings warnings;
    exemplar = read_network_exemplar(
        {.source = o.exemplar, .where = o.where, .scale = o.scale, .subject = "--exemplar"}, 0.0,
        warnings);
    forbidden = run_forbidden_mask(view.run_dir);
    ViewOptions page_options = view;
    page_options.verify = false;  // write_view checked the run already
    page = network_page(page_options, std::filesystem::absolute(o.save).string());
    landing = "network.html";
    server.Get("/network.html", [&](const httplib::Request&, httplib::Response& response) {
      response.set_content(page, "text/html; charset=utf-8");
    });
    // {lines: [[[x, y], ...], ...], region: [[x, y], ...], method: "automatic" | "growth" |
    // "quilt" | "layout" (absent: automatic), lead: as lead_of reads it (absent: none)} ->
    // {suggestions: [...], method: as asked, chosen: the one that made them
    // (chosen_network_method: never automatic), lead_bearing_deg: the compass bearing the
    // exemplar was turned to (null: none), warning: why the lead fell back to the long axis
    // (absent when it did not)}
    server.Post("/complete", [&](const httplib::Request& request, httplib::Response& response) {
      answer(request, response, [&](const json& body) {
        NetworkLines drawn;
        drawn.crs_wkt = crs_wkt;
        drawn.lines = lines_of(body);
        for (std::size_t i = 0; i < drawn.lines.size(); ++i) {
          if (drawn.lines[i].size() < 2) fail("line {}: fewer than two points", i + 1);
          drawn.fids.push_back(std::int64_t(i + 1));
        }
        if (!body.contains("region")) fail("key region: expected a ring of [x, y] points");
        const std::vector<Vec2> ring = points_of(body["region"], "key region");
        NetworkGrowthOptions growth;
        growth.seed = body.value("seed", o.seed);
        growth.method = method_of(body);
        const std::optional<RequestedLead> lead = lead_of(body);
        std::lock_guard lock(one_at_a_time);
        std::string fell_back;
        if (lead && lead->lead == Lead::bearing) {
          growth.lead_bearing = lead->bearing_deg;
        } else if (lead) {
          const LeadAngle angle =
              run_lead_angle(view.run_dir, lead->lead, lead->bearing_deg, {{ring}});
          growth.lead_bearing = compass_degrees(angle.radians);
          if (angle.fell_back)
            fell_back = lead->lead == Lead::nearest_road
                            ? "no road in the run: the lines follow the region's long axis"
                            : "flat or nodata terrain over the region: the lines follow its "
                              "long axis";
        }
        NetworkGrowthReport report;
        const auto suggestions =
            complete_drawing(*exemplar, drawn, {{ring}}, &forbidden, growth, &report);
        json answer{
            {"suggestions", to_json(suggestions)},
            {"method", std::string(network_method_name(growth.method))},
            {"chosen", std::string(chosen_network_method(report))},
            {"lead_bearing_deg", growth.lead_bearing ? json(*growth.lead_bearing) : json()}};
        if (!fell_back.empty()) answer["warning"] = fell_back;
        return answer;
      });
    });
    // The drawing saved at --save, when there is one: {lines, origins} as saved (empty lists
    // when nothing was saved yet), shown by the page on loading as accepted lines.
    server.Get("/drawing", [&](const httplib::Request&, httplib::Response& response) {
      json body = {{"lines", json::array()}, {"origins", json::array()}};
      try {
        std::lock_guard lock(one_at_a_time);
        if (std::filesystem::exists(o.save)) {
          std::vector<std::string> origins;
          body["lines"] = to_json(read_drawn_network(o.save, crs_wkt, origins));
          body["origins"] = origins;
        }
        response.set_content(body.dump(), "application/json");
      } catch (const std::exception& e) {
        response.status = 400;
        response.set_content(json{{"error", single_line(e.what())}}.dump(), "application/json");
      }
    });
    // {lines: [...], origins: ["drawn" | "suggested", ...]} -> {path, lines}
    server.Post("/save", [&](const httplib::Request& request, httplib::Response& response) {
      answer(request, response, [&](const json& body) {
        const auto lines = lines_of(body);
        std::vector<std::string> origins;
        for (const json& origin : body.value("origins", json::array()))
          origins.push_back(origin.is_string() ? origin.get<std::string>() : "drawn");
        std::lock_guard lock(one_at_a_time);
        write_drawn_network(o.save, crs_wkt, lines, origins);
        return json{{"path", std::filesystem::absolute(o.save).string()}, {"lines", lines.size()}};
      });
    });
  }
  server.Get("/", [&](const httplib::Request&, httplib::Response& response) {
    response.set_redirect("/" + landing);
  });
  const int port = o.port == 0 ? server.bind_to_any_port("127.0.0.1")
                               : (server.bind_to_port("127.0.0.1", o.port) ? o.port : -1);
  if (port <= 0) fail("--serve: cannot listen on 127.0.0.1:{} (in use?)", o.port);
  std::printf("serving http://127.0.0.1:%d/%s (Ctrl-C stops)\n", port, landing.c_str());
  std::fflush(stdout);
  server.listen_after_bind();
}

}  // namespace tw
