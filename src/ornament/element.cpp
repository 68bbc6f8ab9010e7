#include "ornament/element.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <set>

#include "core/error.hpp"
#include "core/file_io.hpp"

namespace tw {

namespace {

using Json = nlohmann::json;

// A JSON path and the file it came from, so every error names both.
struct Where {
  const std::string& origin;
  std::string key;
  Where at(const std::string& child) const {
    return {origin, key.empty() ? child : key + "." + child};
  }
  Where at(std::size_t index) const { return {origin, key + "[" + std::to_string(index) + "]"}; }
  template <class... Args>
  [[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) const {
    tw::fail("{}: key '{}': {}", origin, key, fmt::format(format, std::forward<Args>(args)...));
  }
};

const Json& member(const Json& object, const Where& where, const char* name) {
  if (!object.contains(name)) where.fail("missing '{}'", name);
  return object.at(name);
}

std::string string_of(const Json& value, const Where& where) {
  if (!value.is_string()) where.fail("expected a string");
  return value.get<std::string>();
}

double number_of(const Json& value, const Where& where) {
  if (!value.is_number()) where.fail("expected a number");
  const double v = value.get<double>();
  if (!std::isfinite(v)) where.fail("not a finite number");
  return v;
}

double optional_number(const Json& object, const Where& where, const char* name, double fallback) {
  return object.contains(name) ? number_of(object.at(name), where.at(name)) : fallback;
}

Vec2 point_of(const Json& value, const Where& where) {
  if (!value.is_array() || value.size() != 2) where.fail("expected a point [x, y]");
  return {number_of(value[0], where.at(0)), number_of(value[1], where.at(1))};
}

const Json& array_member(const Json& object, const Where& where, const char* name) {
  const Json& value = member(object, where, name);
  if (!value.is_array() || value.empty()) where.at(name).fail("expected a non-empty array");
  return value;
}

BezierSpline spline_of(const Json& value, const Where& where) {
  if (!value.is_object()) where.fail("expected an object");
  BezierSpline spline;
  spline.material = value.contains("material")
                        ? string_of(value.at("material"), where.at("material"))
                        : std::string();
  const Json& points = array_member(value, where, "points");
  if (points.size() < 4 || (points.size() - 1) % 3 != 0) {
    where.at("points").fail("a cubic spline needs 3n + 1 control points, not {}", points.size());
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    spline.control_points.push_back(point_of(points[i], where.at("points").at(i)));
  }
  // A spline whose control points coincide has no length: grown, it becomes a centerline of
  // one repeated point that fails far from this file.
  const Vec2 first = spline.control_points.front();
  if (std::all_of(spline.control_points.begin(), spline.control_points.end(),
                  [&](Vec2 p) { return distance(p, first) < 1e-9; })) {
    where.at("points").fail("all control points are at ({}, {}): a spline needs a length", first.x,
                            first.y);
  }
  return spline;
}

// The spline end at p (within 1e-9), so a growth point and its spline share the exact point.
std::optional<Vec2> spline_end_at(const DecorativeElement& element, Vec2 p) {
  for (const BezierSpline& s : element.splines) {
    for (Vec2 end : {s.control_points.front(), s.control_points.back()}) {
      if (distance(end, p) < 1e-9) return end;
    }
  }
  return std::nullopt;
}

DecorativeElement element_of(const Json& value, const Where& where) {
  if (!value.is_object()) where.fail("expected an object");
  DecorativeElement e;
  e.name = string_of(member(value, where, "name"), where.at("name"));
  e.tag = string_of(member(value, where, "tag"), where.at("tag"));
  const Json& splines = array_member(value, where, "splines");
  for (std::size_t i = 0; i < splines.size(); ++i) {
    e.splines.push_back(spline_of(splines[i], where.at("splines").at(i)));
  }
  // The element hangs from its origin: a spline must start or end there, or the ornament
  // would have a gap at every joint.
  if (!spline_end_at(e, {0.0, 0.0})) {
    where.at("splines").fail("no spline starts or ends at the origin [0, 0]");
  }
  if (value.contains("growth_points")) {
    const Where gw = where.at("growth_points");
    const Json& points = value.at("growth_points");
    if (!points.is_array()) gw.fail("expected an array");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Where w = gw.at(i);
      if (!points[i].is_object()) w.fail("expected an object");
      GrowthPoint g;
      g.tag = string_of(member(points[i], w, "tag"), w.at("tag"));
      g.at = point_of(member(points[i], w, "at"), w.at("at"));
      g.angle = optional_number(points[i], w, "angle_deg", 0.0) * std::numbers::pi / 180.0;
      g.priority = int(optional_number(points[i], w, "priority", 0.0));
      // Growth points sit on spline ends so the next element joins the line exactly there.
      const auto end = spline_end_at(e, g.at);
      if (!end) w.at("at").fail("not the end of one of the element's splines");
      g.at = *end;
      e.growth_points.push_back(g);
    }
  }
  if (value.contains("sizes")) {
    const Json& sizes = array_member(value, where, "sizes");
    e.sizes.clear();
    for (std::size_t i = 0; i < sizes.size(); ++i) {
      const double s = number_of(sizes[i], where.at("sizes").at(i));
      if (s <= 0.0) where.at("sizes").at(i).fail("a size must be > 0, not {}", s);
      e.sizes.push_back(s);
    }
  }
  const double jitter = optional_number(value, where, "rotation_jitter_deg", 0.0);
  if (jitter < 0.0 || jitter > 180.0) {
    where.at("rotation_jitter_deg").fail("must be in [0, 180], not {}", jitter);
  }
  e.rotation_jitter = jitter * std::numbers::pi / 180.0;
  return e;
}

}  // namespace

ElementSet parse_element_set(const std::string& text, const std::string& origin) {
  Json root;
  try {
    root = Json::parse(text);
  } catch (const Json::exception& e) {  // parse_error, and out_of_range for 1e400
    // nlohmann's text without its "[json.exception.parse_error.101] parse error at ..." prefix.
    std::string reason = e.what();
    if (const std::size_t end = reason.find("] "); reason.starts_with("[json.exception."))
      reason.erase(0, end + 2);
    if (const std::size_t colon = reason.find(": "); reason.starts_with("parse error"))
      reason.erase(0, colon + 2);
    const auto* parse = dynamic_cast<const Json::parse_error*>(&e);
    fail("{}: not valid JSON{}: {}; give an element set (samples/ornaments/*.json)", origin,
         parse ? fmt::format(" at byte {}", parse->byte) : std::string(), reason);
  }
  const Where top{origin, ""};
  if (!root.is_object()) fail("{}: expected a JSON object", origin);
  ElementSet set;
  set.name = string_of(member(root, top, "name"), top.at("name"));
  set.kind = string_of(member(root, top, "kind"), top.at("kind"));
  static const std::set<std::string> kinds{"hedge", "wall", "trail", "ditch"};
  if (!kinds.contains(set.kind)) {
    top.at("kind").fail("'{}' is not one of hedge, wall, trail, ditch", set.kind);
  }
  set.scale_m = optional_number(root, top, "scale_m", set.scale_m);
  if (set.scale_m <= 0.0) top.at("scale_m").fail("must be > 0, not {}", set.scale_m);
  set.clearance_m = optional_number(root, top, "clearance_m", 0.0);
  if (set.clearance_m < 0.0) top.at("clearance_m").fail("must be >= 0, not {}", set.clearance_m);
  const Json& elements = array_member(root, top, "elements");
  std::set<std::string> tags, names;
  for (std::size_t i = 0; i < elements.size(); ++i) {
    set.elements.push_back(element_of(elements[i], top.at("elements").at(i)));
    if (!names.insert(set.elements.back().name).second) {
      top.at("elements").at(i).at("name").fail("'{}' names two elements", set.elements.back().name);
    }
    tags.insert(set.elements.back().tag);
  }
  set.seed_tag = string_of(member(root, top, "seed_tag"), top.at("seed_tag"));
  if (!tags.contains(set.seed_tag))
    top.at("seed_tag").fail("no element has tag '{}'", set.seed_tag);
  // A growth point whose tag no element answers would silently never grow.
  for (std::size_t i = 0; i < set.elements.size(); ++i) {
    const auto& points = set.elements[i].growth_points;
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (!tags.contains(points[j].tag)) {
        top.at("elements")
            .at(i)
            .at("growth_points")
            .at(j)
            .at("tag")
            .fail("no element has tag '{}'", points[j].tag);
      }
    }
  }
  return set;
}

ElementSet read_element_set(const std::filesystem::path& path) {
  return parse_element_set(read_file_bytes(path), path.string());
}

std::vector<int> elements_with_tag(const ElementSet& set, const std::string& tag) {
  std::vector<int> out;
  for (std::size_t i = 0; i < set.elements.size(); ++i) {
    if (set.elements[i].tag == tag) out.push_back(int(i));
  }
  return out;
}

std::vector<Vec2> planar_polyline(const BezierSpline& spline, int per_segment) {
  const auto& c = spline.control_points;
  std::vector<Vec2> out{c.front()};
  for (std::size_t s = 0; s + 3 < c.size(); s += 3) {
    for (int k = 1; k <= per_segment; ++k) {
      const double t = double(k) / per_segment, u = 1.0 - t;
      out.push_back(c[s] * (u * u * u) + c[s + 1] * (3 * u * u * t) + c[s + 2] * (3 * u * t * t) +
                    c[s + 3] * (t * t * t));
    }
  }
  return out;
}

}  // namespace tw
