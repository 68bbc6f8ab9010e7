#pragma once
// The implicit grid triangulation shared by the walk (surface.cpp) and the CGAL mesh
// (surface_mesh.cpp). Vertex (i, j) is window pixel (i, j)'s centre at local (i dx, -j dy);
// cell (i, j) splits along the diagonal (i, j)-(i+1, j+1) into face 2 (j (nx-1) + i) + k, k = 0
// below the diagonal (t >= s), k = 1 above it.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "ornament/surface.hpp"

namespace tw::detail {

struct Vec3 {
  double x = 0, y = 0, z = 0;
  friend Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  friend Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  friend Vec3 operator*(Vec3 a, double s) { return {a.x * s, a.y * s, a.z * s}; }
};
inline double dot(Vec3 a, Vec3 b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) {
  return std::sqrt(dot(a, a));
}
inline Vec3 unit(Vec3 a) {
  return a * (1.0 / norm(a));
}

// CGAL's Surface_mesh with its heat-method solver, behind a pointer (surface_mesh.cpp).
struct CgalMesh;
struct CgalMeshDeleter {
  void operator()(CgalMesh* mesh) const;
};
std::unique_ptr<CgalMesh, CgalMeshDeleter> make_cgal_mesh(const TerrainSurface::Impl& surface);

}  // namespace tw::detail

namespace tw {

struct TerrainSurface::Impl {
  GridSpec grid;
  Window window;
  int nx = 0, ny = 0;
  double dx = 1, dy = 1;
  std::vector<float> z;  // row-major, nx * ny
  // Built on the first distance query (the heat method factors its matrices once).
  mutable std::once_flag mesh_once;
  mutable std::unique_ptr<detail::CgalMesh, detail::CgalMeshDeleter> mesh;
  const detail::CgalMesh& cgal() const {
    std::call_once(mesh_once, [this] { mesh = detail::make_cgal_mesh(*this); });
    return *mesh;
  }

  int cells_x() const { return nx - 1; }
  detail::Vec3 vertex(int i, int j) const {
    return {i * dx, -j * dy, double(z[std::size_t(j) * nx + i])};
  }
  detail::Vec3 vertex(int v) const { return vertex(v % nx, v / nx); }
  // The face's vertex ids in counter-clockwise order (A, B, C as in surface.cpp's edge table).
  std::array<int, 3> face_vertices(int face) const {
    const int cell = face / 2, i = cell % cells_x(), j = cell / cells_x();
    const int v00 = j * nx + i, v01 = v00 + nx, v11 = v01 + 1, v10 = v00 + 1;
    return face % 2 == 0 ? std::array<int, 3>{v00, v01, v11} : std::array<int, 3>{v00, v11, v10};
  }
  // Barycentric coordinates of a local point in a face (in face_vertices order).
  std::array<double, 3> barycentric(int face, Vec2 p) const {
    const auto v = face_vertices(face);
    const detail::Vec3 a = vertex(v[0]), b = vertex(v[1]), c = vertex(v[2]);
    const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    const double wb = ((p.x - a.x) * (c.y - a.y) - (c.x - a.x) * (p.y - a.y)) / det;
    const double wc = ((b.x - a.x) * (p.y - a.y) - (p.x - a.x) * (b.y - a.y)) / det;
    return {1.0 - wb - wc, wb, wc};
  }
  std::optional<SurfacePoint> locate_local(Vec2 local) const {
    const double u = local.x / dx, v = -local.y / dy;
    if (!(u >= 0.0 && v >= 0.0 && u <= nx - 1 && v <= ny - 1)) return std::nullopt;
    const int i = std::min(int(u), nx - 2), j = std::min(int(v), ny - 2);
    const int k = (v - j) >= (u - i) ? 0 : 1;
    return SurfacePoint{2 * (j * cells_x() + i) + k, local};
  }
  // A horizontal direction lifted into a face's plane, unit length.
  detail::Vec3 lift(int face, Vec2 h) const {
    const auto v = face_vertices(face);
    const detail::Vec3 a = vertex(v[0]);
    const detail::Vec3 n = detail::cross(vertex(v[1]) - a, vertex(v[2]) - a);
    return detail::unit({h.x, h.y, -(n.x * h.x + n.y * h.y) / n.z});
  }
  detail::Vec3 position(const SurfacePoint& p) const {
    const auto w = barycentric(p.face, p.local);
    const auto v = face_vertices(p.face);
    return {
        p.local.x, p.local.y,
        w[0] * z[std::size_t(v[0])] + w[1] * z[std::size_t(v[1])] + w[2] * z[std::size_t(v[2])]};
  }
};

}  // namespace tw
