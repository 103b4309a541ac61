//! Decimation of a surface finer than the construction needs (see fine_surface.h).
#include "construct/fine_surface.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_distance_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "core/log.h"
#include "core/stopwatch.h"

namespace polycube::construct {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

Mesh to_cgal(const core::TriMesh& s) {
  Mesh m;
  m.reserve(static_cast<Mesh::size_type>(s.points.size()), static_cast<Mesh::size_type>(3 * s.cells.size() / 2),
            static_cast<Mesh::size_type>(s.cells.size()));
  for (const core::Vec3& p : s.points) m.add_vertex({p.x(), p.y(), p.z()});
  for (const core::Tri& t : s.cells)
    m.add_face(Mesh::Vertex_index(static_cast<Mesh::size_type>(t[0])),
               Mesh::Vertex_index(static_cast<Mesh::size_type>(t[1])),
               Mesh::Vertex_index(static_cast<Mesh::size_type>(t[2])));
  return m;
}

//! The collapsed mesh back in core form (garbage collected first, so indices are dense and in
//! the order the collapses left them).
core::TriMesh from_cgal(Mesh& m) {
  m.collect_garbage();
  core::TriMesh s;
  s.points.reserve(m.number_of_vertices());
  for (const Mesh::Vertex_index v : m.vertices()) {
    const Kernel::Point_3& p = m.point(v);
    s.points.emplace_back(p.x(), p.y(), p.z());
  }
  s.cells.reserve(m.number_of_faces());
  for (const Mesh::Face_index f : m.faces()) {
    core::Tri t{};
    int k = 0;
    for (const Mesh::Vertex_index v : CGAL::vertices_around_face(m.halfedge(f), m)) t[k++] = static_cast<int>(v.idx());
    s.cells.push_back(t);
  }
  return s;
}

}  // namespace

std::optional<core::TriMesh> decimate_surface(const core::TriMesh& surface, int max_triangles, double tolerance,
                                              SurfaceDecimation& done) {
  if (max_triangles <= 0 || static_cast<int>(surface.cells.size()) <= max_triangles || !(tolerance > 0.0))
    return std::nullopt;
  const core::Stopwatch clock;
  Mesh m = to_cgal(surface);
  if (!m.is_valid(false) || !CGAL::is_closed(m)) return std::nullopt;  // the checks before name the defect
  // A closed triangle surface has 3/2 edges per triangle.
  const SMS::Count_stop_predicate<Mesh> stop(static_cast<Mesh::size_type>(3 * static_cast<long>(max_triangles) / 2));
  // The placement is refused where it lies farther than the tolerance from the input (an AABB
  // tree of the input). CGAL's polyhedral envelope, which bounds whole triangles, took 27 s on a
  // box of 3,072 triangles (its flat faces make every test exact), against 0.4 s for this.
  const SMS::Bounded_distance_placement<SMS::LindstromTurk_placement<Mesh>, Kernel> placement(tolerance);
  const SMS::Bounded_normal_change_filter<> no_turn;
  SMS::edge_collapse(
      m, stop,
      CGAL::parameters::get_cost(SMS::LindstromTurk_cost<Mesh>()).get_placement(placement).filter(no_turn));
  core::TriMesh out = from_cgal(m);
  if (out.cells.size() == surface.cells.size()) return std::nullopt;  // the tolerance allowed no collapse
  if (CGAL::Polygon_mesh_processing::does_self_intersect(m)) {
    core::logger().warn(
        "construct: decimating {} triangles to {} made the surface intersect itself: the input is used as it is",
        surface.cells.size(), out.cells.size());
    return std::nullopt;
  }
  done.triangles_before = static_cast<int>(surface.cells.size());
  done.triangles_after = static_cast<int>(out.cells.size());
  done.tolerance = tolerance;
  done.seconds = clock.seconds();
  return out;
}

}  // namespace polycube::construct
