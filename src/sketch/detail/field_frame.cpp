#include "sketch/detail/field_frame.hpp"

#include <algorithm>
#include <cmath>

namespace tw::detail {

namespace {

// The field's direction at p (across it when `across`), signed to agree with `heading`: the
// field is sign-free (an angle modulo pi). Where it is undefined, the heading goes on.
Vec2 oriented(const LeadField& field, Vec2 p, Vec2 heading, bool across) {
  const std::optional<double> angle = field(p);
  if (!angle || !std::isfinite(*angle)) return heading;
  Vec2 d{std::cos(*angle), std::sin(*angle)};
  if (across) d = perp(d);
  return dot(d, heading) < 0.0 ? -d : d;
}

// One midpoint-rule step of `h` metres: the explicit Euler step drifts off a circle by O(h)
// per turn, the midpoint rule by O(h^2).
Vec2 advance(const LeadField& field, Vec2 p, Vec2& heading, double h, bool across) {
  const Vec2 first = oriented(field, p, heading, across);
  heading = oriented(field, p + first * (0.5 * h), first, across);
  return p + heading * h;
}

}  // namespace

FieldFrame::FieldFrame(Vec2 anchor, double bearing, const LeadField& field, double reach,
                       double step)
    : step_(step) {
  half_ = std::max(1, int(std::ceil(reach / step)));
  side_ = std::size_t(2 * half_ + 1);
  nodes_.resize(side_ * side_);
  const auto at = [&](int i, int j) -> Vec2& {
    return nodes_[std::size_t(j + half_) * side_ + std::size_t(i + half_)];
  };
  // The axis, both ways from the anchor, with its tangents (pointing towards +u).
  std::vector<Vec2> tangent(side_);
  const Vec2 start = oriented(field, anchor, {std::cos(bearing), std::sin(bearing)}, false);
  at(0, 0) = anchor;
  tangent[std::size_t(half_)] = start;
  for (const int sign : {1, -1}) {
    Vec2 p = anchor, heading = start * double(sign);
    for (int k = 1; k <= half_; ++k) {
      p = advance(field, p, heading, step, false);
      at(sign * k, 0) = p;
      tangent[std::size_t(half_ + sign * k)] = heading * double(sign);
    }
  }
  // From every axis node, the curve across the field, +v to the left of the axis.
  for (int i = -half_; i <= half_; ++i) {
    const Vec2 normal = perp(tangent[std::size_t(i + half_)]);
    for (const int sign : {1, -1}) {
      Vec2 p = at(i, 0), heading = normal * double(sign);
      for (int k = 1; k <= half_; ++k) {
        p = advance(field, p, heading, step, true);
        at(i, sign * k) = p;
      }
    }
  }
}

Vec2 FieldFrame::to_world(Vec2 uv) const {
  const double x = uv.x / step_ + half_, y = uv.y / step_ + half_;
  const double last = double(side_) - 2.0;
  const double fx = std::clamp(std::floor(x), 0.0, last), fy = std::clamp(std::floor(y), 0.0, last);
  const int i = int(fx), j = int(fy);
  const double tx = x - fx, ty = y - fy;  // outside [0, 1] beyond the lattice: extrapolated
  const Vec2 a = lerp(node(i, j), node(i + 1, j), tx);
  const Vec2 b = lerp(node(i, j + 1), node(i + 1, j + 1), tx);
  return lerp(a, b, ty);
}

void FieldFrame::extent_within(Vec2 lo, Vec2 hi, Vec2& uv_lo, Vec2& uv_hi) const {
  uv_lo = uv_hi = Vec2{};
  for (std::size_t j = 0; j < side_; ++j)
    for (std::size_t i = 0; i < side_; ++i) {
      const Vec2 p = nodes_[j * side_ + i];
      if (p.x < lo.x || p.y < lo.y || p.x > hi.x || p.y > hi.y) continue;
      const Vec2 uv{(double(i) - half_) * step_, (double(j) - half_) * step_};
      uv_lo = {std::min(uv_lo.x, uv.x), std::min(uv_lo.y, uv.y)};
      uv_hi = {std::max(uv_hi.x, uv.x), std::max(uv_hi.y, uv.y)};
    }
  // The box's edges may fall between nodes: one step more on every side.
  uv_lo = uv_lo - Vec2{step_, step_};
  uv_hi = uv_hi + Vec2{step_, step_};
}

}  // namespace tw::detail
