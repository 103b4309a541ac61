#include "support/exact_geometry.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace polycube::test {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace {
K::Point_3 point(const core::Vec3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

bool self_intersects(const core::TriMesh& m) {
  CGAL::Surface_mesh<K::Point_3> sm;
  std::vector<CGAL::Surface_mesh<K::Point_3>::Vertex_index> v;
  for (const core::Vec3& p : m.points) v.push_back(sm.add_vertex(point(p)));
  for (const auto& t : m.cells)
    if (sm.add_face(v[t[0]], v[t[1]], v[t[2]]) == sm.null_face())
      throw std::runtime_error("self_intersects: a face cannot be added to a halfedge structure");
  return CGAL::Polygon_mesh_processing::does_self_intersect(sm);
}

double farthest_from(const std::vector<core::Vec3>& points, const core::TriMesh& surface) {
  std::vector<K::Triangle_3> tris;
  for (const auto& t : surface.cells)
    tris.emplace_back(point(surface.points[t[0]]), point(surface.points[t[1]]), point(surface.points[t[2]]));
  using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
  CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree(tris.cbegin(), tris.cend());
  tree.accelerate_distance_queries();
  double worst = 0;
  for (const auto& p : points) worst = std::max(worst, std::sqrt(tree.squared_distance(point(p))));
  return worst;
}

}  // namespace polycube::test
