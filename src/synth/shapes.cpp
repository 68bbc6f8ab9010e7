#include "synth/shapes.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace tw {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kSamples = 240;

void add_arc(Curve& c, Vec2 centre, double radius, double from, double to, int samples) {
  for (int i = 0; i <= samples; ++i) {
    const double a = from + (to - from) * i / samples;
    const Vec2 p = centre + Vec2{std::cos(a), std::sin(a)} * radius;
    if (c.points.empty() || distance(c.points.back(), p) > 1e-9) c.points.push_back(p);
  }
}

}  // namespace

Curve make_shape(const std::string& name, double L) {
  if (!(L > 0.0)) fail("shape \"{}\": length scale must be > 0 (got {})", name, L);
  Curve c;
  if (name == "line") {
    for (int i = 0; i <= kSamples; ++i) c.points.push_back({L * i / kSamples, 0.0});
  } else if (name == "arc") {
    add_arc(c, {0.0, 0.0}, L / 2, kPi, 0.0, kSamples);  // clockwise over the top
  } else if (name == "s-curve") {
    add_arc(c, {0.0, 0.0}, L / 4, kPi, 0.0, kSamples / 2);
    add_arc(c, {L / 2, 0.0}, L / 4, kPi, 2 * kPi, kSamples / 2);
  } else if (name == "circle") {
    add_arc(c, {0.0, 0.0}, L / 2, 0.0, 2 * kPi * (1.0 - 1.0 / kSamples), kSamples - 1);
    c.closed = true;
  } else if (name == "heart") {
    // The classic heart curve, scaled to about L wide; walked clockwise.
    for (int i = 0; i < kSamples; ++i) {
      const double t = -2 * kPi * i / kSamples;
      const double x = 16 * std::pow(std::sin(t), 3);
      const double y =
          13 * std::cos(t) - 5 * std::cos(2 * t) - 2 * std::cos(3 * t) - std::cos(4 * t);
      c.points.push_back(Vec2{x, y} * (L / 32.0));
    }
    c.closed = true;
  } else if (name == "hairpin") {
    const double gap = 0.12 * L;
    for (int i = 0; i <= kSamples / 2; ++i) c.points.push_back({L * i / (kSamples / 2), 0.0});
    add_arc(c, {L, gap / 2}, gap / 2, -kPi / 2, kPi / 2, 24);
    for (int i = 1; i <= kSamples / 2; ++i) c.points.push_back({L - L * i / (kSamples / 2), gap});
  } else {
    fail("unknown shape \"{}\" (known: line, arc, s-curve, circle, heart, hairpin)", name);
  }
  return c;
}

}  // namespace tw
