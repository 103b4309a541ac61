#pragma once
//! \file cgal_surface_mesh.h
//! \brief Triangle surfaces to and from CGAL's Surface_mesh (inexact-constructions kernel).
//! Header only, for the files that call CGAL: include it only from targets that link CGAL.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <optional>
#include <vector>

#include "core/types.h"

namespace polycube::core::cgal {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

//! The surface as a CGAL surface mesh, vertex and face numbers kept; nullopt when a triangle
//! cannot be attached (not manifold, or not consistently oriented).
inline std::optional<SurfaceMesh> to_surface_mesh(const TriMesh& m) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(m.points.size());
  for (const Vec3& p : m.points) v.push_back(sm.add_vertex({p.x(), p.y(), p.z()}));
  for (const Tri& t : m.cells)
    if (sm.add_face(v[t[0]], v[t[1]], v[t[2]]) == SurfaceMesh::null_face()) return std::nullopt;
  return sm;
}

//! The surface mesh back as a TriMesh: removed vertices and faces skipped, the others in their
//! index order.
inline TriMesh to_tri_mesh(const SurfaceMesh& sm) {
  TriMesh m;
  std::vector<int> id(sm.number_of_vertices() + sm.number_of_removed_vertices(), -1);
  for (auto v : sm.vertices()) {
    id[v.idx()] = static_cast<int>(m.points.size());
    const auto& p = sm.point(v);
    m.points.emplace_back(p.x(), p.y(), p.z());
  }
  for (auto f : sm.faces()) {
    Tri t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) t[static_cast<std::size_t>(k++)] = id[v.idx()];
    m.cells.push_back(t);
  }
  return m;
}

}  // namespace polycube::core::cgal
