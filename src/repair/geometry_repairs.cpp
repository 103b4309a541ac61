//! The repairs built on CGAL (see geometry_repairs.h).
#include "repair/geometry_repairs.h"

#include "core/cgal_surface_mesh.h"
#include "core/topology.h"

#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/alpha_wrap_3.h>

#include <algorithm>
#include <array>
#include <iterator>
#include <optional>
#include <vector>

namespace polycube::repair::detail {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = core::cgal::Kernel;
using SurfaceMesh = core::cgal::SurfaceMesh;

using core::cgal::to_surface_mesh;
using core::cgal::to_tri_mesh;

//! Whether every closed component encloses a positive volume and there is one component: then
//! the surface bounds its volume as it is (the common case, decided without CGAL).
bool one_outward_shell(const core::TriMesh& m, const core::SurfaceReport& r) {
  return r.components == 1 && r.closed && core::signed_volume(m) > 0;
}

}  // namespace

void orient_to_bound_volume(core::TriMesh& mesh, RepairReport& report) {
  const core::SurfaceReport r = core::analyze_surface(mesh);
  if (!r.manifold || !r.orientable) return;  // the check after the repairs says why
  if (r.consistently_oriented && (!r.closed || one_outward_shell(mesh, r))) return;
  const std::vector<core::Tri> before = mesh.cells;
  if (!r.consistently_oriented) core::orient_consistently(mesh);
  if (r.closed) {
    // Nested shells (cavities) face into the cavity: CGAL decides which shell is inside which.
    std::optional<SurfaceMesh> sm = to_surface_mesh(mesh);
    if (sm && !PMP::does_self_intersect(*sm)) {
      PMP::orient_to_bound_a_volume(*sm);
      std::size_t i = 0;
      for (auto f : sm->faces()) {
        core::Tri& t = mesh.cells[i++];
        // A turned face keeps its first vertex (as core::orient_consistently does).
        for (auto h : CGAL::halfedges_around_face(sm->halfedge(f), *sm))
          if (static_cast<int>(sm->source(h).idx()) == t[0] && static_cast<int>(sm->target(h).idx()) == t[2])
            t = {t[0], t[2], t[1]};
      }
    }
  }
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (mesh.cells[i] == before[i]) continue;
    ++report.turned_triangles;
    RepairReport::note(report.sites.turned, centre(mesh.points, before[i]));
  }
}

void fill_holes(core::TriMesh& mesh, int max_edges, RepairReport& report) {
  std::optional<SurfaceMesh> sm = to_surface_mesh(mesh);
  if (!sm) return;  // not manifold: the check after the repairs says where
  // One border halfedge per hole, in a fixed order, before any patch changes the borders.
  std::vector<SurfaceMesh::Halfedge_index> holes;
  std::vector<bool> seen(sm->number_of_halfedges(), false);
  for (auto h : sm->halfedges()) {
    if (!sm->is_border(h) || seen[h.idx()]) continue;
    int edges = 0;
    core::Vec3 sum = core::Vec3::Zero();
    for (auto g : CGAL::halfedges_around_face(h, *sm)) {
      seen[g.idx()] = true;
      ++edges;
      const auto& p = sm->point(sm->target(g));
      sum += core::Vec3(p.x(), p.y(), p.z());
    }
    const core::Vec3 centre = sum / std::max(1, edges);
    if (edges <= max_edges) {
      holes.push_back(h);
      RepairReport::note(report.sites.filled, centre);
    } else {
      ++report.open_holes;
      RepairReport::note(report.sites.open, centre);
    }
  }
  for (auto h : holes) {
    std::vector<SurfaceMesh::Face_index> faces;
    std::vector<SurfaceMesh::Vertex_index> vertices;
    const bool faired = std::get<0>(
        PMP::triangulate_refine_and_fair_hole(*sm, h, std::back_inserter(faces), std::back_inserter(vertices)));
    (void)faired;  // a patch that could not be faired is still a refined, closed patch
    ++report.filled_holes;
    report.hole_triangles += static_cast<int>(faces.size());
  }
  if (!holes.empty()) mesh = to_tri_mesh(*sm);
}

void alpha_wrap(core::TriMesh& mesh, double alpha, double offset, RepairReport& report) {
  std::vector<Kernel::Point_3> points;
  points.reserve(mesh.points.size());
  for (const core::Vec3& p : mesh.points) points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::array<std::size_t, 3>> faces;
  faces.reserve(mesh.cells.size());
  for (const core::Tri& t : mesh.cells)
    faces.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  SurfaceMesh wrap;
  CGAL::alpha_wrap_3(points, faces, alpha, offset, wrap);
  mesh = to_tri_mesh(wrap);
  report.wrapped = true;
  report.wrap_triangles = static_cast<int>(mesh.cells.size());
  report.wrap_alpha = alpha;
  report.wrap_offset = offset;
}

}  // namespace polycube::repair::detail
