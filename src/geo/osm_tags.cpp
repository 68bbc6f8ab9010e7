#include "geo/osm_tags.hpp"

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

#include <fmt/format.h>

namespace tw {
namespace {

struct ClassWidth {
  std::string_view key;
  std::string_view value;
  double metres;
};

// Default widths (metres of the surface the feature shapes) where a way has neither `width`
// nor `lanes`. OSM itself defines no widths: these follow the carriageways the wiki's
// highway=* classes describe (two lanes of ~3.5 m for primary roads, a single lane for
// tracks, footpaths for people), and the waterway=* wiki's river (wide enough to be drawn as
// an area), stream (a person can jump across), canal and drain. A motorway or trunk way is
// one carriageway: OSM draws dual carriageways as two ways.
constexpr std::array kClassWidths{
    ClassWidth{"highway", "motorway", 11.0},      ClassWidth{"highway", "trunk", 9.0},
    ClassWidth{"highway", "primary", 7.0},        ClassWidth{"highway", "secondary", 6.5},
    ClassWidth{"highway", "tertiary", 6.0},       ClassWidth{"highway", "motorway_link", 5.0},
    ClassWidth{"highway", "trunk_link", 5.0},     ClassWidth{"highway", "primary_link", 5.0},
    ClassWidth{"highway", "secondary_link", 5.0}, ClassWidth{"highway", "tertiary_link", 5.0},
    ClassWidth{"highway", "unclassified", 5.0},   ClassWidth{"highway", "residential", 5.5},
    ClassWidth{"highway", "living_street", 4.5},  ClassWidth{"highway", "service", 3.5},
    ClassWidth{"highway", "track", 3.0},          ClassWidth{"highway", "cycleway", 2.0},
    ClassWidth{"highway", "footway", 1.5},        ClassWidth{"highway", "bridleway", 1.5},
    ClassWidth{"highway", "path", 1.5},           ClassWidth{"highway", "steps", 1.5},
    ClassWidth{"waterway", "river", 20.0},        ClassWidth{"waterway", "canal", 10.0},
    ClassWidth{"waterway", "stream", 3.0},        ClassWidth{"waterway", "drain", 2.0},
    ClassWidth{"waterway", "ditch", 1.5},         ClassWidth{"natural", "ridge", 40.0},
    ClassWidth{"natural", "arete", 15.0},         ClassWidth{"natural", "cliff", 10.0},
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// A positive number of metres: "7", "7.5", "7 m", "7m"; none for other units or words.
std::optional<double> parse_metres(std::string_view text) {
  text = trim(text);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || !std::isfinite(value) || value <= 0.0) return std::nullopt;
  const std::string_view unit = trim(text.substr(std::size_t(end - text.data())));
  if (!unit.empty() && unit != "m") return std::nullopt;
  return value;
}

std::optional<int> parse_int(std::string_view text) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

bool says_no(std::string_view value) {
  value = trim(value);
  return value.empty() || value == "no" || value == "0" || value == "false";
}

}  // namespace

std::optional<double> osm_class_width(std::string_view key, std::string_view value) {
  for (const ClassWidth& c : kClassWidths)
    if (c.key == key && c.value == value) return c.metres;
  return std::nullopt;
}

OsmWidth osm_width(const OsmWidthTags& tags) {
  OsmWidth out;
  auto note = [&](std::string problem) {
    out.problem += out.problem.empty() ? "" : "; ";
    out.problem += problem;
  };
  if (!trim(tags.width).empty()) {
    if (const auto metres = parse_metres(tags.width)) {
      out.metres = *metres;
      out.from = fmt::format("width={}", tags.width);
      return out;
    }
    note(fmt::format("width={} is not a positive number of metres", tags.width));
  }
  if (!trim(tags.lanes).empty()) {
    if (const auto lanes = parse_int(tags.lanes); lanes && *lanes > 0) {
      out.metres = *lanes * kOsmLaneWidth;
      out.from = fmt::format("lanes={}", tags.lanes);
      return out;
    }
    note(fmt::format("lanes={} is not a positive whole number", tags.lanes));
  }
  for (const auto& [key, value] :
       {std::pair<std::string_view, const std::string&>{"highway", tags.highway},
        {"waterway", tags.waterway},
        {"natural", tags.natural}}) {
    if (const auto metres = osm_class_width(key, value)) {
      out.metres = *metres;
      out.from = fmt::format("{}={}", key, value);
      return out;
    }
  }
  return out;
}

std::string_view osm_kind_of_key(std::string_view key) {
  if (key == "highway") return "road";
  if (key == "waterway") return "river";
  if (key == "natural") return "ridge";
  return "";
}

Structure osm_structure(std::string_view bridge, std::string_view tunnel) {
  if (!says_no(bridge)) return Structure::bridge;
  if (!says_no(tunnel) && trim(tunnel) != "building_passage") return Structure::tunnel;
  return Structure::ground;
}

std::optional<int> parse_osm_layer(std::string_view layer) {
  return parse_int(layer);
}

}  // namespace tw
