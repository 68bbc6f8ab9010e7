#include "ornament/surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "ornament/detail/surface_impl.hpp"

namespace tw {

using detail::Vec3;

namespace {

double cross2(Vec3 a, Vec3 b) {
  return a.x * b.y - a.y * b.x;
}

// The face across local edge e (0: A->B, 1: B->C, 2: C->A) and that edge's index in it;
// {-1, -1} at the mesh's border. See surface_impl.hpp for the layout.
std::pair<int, int> across(const TerrainSurface::Impl& s, int face, int e) {
  const int cell = face / 2, i = cell % s.cells_x(), j = cell / s.cells_x();
  const auto face_of = [&](int ci, int cj, int k) { return 2 * (cj * s.cells_x() + ci) + k; };
  if (face % 2 == 0) {
    if (e == 0) return i > 0 ? std::pair{face_of(i - 1, j, 1), 1} : std::pair{-1, -1};
    if (e == 1) return j + 1 < s.ny - 1 ? std::pair{face_of(i, j + 1, 1), 2} : std::pair{-1, -1};
    return {face_of(i, j, 1), 0};
  }
  if (e == 0) return {face_of(i, j, 0), 2};
  if (e == 1) return i + 1 < s.nx - 1 ? std::pair{face_of(i + 1, j, 0), 0} : std::pair{-1, -1};
  return j > 0 ? std::pair{face_of(i, j - 1, 0), 1} : std::pair{-1, -1};
}

Vec3 face_normal(const TerrainSurface::Impl& s, int face) {
  const auto v = s.face_vertices(face);
  const Vec3 a = s.vertex(v[0]);
  return detail::unit(detail::cross(s.vertex(v[1]) - a, s.vertex(v[2]) - a));
}

// The frame's axes in the tangent plane of its origin's face.
std::pair<Vec3, Vec3> frame_axes(const TerrainSurface::Impl& s, const SurfaceFrame& frame) {
  const Vec3 x = s.lift(frame.origin.face, frame.heading);
  return {x, detail::cross(face_normal(s, frame.origin.face), x)};
}

}  // namespace

TerrainSurface::TerrainSurface(const Raster<float>& heights, const GridSpec& grid,
                               const Window& window)
    : impl_(std::make_unique<Impl>()) {
  if (heights.width != window.width || heights.height != window.height) {
    fail("surface: heights are {}x{}, the window {}x{}", heights.width, heights.height,
         window.width, window.height);
  }
  if (window.width < 2 || window.height < 2) {
    fail("surface: a {}x{} window has no triangles", window.width, window.height);
  }
  for (float h : heights.pixels) {
    if (!std::isfinite(h)) fail("surface: a height is not finite (nodata must be filled first)");
  }
  Impl& s = *impl_;
  s.grid = grid;
  s.window = window;
  s.nx = window.width;
  s.ny = window.height;
  s.dx = grid.pixel_width;
  s.dy = grid.pixel_height;
  s.z = heights.pixels;
}

TerrainSurface::~TerrainSurface() = default;
TerrainSurface::TerrainSurface(TerrainSurface&&) noexcept = default;
TerrainSurface& TerrainSurface::operator=(TerrainSurface&&) noexcept = default;

const GridSpec& TerrainSurface::grid() const {
  return impl_->grid;
}
const Window& TerrainSurface::window() const {
  return impl_->window;
}
int TerrainSurface::vertex_count() const {
  return impl_->nx * impl_->ny;
}
int TerrainSurface::face_count() const {
  return 2 * (impl_->nx - 1) * (impl_->ny - 1);
}

std::optional<SurfacePoint> TerrainSurface::locate(Vec2 world) const {
  const Impl& s = *impl_;
  return s.locate_local(world - s.grid.pixel_centre_world(s.window.col0, s.window.row0));
}

Vec2 TerrainSurface::world(const SurfacePoint& p) const {
  return impl_->grid.pixel_centre_world(impl_->window.col0, impl_->window.row0) + p.local;
}

double TerrainSurface::height(const SurfacePoint& p) const {
  return impl_->position(p).z;
}

std::pair<int, int> TerrainSurface::pixel_of(const SurfacePoint& p) const {
  const Vec2 px = impl_->grid.world_to_pixel(world(p));
  return {int(std::floor(px.x)), int(std::floor(px.y))};
}

std::optional<TerrainSurface::Walk> TerrainSurface::straightest_geodesic(const SurfaceFrame& frame,
                                                                         Vec2 offset) const {
  const Impl& s = *impl_;
  const double length = tw::length(offset);
  const auto [ex, ey] = frame_axes(s, frame);
  if (length == 0.0) return Walk{frame.origin, frame.heading};
  Vec3 d = detail::unit(ex * offset.x + ey * offset.y);
  Vec3 p = s.position(frame.origin);
  int face = frame.origin.face, entry = -1;
  bool stuck = false;
  double left = length;
  // Each step crosses one triangle; a walk longer than the mesh's perimeter times its cells
  // means a degenerate loop, reported as a failed walk rather than a hang.
  for (int step = 0; step < 4 * (s.nx + s.ny) * 8 + 64; ++step) {
    const auto v = s.face_vertices(face);
    int exit = -1;
    double exit_s = std::numeric_limits<double>::infinity(), exit_u = 0.0;
    for (int e = 0; e < 3; ++e) {
      if (e == entry) continue;
      const Vec3 a = s.vertex(v[e]), edge = s.vertex(v[(e + 1) % 3]) - a;
      const double denom = cross2(d, edge);
      if (std::abs(denom) < 1e-15) continue;
      const double t = cross2(a - p, edge) / denom, u = cross2(a - p, d) / denom;
      if (t > 1e-12 && u >= -1e-9 && u <= 1.0 + 1e-9 && t < exit_s) {
        exit = e;
        exit_s = t;
        exit_u = std::clamp(u, 0.0, 1.0);
      }
    }
    if (exit < 0) {
      // On an edge or a vertex, heading out of this face at once: continue in the face the
      // heading enters, keeping the horizontal heading (through a vertex the tangent angle is
      // not defined; Polthier & Schmies split it, we keep the map direction).
      if (stuck) return std::nullopt;
      stuck = true;
      const Vec2 dxy = normalized(Vec2{d.x, d.y});
      const auto next = s.locate_local(Vec2{p.x, p.y} + dxy * (1e-7 * s.dx));
      if (!next || next->face == face) return std::nullopt;
      face = next->face;
      d = s.lift(face, dxy);
      entry = -1;
      continue;
    }
    stuck = false;
    if (left <= exit_s) {
      const Vec3 q = p + d * left;
      return Walk{SurfacePoint{face, {q.x, q.y}}, normalized(Vec2{d.x, d.y})};
    }
    const Vec3 a = s.vertex(v[exit]), edge = s.vertex(v[(exit + 1) % 3]) - a;
    p = a + edge * exit_u;  // on the edge exactly, so no drift accumulates
    left -= exit_s;
    const auto [next, next_entry] = across(s, face, exit);
    if (next < 0) return std::nullopt;  // left the window
    // Keep the angle to the edge: the direction's component along the edge is kept and the
    // rest turns into the next face's plane (unfolding about the edge).
    const Vec3 along = detail::unit(edge);
    const auto w = s.face_vertices(next);
    const Vec3 opposite = s.vertex(w[(next_entry + 2) % 3]) - a;
    const Vec3 inward = detail::unit(opposite - along * detail::dot(opposite, along));
    const double c = std::clamp(detail::dot(d, along), -1.0, 1.0);
    d = detail::unit(along * c + inward * std::sqrt(1.0 - c * c));
    face = next;
    entry = next_entry;
  }
  return std::nullopt;
}

std::optional<SurfacePoint> TerrainSurface::geodesic_lerp(const SurfacePoint& a,
                                                          const SurfacePoint& b, double t) const {
  const Impl& s = *impl_;
  if (a == b) return a;
  const Vec3 pa = s.position(a), pb = s.position(b);
  SurfaceFrame frame{a, normalized(b.local - a.local)};
  const auto [ex, ey] = frame_axes(s, frame);
  Vec2 offset{detail::norm(pb - pa), 0.0};
  const double scale = offset.x;
  // Newton on the exponential map with its differential taken as the identity (exact on a
  // plane, close on a smooth surface over the short spans of a subdivided spline).
  for (int iteration = 0;; ++iteration) {
    const auto walk = straightest_geodesic(frame, offset);
    if (!walk) return std::nullopt;
    const Vec3 miss = pb - s.position(walk->end);
    const double error = detail::norm(miss);
    if (error <= 1e-9 * (1.0 + scale)) break;
    if (iteration == 8) {
      if (error > 1e-3 * scale) return std::nullopt;
      break;
    }
    offset += Vec2{detail::dot(miss, ex), detail::dot(miss, ey)};
  }
  const auto walk = straightest_geodesic(frame, offset * t);
  if (!walk) return std::nullopt;
  return walk->end;
}

Vec2 TerrainSurface::contour_direction(const SurfacePoint& p) const {
  const Impl& s = *impl_;
  const auto gradient = [&](int i, int j) {
    const auto h = [&](int a, int b) {
      return double(
          s.z[std::size_t(std::clamp(b, 0, s.ny - 1)) * s.nx + std::clamp(a, 0, s.nx - 1)]);
    };
    const int i0 = std::max(i - 1, 0), i1 = std::min(i + 1, s.nx - 1);
    const int j0 = std::max(j - 1, 0), j1 = std::min(j + 1, s.ny - 1);
    return Vec2{(h(i1, j) - h(i0, j)) / ((i1 - i0) * s.dx),
                (h(i, j0) - h(i, j1)) / ((j1 - j0) * s.dy)};  // row j-1 is north
  };
  const double u = p.local.x / s.dx, v = -p.local.y / s.dy;
  const int i = std::clamp(int(u), 0, s.nx - 2), j = std::clamp(int(v), 0, s.ny - 2);
  const double fu = u - i, fv = v - j;
  const Vec2 g = gradient(i, j) * ((1 - fu) * (1 - fv)) + gradient(i + 1, j) * (fu * (1 - fv)) +
                 gradient(i, j + 1) * ((1 - fu) * fv) + gradient(i + 1, j + 1) * (fu * fv);
  if (tw::length(g) < 1e-9) return {};
  return normalized(perp(g));
}

double TerrainSurface::interpolate(const std::vector<double>& values, const SurfacePoint& p) const {
  const auto w = impl_->barycentric(p.face, p.local);
  const auto v = impl_->face_vertices(p.face);
  return w[0] * values[std::size_t(v[0])] + w[1] * values[std::size_t(v[1])] +
         w[2] * values[std::size_t(v[2])];
}

int TerrainSurface::nearest_vertex(const SurfacePoint& p) const {
  const Impl& s = *impl_;
  const int i = std::clamp(int(std::lround(p.local.x / s.dx)), 0, s.nx - 1);
  const int j = std::clamp(int(std::lround(-p.local.y / s.dy)), 0, s.ny - 1);
  return j * s.nx + i;
}

SurfacePoint TerrainSurface::vertex_point(int vertex) const {
  const Impl& s = *impl_;
  const Vec3 q = s.vertex(vertex);
  const int i = std::min(vertex % s.nx, s.nx - 2), j = std::min(vertex / s.nx, s.ny - 2);
  // Vertex (i, j) belongs to face k = 0 of its cell (or of the cell to its left/above at the
  // far borders, where it is still a corner of that face's triangle pair).
  const int k = (vertex % s.nx == s.nx - 1 && vertex / s.nx < s.ny - 1) ? 1 : 0;
  return {2 * (j * s.cells_x() + i) + k, {q.x, q.y}};
}

}  // namespace tw
