#include "network/detail/svg_lines.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace tw::detail {

namespace {

std::string attribute(const std::string& tag, const std::string& name) {
  std::size_t at = 0;
  while ((at = tag.find(name, at)) != std::string::npos) {
    const bool word_start = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
    std::size_t eq = at + name.size();
    while (eq < tag.size() && std::isspace(static_cast<unsigned char>(tag[eq]))) ++eq;
    if (word_start && eq < tag.size() && tag[eq] == '=') {
      std::size_t q = eq + 1;
      while (q < tag.size() && std::isspace(static_cast<unsigned char>(tag[q]))) ++q;
      if (q >= tag.size() || (tag[q] != '"' && tag[q] != '\'')) return {};  // not XML: no value
      const std::size_t end = tag.find(tag[q], q + 1);
      return tag.substr(q + 1, end == std::string::npos ? std::string::npos : end - q - 1);
    }
    at += name.size();
  }
  return {};
}

// Numbers of a points list or path data, with the commands as separate tokens.
class Scanner {
 public:
  Scanner(const std::string& text, const std::string& where) : s_(text), where_(where) {}
  void skip() {
    while (i_ < s_.size() && (std::isspace(static_cast<unsigned char>(s_[i_])) || s_[i_] == ','))
      ++i_;
  }
  bool done() {
    skip();
    return i_ >= s_.size();
  }
  bool at_command() {
    skip();
    return i_ < s_.size() && std::isalpha(static_cast<unsigned char>(s_[i_])) && s_[i_] != 'e' &&
           s_[i_] != 'E';
  }
  char command() { return s_[i_++]; }
  bool number(double& v) {
    skip();
    const char* begin = s_.c_str() + i_;
    char* end = nullptr;
    v = std::strtod(begin, &end);
    if (end == begin) return false;
    // strtod reads "inf", "nan" and 1e999 too: no coordinate of a drawing.
    if (!std::isfinite(v))
      fail("{}: a number out of range: {}", where_, std::string(begin, std::size_t(end - begin)));
    i_ += std::size_t(end - begin);
    return true;
  }

 private:
  const std::string& s_;
  const std::string& where_;
  std::size_t i_ = 0;
};

void flatten_cubic(std::vector<Vec2>& out, Vec2 p0, Vec2 p1, Vec2 p2, Vec2 p3) {
  constexpr int steps = 16;
  for (int k = 1; k <= steps; ++k) {
    const double t = double(k) / steps, u = 1.0 - t;
    out.push_back(u * u * u * p0 + 3 * u * u * t * p1 + 3 * u * t * t * p2 + t * t * t * p3);
  }
}

std::vector<std::vector<Vec2>> path_lines(const std::string& d, const std::string& where) {
  std::vector<std::vector<Vec2>> out;
  Scanner scan(d, where);
  Vec2 pen, start, control;
  char cmd = 0, previous = 0;
  const auto need = [&](double& v) {
    if (!scan.number(v)) fail("{}: path data: a number expected after '{}'", where, cmd);
  };
  while (!scan.done()) {
    if (scan.at_command())
      cmd = scan.command();
    else if (cmd == 0)
      fail("{}: path data does not start with a command", where);
    if (out.empty() && std::toupper(static_cast<unsigned char>(cmd)) != 'M')
      fail("{}: path data must start with a moveto (M or m), not '{}'", where, cmd);
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const Vec2 base = rel ? pen : Vec2{};
    double x = 0, y = 0;
    switch (std::toupper(static_cast<unsigned char>(cmd))) {
      case 'M':
        need(x), need(y);
        pen = start = base + Vec2{x, y};
        out.push_back({pen});
        cmd = rel ? 'l' : 'L';  // further pairs are line-tos
        break;
      case 'L':
        need(x), need(y);
        pen = base + Vec2{x, y};
        out.back().push_back(pen);
        break;
      case 'H':
        need(x);
        pen = {(rel ? pen.x : 0.0) + x, pen.y};
        out.back().push_back(pen);
        break;
      case 'V':
        need(y);
        pen = {pen.x, (rel ? pen.y : 0.0) + y};
        out.back().push_back(pen);
        break;
      case 'C':
      case 'S': {
        Vec2 c1;
        if (std::toupper(static_cast<unsigned char>(cmd)) == 'C') {
          need(x), need(y);
          c1 = base + Vec2{x, y};
        } else {
          const char p = char(std::toupper(static_cast<unsigned char>(previous)));
          c1 = (p == 'C' || p == 'S') ? 2.0 * pen - control : pen;
        }
        double x2, y2;
        need(x2), need(y2), need(x), need(y);
        control = base + Vec2{x2, y2};
        const Vec2 end = base + Vec2{x, y};
        flatten_cubic(out.back(), pen, c1, control, end);
        pen = end;
        break;
      }
      case 'Q':
      case 'T': {
        Vec2 q;
        if (std::toupper(static_cast<unsigned char>(cmd)) == 'Q') {
          need(x), need(y);
          q = base + Vec2{x, y};
        } else {
          const char p = char(std::toupper(static_cast<unsigned char>(previous)));
          q = (p == 'Q' || p == 'T') ? 2.0 * pen - control : pen;
        }
        need(x), need(y);
        const Vec2 end = base + Vec2{x, y};
        control = q;
        flatten_cubic(out.back(), pen, pen + (2.0 / 3.0) * (q - pen), end + (2.0 / 3.0) * (q - end),
                      end);
        pen = end;
        break;
      }
      case 'Z':
        out.back().push_back(start);
        pen = start;
        break;
      default:
        fail("{}: path command '{}' is not supported (lines and Bézier curves only)", where, cmd);
    }
    previous = cmd;
  }
  return out;
}

std::vector<Vec2> points_list(const std::string& text, const std::string& where) {
  Scanner scan(text, where);
  std::vector<Vec2> pts;
  double x, y;
  while (!scan.done()) {
    if (!scan.number(x) || !scan.number(y)) fail("{}: points: pairs of numbers expected", where);
    pts.push_back({x, y});
  }
  return pts;
}

}  // namespace

