//! Decimation of a surface finer than the construction needs (see fine_surface.h).
#include "construct/fine_surface.h"

#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_distance_placement.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_cost.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk_placement.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include "core/cgal_surface_mesh.h"
#include "core/log.h"
#include "core/stopwatch.h"

namespace polycube::construct {

namespace {

using Kernel = core::cgal::Kernel;
using Mesh = core::cgal::SurfaceMesh;
namespace SMS = CGAL::Surface_mesh_simplification;

}  // namespace

std::optional<core::TriMesh> decimate_surface(const core::TriMesh& surface, int max_triangles, double tolerance,
                                              SurfaceDecimation& done) {
  if (max_triangles <= 0 || static_cast<int>(surface.cells.size()) <= max_triangles || !(tolerance > 0.0))
    return std::nullopt;
  const core::Stopwatch clock;
  // A surface CGAL cannot hold is left to the checks of the tetrahedralization, which name the
  // defect.
  for (const core::Tri& t : surface.cells)
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return std::nullopt;
  std::optional<Mesh> cgal_mesh = core::cgal::to_surface_mesh(surface);
  if (!cgal_mesh || !CGAL::is_closed(*cgal_mesh)) return std::nullopt;
  Mesh& m = *cgal_mesh;
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
  m.collect_garbage();
  core::TriMesh out = core::cgal::to_tri_mesh(m);
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
