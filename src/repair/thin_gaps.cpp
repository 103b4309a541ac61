//! Gaps narrower than a width between sheets of a closed surface (see thin_gaps.h).
#include "repair/thin_gaps.h"

#include "core/cgal_surface_mesh.h"
#include "core/errors.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <fmt/format.h>
#include <Eigen/Geometry>

#include <algorithm>

namespace polycube::repair {

namespace {

using Kernel = core::cgal::Kernel;
using Triangles = std::vector<Kernel::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

//! Backward-facing threshold: the hit triangle's normal against the ray (cos 120°).
constexpr double kFacingBack = -0.5;

core::Vec3 triangle_normal(const core::TriMesh& s, const core::Tri& t) {
  return (s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]]);
}

}  // namespace

ThinGaps find_thin_gaps(const core::TriMesh& surface, double width) {
  if (!(width > 0.0)) throw core::InputError(fmt::format("thin gaps: the width must be positive (got {})", width));
  ThinGaps out;
  out.width = width;
  if (surface.cells.empty()) return out;
  const auto point = [&](int v) {
    return Kernel::Point_3(surface.points[v].x(), surface.points[v].y(), surface.points[v].z());
  };
  Triangles triangles;
  triangles.reserve(surface.cells.size());
  std::vector<core::Vec3> vertex_normals(surface.points.size(), core::Vec3::Zero());
  std::vector<std::vector<int>> incident(surface.points.size());
  for (std::size_t i = 0; i < surface.cells.size(); ++i) {
    const core::Tri& t = surface.cells[i];
    triangles.emplace_back(point(t[0]), point(t[1]), point(t[2]));
    const core::Vec3 n = triangle_normal(surface, t);  // |n| = twice the area: area-weighted
    for (const int v : t) {
      vertex_normals[v] += n;
      incident[v].push_back(static_cast<int>(i));
    }
  }
  const Tree tree(triangles.begin(), triangles.end());
  for (std::size_t v = 0; v < surface.points.size(); ++v) {
    if (incident[v].empty() || vertex_normals[v].norm() == 0.0) continue;
    const core::Vec3 dir = vertex_normals[v].normalized();
    const core::Vec3& p = surface.points[v];
    const Kernel::Ray_3 ray(point(static_cast<int>(v)), Kernel::Vector_3(dir.x(), dir.y(), dir.z()));
    // The vertex's own triangles touch the ray at its origin: skipped.
    const auto skip = [&](Triangles::const_iterator id) {
      const int t = static_cast<int>(id - triangles.begin());
      return std::find(incident[v].begin(), incident[v].end(), t) != incident[v].end();
    };
    const auto hit = tree.first_intersected_primitive(ray, skip);
    if (!hit) continue;
    const core::Tri& t = surface.cells[static_cast<std::size_t>(*hit - triangles.begin())];
    const core::Vec3 n = triangle_normal(surface, t);
    if (n.norm() == 0.0 || n.normalized().dot(dir) > kFacingBack) continue;
    // Distance along the ray to the hit triangle's plane.
    const double along = n.dot(surface.points[t[0]] - p) / n.dot(dir);
    if (!(along < width)) continue;
    if (out.vertices == 0 || along < out.narrowest) out.narrowest = std::max(0.0, along);
    ++out.vertices;
    RepairReport::note(out.sites, p);
  }
  return out;
}

std::string ThinGaps::line() const {
  if (vertices == 0) return {};
  return fmt::format("{} vertices face the surface across gaps narrower than {:.3g} (the narrowest {:.3g})", vertices,
                     width, narrowest) +
         places_text(sites, vertices);
}

ThinGaps gaps_the_wrap_closes(const core::TriMesh& surface, const RepairOptions& wrap) {
  const double diagonal = core::bounding_box(surface.points).diagonal();
  if (!(diagonal > 0.0) || !(wrap.wrap_alpha > 0.0)) return {};
  return find_thin_gaps(surface, 2.0 * wrap.wrap_alpha * diagonal);
}

}  // namespace polycube::repair