std::vector<SvgLine> read_svg_lines(const std::string& path, const std::string& subject) {
  std::ifstream in(path);
  if (!in) fail("{} {}: cannot read", subject, path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  std::vector<SvgLine> out;
  std::int64_t element = 0;
  std::size_t at = 0;
  while ((at = text.find('<', at)) != std::string::npos) {
    if (text.compare(at, 4, "<!--") == 0) {
      at = text.find("-->", at);
      if (at == std::string::npos) break;
      continue;
    }
    const std::size_t end = text.find('>', at);
    if (end == std::string::npos) break;
    const std::string tag = text.substr(at + 1, end - at - 1);
    at = end;
    if (tag.empty() || tag[0] == '/' || tag[0] == '?' || tag[0] == '!') continue;
    std::size_t name_end = 0;
    while (name_end < tag.size() && !std::isspace(static_cast<unsigned char>(tag[name_end])) &&
           tag[name_end] != '/')
      ++name_end;
    const std::string name = tag.substr(0, name_end);
    static const char* const ignored[] = {"svg",          "g",        "defs",  "title",
                                          "desc",         "metadata", "style", "sodipodi:namedview",
                                          "inkscape:grid"};
    bool skip = false;
    for (const char* i : ignored) skip = skip || name == i;
    if (!attribute(tag, "transform").empty())
      fail(
          "{} {}: element {} <{}>: transform attributes are not supported (apply them first, "
          "e.g. Inkscape's 'Apply Transform')",
          subject, path, element, name);
    if (skip) continue;
    const std::string where = fmt::format("{} {}: element {} <{}>", subject, path, element, name);
    if (name == "path") {
      for (auto& line : path_lines(attribute(tag, "d"), where))
        if (line.size() >= 2) out.push_back({element, std::move(line)});
    } else if (name == "line") {
      const auto num = [&](const char* a) {
        const std::string text = attribute(tag, a);
        Scanner scan(text, where);
        double v = 0.0;
        if (!text.empty() && !scan.number(v)) fail("{}: {}: a number expected", where, a);
        return v;
      };
      out.push_back({element, {{num("x1"), num("y1")}, {num("x2"), num("y2")}}});
    } else if (name == "polyline" || name == "polygon") {
      std::vector<Vec2> pts = points_list(attribute(tag, "points"), where);
      if (name == "polygon" && !pts.empty()) pts.push_back(pts.front());
      if (pts.size() >= 2) out.push_back({element, std::move(pts)});
    } else {
      fail("{}: not supported (only path, line, polyline and polygon are network lines)", where);
    }
    ++element;
  }
  return out;
}

}  // namespace tw::detail
