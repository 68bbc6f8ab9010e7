#pragma once
// A heightfield window as a triangle surface in its intrinsic metric (FloralSurf, Sections
// 3.2-3.3): one vertex per pixel centre, two triangles per cell. Straightest geodesics (the
// exponential map used to place an element's control points) walk the triangles directly;
// heat-method distances and exact shortest paths come from CGAL (Heat_method_3,
// Surface_mesh_shortest_path) on the same mesh. docs/ornaments.md cites both.
#include <memory>
#include <optional>
#include <vector>

#include "core/grid.hpp"
#include "core/vec2.hpp"

namespace tw {

// A point on the surface: its triangle and its position in the window's local metric frame
// (metres east and north of the first vertex; the height follows from the triangle).
struct SurfacePoint {
  int face = -1;
  Vec2 local;
  friend bool operator==(const SurfacePoint&, const SurfacePoint&) = default;
};

// A tangent frame: its x axis is `heading` (a horizontal direction, unit length) lifted into
// the tangent plane at `origin`; its y axis is the x axis turned +90 degrees about the normal.
struct SurfaceFrame {
  SurfacePoint origin;
  Vec2 heading{1.0, 0.0};
};

class TerrainSurface {
 public:
  // heights: the window's heights in metres (window-sized, every value finite), at least 2 x 2.
  TerrainSurface(const Raster<float>& heights, const GridSpec& grid, const Window& window);
  ~TerrainSurface();
  TerrainSurface(TerrainSurface&&) noexcept;
  TerrainSurface& operator=(TerrainSurface&&) noexcept;

  const GridSpec& grid() const;
  const Window& window() const;
  int vertex_count() const;
  int face_count() const;

  std::optional<SurfacePoint> locate(Vec2 world) const;  // nullopt outside the mesh
  Vec2 world(const SurfacePoint& p) const;
  double height(const SurfacePoint& p) const;
  // Pixel (col, row) of the grid under a point.
  std::pair<int, int> pixel_of(const SurfacePoint& p) const;

  // The straightest geodesic (Polthier & Schmies) from the frame's origin in the tangent
  // direction of `offset` (metres, frame coordinates), |offset| metres long: the exponential
  // map. Its end and the horizontal heading there; nullopt when it leaves the mesh.
  struct Walk {
    SurfacePoint end;
    Vec2 heading;
  };
  std::optional<Walk> straightest_geodesic(const SurfaceFrame& frame, Vec2 offset) const;
  // The point a fraction t of the way along the geodesic from a to b, found by shooting
  // straightest geodesics from a (Newton on the exponential map); nullopt when shooting fails.
  std::optional<SurfacePoint> geodesic_lerp(const SurfacePoint& a, const SurfacePoint& b,
                                            double t) const;
  // Unit horizontal direction along the contour at p (the height gradient turned +90 degrees,
  // bilinear over vertex gradients), or {0, 0} where the surface is flat.
  Vec2 contour_direction(const SurfacePoint& p) const;

  // Heat-method geodesic distance (Crane et al., CGAL Heat_method_3) from the nearest vertices
  // of `sources` to every vertex, in metres; +inf everywhere when sources is empty.
  std::vector<double> heat_distances(const std::vector<SurfacePoint>& sources) const;
  // The same on the part of the mesh inside `part` (vertex columns and rows of this surface's
  // window, at least 2 x 2, inside it) only: a mesh and factorization of its vertices, so the
  // cost follows the part, not the surface. Part-sized (row-major over `part`); sources outside
  // it are dropped (+inf everywhere when none is left). Its edge is the heat method's boundary,
  // so distances well inside it match the whole mesh's (tests/ornament/surface_test.cpp).
  std::vector<double> heat_distances(const std::vector<SurfacePoint>& sources,
                                     const Window& part) const;
  // A per-vertex field at a point (barycentric in its triangle).
  double interpolate(const std::vector<double>& vertex_values, const SurfacePoint& p) const;
  // The exact geodesic distance between two points (CGAL Surface_mesh_shortest_path; costly:
  // it expands over the whole mesh): a reference for tests and single queries.
  double shortest_path_length(const SurfacePoint& a, const SurfacePoint& b) const;
  // The vertex nearest a point, and a vertex's point on the surface.
  int nearest_vertex(const SurfacePoint& p) const;
  SurfacePoint vertex_point(int vertex) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tw
