//! Measuring the partition property (see partition_check.h).
#include "fabricate/partition_check.h"

#include "quality/surface_distance.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>
#include <memory>

namespace polycube::fabricate {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
using Inside = CGAL::Side_of_triangle_mesh<SurfaceMesh, K>;

//! A closed surface with its point-in-solid test (the test keeps a reference to the mesh).
struct Solid {
  SurfaceMesh mesh;
  std::unique_ptr<Inside> inside;
  core::BoundingBox box;
};

std::unique_ptr<Solid> make_solid(const core::TriMesh& m) {
  auto s = std::make_unique<Solid>();
  std::vector<SurfaceMesh::Vertex_index> v;
  for (const core::Vec3& p : m.points)
    v.push_back(s->mesh.add_vertex(K::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : m.cells) s->mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
  s->inside = std::make_unique<Inside>(s->mesh);
  s->box = core::bounding_box(m.points);
  return s;
}

bool contains(const Solid& s, const core::Vec3& p) {
  for (int a = 0; a < 3; ++a)
    if (p[a] < s.box.min[a] || p[a] > s.box.max[a]) return false;
  return (*s.inside)(K::Point_3(p.x(), p.y(), p.z())) == CGAL::ON_BOUNDED_SIDE;
}

//! The parts' triangles that are not on a cut plane, in one mesh.
core::TriMesh own_triangles(const Parts& parts) {
  core::TriMesh out;
  for (const Part& p : parts.parts) {
    const int base = static_cast<int>(out.points.size());
    out.points.insert(out.points.end(), p.mesh.points.begin(), p.mesh.points.end());
    for (std::size_t t = 0; t < p.mesh.cells.size(); ++t)
      if (p.triangle_side.empty() || p.triangle_side[t] < 0) {
        const auto& c = p.mesh.cells[t];
        out.cells.push_back({c[0] + base, c[1] + base, c[2] + base});
      }
  }
  return out;
}

}  // namespace

PartitionCheck check_partition(const Parts& parts, const core::TriMesh& solid,
                               int samples_per_axis) {
  PartitionCheck out;
  const auto whole = make_solid(solid);
  std::vector<std::unique_ptr<Solid>> pieces;
  for (const Part& p : parts.parts)
    if (!p.mesh.cells.empty()) pieces.push_back(make_solid(p.mesh));
  const core::Vec3 extent = whole->box.extent();
  const double step = extent.maxCoeff() / samples_per_axis;
  // Irrational shifts (fractions of the golden ratio and of sqrt 2) keep samples off the cut
  // planes, which on CAD shapes sit at round coordinates.
  const core::Vec3 shift(0.6180339887 * step, 0.4142135624 * step, 0.7320508076 * step);
  int overlap = 0, gap = 0;
  for (double z = whole->box.min.z() + shift.z(); z < whole->box.max.z(); z += step)
    for (double y = whole->box.min.y() + shift.y(); y < whole->box.max.y(); y += step)
      for (double x = whole->box.min.x() + shift.x(); x < whole->box.max.x(); x += step) {
        const core::Vec3 p(x, y, z);
        if (!contains(*whole, p)) continue;
        ++out.samples_inside;
        int in = 0;
        for (const auto& piece : pieces) in += contains(*piece, p) ? 1 : 0;
        overlap += in > 1 ? 1 : 0;
        gap += in == 0 ? 1 : 0;
      }
  if (out.samples_inside > 0) {
    out.overlap = static_cast<double>(overlap) / out.samples_inside;
    out.gap = static_cast<double>(gap) / out.samples_inside;
  }
  const core::TriMesh own = own_triangles(parts);
  if (!own.cells.empty()) {
    const quality::SurfaceDistance d = quality::hausdorff_distance(own, solid);
    out.surface_deviation = d.surface_to_reference.max / d.reference_diagonal;
  }
  return out;
}

}  // namespace polycube::fabricate
