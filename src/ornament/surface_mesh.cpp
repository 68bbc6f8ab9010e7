// The CGAL side of TerrainSurface: the grid triangulation as a CGAL::Surface_mesh, heat-method
// distances (Heat_method_3: two sparse solves per query after one factorization) and exact
// point-to-point geodesics (Surface_mesh_shortest_path, Xin & Wang's exact algorithm). One of
// the module's two CGAL translation units (segment_index.cpp is the other).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <algorithm>
#include <limits>
#include <mutex>
#include <set>

#include "core/error.hpp"
#include "ornament/detail/surface_impl.hpp"

namespace tw::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vertex = Mesh::Vertex_index;
using HeatMethod = CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<Mesh>;
using ShortestPathTraits = CGAL::Surface_mesh_shortest_path_traits<Kernel, Mesh>;
using ShortestPath = CGAL::Surface_mesh_shortest_path<ShortestPathTraits>;

struct CgalMesh {
  Mesh mesh;
  std::unique_ptr<HeatMethod> heat;
  std::mutex mutex;  // the heat solver keeps its source set between queries
};

void CgalMeshDeleter::operator()(CgalMesh* mesh) const {
  delete mesh;
}

std::unique_ptr<CgalMesh, CgalMeshDeleter> make_cgal_mesh(const TerrainSurface::Impl& s) {
  std::unique_ptr<CgalMesh, CgalMeshDeleter> out(new CgalMesh);
  Mesh& mesh = out->mesh;
  // Vertices and faces in the implicit layout's order, so CGAL's indices are ours.
  for (int v = 0; v < s.nx * s.ny; ++v) {
    const Vec3 p = s.vertex(v);
    mesh.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  }
  const int faces = 2 * (s.nx - 1) * (s.ny - 1);
  for (int f = 0; f < faces; ++f) {
    const auto v = s.face_vertices(f);
    mesh.add_face(Vertex(v[0]), Vertex(v[1]), Vertex(v[2]));
  }
  out->heat = std::make_unique<HeatMethod>(mesh);
  return out;
}

namespace {

// A point as CGAL's face location: barycentric weights in the order CGAL walks the face.
ShortestPath::Face_location location(const TerrainSurface::Impl& s, const Mesh& mesh,
                                     const SurfacePoint& p) {
  const Mesh::Face_index face(static_cast<Mesh::size_type>(p.face));
  const auto ours = s.face_vertices(p.face);
  const auto weights = s.barycentric(p.face, p.local);
  ShortestPath::Barycentric_coordinates b{0, 0, 0};
  int k = 0;
  for (Vertex v : CGAL::vertices_around_face(mesh.halfedge(face), mesh)) {
    for (int m = 0; m < 3; ++m) {
      if (int(v.idx()) == ours[m]) b[k] = weights[m];
    }
    ++k;
  }
  return {face, b};
}

}  // namespace

}  // namespace tw::detail

namespace tw {

std::vector<double> TerrainSurface::heat_distances(const std::vector<SurfacePoint>& sources) const {
  std::vector<double> out(std::size_t(vertex_count()), std::numeric_limits<double>::infinity());
  if (sources.empty()) return out;
  std::set<int> vertices;
  for (const SurfacePoint& p : sources) vertices.insert(nearest_vertex(p));
  detail::CgalMesh& cgal = const_cast<detail::CgalMesh&>(impl_->cgal());
  std::lock_guard lock(cgal.mutex);
  cgal.heat->clear_sources();
  for (int v : vertices) cgal.heat->add_source(detail::Vertex(v));
  auto distance = cgal.mesh.add_property_map<detail::Vertex, double>("v:heat", 0.0).first;
  cgal.heat->estimate_geodesic_distances(distance);
  for (detail::Vertex v : cgal.mesh.vertices()) out[v.idx()] = std::max(0.0, distance[v]);
  cgal.mesh.remove_property_map(distance);
  return out;
}

std::vector<double> TerrainSurface::heat_distances(const std::vector<SurfacePoint>& sources,
                                                   const Window& part) const {
  const Impl& s = *impl_;
  if (part.col0 < 0 || part.row0 < 0 || part.width < 2 || part.height < 2 ||
      part.col0 + part.width > s.nx || part.row0 + part.height > s.ny) {
    fail("surface: part {}+{}x{}+{} is not a 2 x 2 or larger part of the {}x{} mesh", part.col0,
         part.width, part.row0, part.height, s.nx, s.ny);
  }
  std::vector<double> out(std::size_t(part.width) * part.height,
                          std::numeric_limits<double>::infinity());
  std::set<int> vertices;  // in the part's numbering
  for (const SurfacePoint& p : sources) {
    const int v = nearest_vertex(p), i = v % s.nx - part.col0, j = v / s.nx - part.row0;
    if (i >= 0 && j >= 0 && i < part.width && j < part.height) vertices.insert(j * part.width + i);
  }
  if (vertices.empty()) return out;
  // The part as a surface of its own: same spacing, its heights; its local coordinates shift by
  // whole vertices, which distances do not see.
  Impl sub;
  sub.grid = s.grid;
  sub.window = {s.window.col0 + part.col0, s.window.row0 + part.row0, part.width, part.height};
  sub.nx = part.width;
  sub.ny = part.height;
  sub.dx = s.dx;
  sub.dy = s.dy;
  sub.z.reserve(out.size());
  for (int j = part.row0; j < part.row0 + part.height; ++j)
    for (int i = part.col0; i < part.col0 + part.width; ++i)
      sub.z.push_back(s.z[std::size_t(j) * s.nx + i]);
  const auto cgal = detail::make_cgal_mesh(sub);
  for (int v : vertices) cgal->heat->add_source(detail::Vertex(v));
  auto distance = cgal->mesh.add_property_map<detail::Vertex, double>("v:heat", 0.0).first;
  cgal->heat->estimate_geodesic_distances(distance);
  for (detail::Vertex v : cgal->mesh.vertices()) out[v.idx()] = std::max(0.0, distance[v]);
  return out;
}

double TerrainSurface::shortest_path_length(const SurfacePoint& a, const SurfacePoint& b) const {
  const detail::CgalMesh& cgal = impl_->cgal();
  detail::ShortestPath paths(cgal.mesh);
  paths.add_source_point(detail::location(*impl_, cgal.mesh, a));
  return paths
      .shortest_distance_to_source_points(detail::location(*impl_, cgal.mesh, b).first,
                                          detail::location(*impl_, cgal.mesh, b).second)
      .first;
}

}  // namespace tw
