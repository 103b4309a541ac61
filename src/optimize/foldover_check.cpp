//! Global fold-over check (see foldover_check.h): exact orientation of every corner tet, Verdict
//! scaled Jacobian, and boundary self-intersection by CGAL box intersection + exact predicates.
#include "optimize/foldover_check.h"

#include "core/elements.h"
#include "core/errors.h"
#include "core/topology.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include <CGAL/Box_intersection_d/Box_with_handle_d.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <vector>

namespace polycube::optimize {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = K::Point_3;
using Triangle3 = K::Triangle_3;
using Segment3 = K::Segment_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

Point3 to_cgal(const core::Vec3& p) { return {p.x(), p.y(), p.z()}; }

//! Do triangles a and b (vertex ids ta, tb) intersect other than in what they share?
bool triangles_cross(const std::array<int, 3>& ta, const std::array<int, 3>& tb, const std::vector<Point3>& P) {
  std::array<int, 3> sa{-1, -1, -1}, sb{-1, -1, -1};  // local index in b of a's vertices (and back)
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (ta[i] == tb[j]) {
        sa[i] = j;
        sb[j] = i;
        ++shared;
      }
  const Triangle3 A(P[ta[0]], P[ta[1]], P[ta[2]]);
  const Triangle3 B(P[tb[0]], P[tb[1]], P[tb[2]]);
  if (A.is_degenerate() || B.is_degenerate()) return false;  // flat elements are caught elsewhere
  if (shared == 0) return CGAL::do_intersect(A, B);
  if (shared >= 3) return true;  // the same triangle twice: the surface overlaps itself
  if (shared == 2) {
    // Common edge (p, q); they overlap exactly when coplanar with the third vertices on the same side.
    int ia = 0, ib = 0;
    while (sa[ia] >= 0) ++ia;
    while (sb[ib] >= 0) ++ib;
    const Point3& p = P[ta[(ia + 1) % 3]];
    const Point3& q = P[ta[(ia + 2) % 3]];
    const Point3& a = P[ta[ia]];
    const Point3& b = P[tb[ib]];
    if (CGAL::orientation(p, q, a, b) != CGAL::COPLANAR) return false;
    return CGAL::coplanar_orientation(p, q, a, b) == CGAL::POSITIVE;
  }
  // One shared vertex v: they cross exactly when the edge opposite v in one meets the other.
  int ia = 0, ib = 0;
  while (sa[ia] < 0) ++ia;
  while (sb[ib] < 0) ++ib;
  const Segment3 ea(P[ta[(ia + 1) % 3]], P[ta[(ia + 2) % 3]]);
  const Segment3 eb(P[tb[(ib + 1) % 3]], P[tb[(ib + 2) % 3]]);
  if (CGAL::do_intersect(ea, B) || CGAL::do_intersect(eb, A)) return true;
  // Coplanar triangles can also overlap around v without either opposite edge meeting the other
  // (one fan sector inside the other): then an edge from v of one lies inside the other's angle.
  const Point3& v = P[ta[ia]];
  if (CGAL::orientation(A[0], A[1], A[2], P[tb[(ib + 1) % 3]]) == CGAL::COPLANAR &&
      CGAL::orientation(A[0], A[1], A[2], P[tb[(ib + 2) % 3]]) == CGAL::COPLANAR) {
    for (int k = 1; k <= 2; ++k) {
      const Point3& w = P[tb[(ib + k) % 3]];
      const Point3& a1 = P[ta[(ia + 1) % 3]];
      const Point3& a2 = P[ta[(ia + 2) % 3]];
      // w strictly inside the angle (a1, v, a2) of A
      if (CGAL::coplanar_orientation(v, a1, a2, w) == CGAL::POSITIVE &&
          CGAL::coplanar_orientation(v, a2, a1, w) == CGAL::POSITIVE)
        return true;
    }
  }
  return false;
}

}  // namespace

std::string FoldoverReport::reason() const {
  if (ok()) return "ok";
  std::string r;
  auto add = [&r](const std::string& s) { r += (r.empty() ? "" : "; ") + s; };
  if (inverted_hexes > 0) add(fmt::format("{} of {} hexes have a flat or inverted corner", inverted_hexes, hexes));
  if (nonpositive_scaled_jacobian > 0)
    add(fmt::format("{} hexes have a scaled Jacobian <= 0", nonpositive_scaled_jacobian));
  if (boundary_self_intersections > 0)
    add(fmt::format("the boundary crosses itself ({}{} intersecting triangle pairs{})", boundary_self_intersections,
                    boundary_self_intersections >= 100 ? "+" : "",
                    crossings.empty() ? std::string()
                                      : fmt::format(", the first near ({:.4g}, {:.4g}, {:.4g})", crossings[0].x(),
                                                    crossings[0].y(), crossings[0].z())));
  return r;
}

int count_self_intersections(const core::TriMesh& soup, int cap, std::vector<std::array<int, 2>>* where) {
  core::check_indices(soup);
  std::vector<Point3> P;
  P.reserve(soup.points.size());
  for (const auto& p : soup.points) P.push_back(to_cgal(p));
  std::vector<Box> boxes;
  boxes.reserve(soup.cells.size());
  for (std::size_t f = 0; f < soup.cells.size(); ++f) {
    const auto& t = soup.cells[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    const auto bb = P[t[0]].bbox() + P[t[1]].bbox() + P[t[2]].bbox();
    boxes.emplace_back(bb, static_cast<int>(f));
  }
  // Collect candidate pairs, then test them in a fixed order (the callback order is not specified).
  std::vector<std::array<int, 2>> pairs;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&pairs](const Box& a, const Box& b) {
    pairs.push_back({std::min(a.info(), b.info()), std::max(a.info(), b.info())});
  });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  int count = 0;
  for (const auto& pr : pairs) {
    if (!triangles_cross(soup.cells[pr[0]], soup.cells[pr[1]], P)) continue;
    ++count;
    if (where) where->push_back(pr);
    if (count >= cap) break;
  }
  return count;
}

FoldoverReport check_foldover(const core::HexMesh& mesh, const FoldoverOptions& options) {
  core::check_indices(mesh);
  FoldoverReport r;
  r.hexes = mesh.num_cells();
  std::vector<Point3> P;
  P.reserve(mesh.points.size());
  for (const auto& p : mesh.points) P.push_back(to_cgal(p));
  for (const auto& h : mesh.cells) {
    bool bad = false;
    for (int i = 0; i < 8 && !bad; ++i) {
      const auto& n = core::kHexCornerNeighbors[i];
      bad = CGAL::orientation(P[h[i]], P[h[n[0]]], P[h[n[1]]], P[h[n[2]]]) != CGAL::POSITIVE;
    }
    r.inverted_hexes += bad;
  }
  quality::ScaledJacobianOptions so;
  so.keep_values = false;
  const auto sj = quality::scaled_jacobian(mesh, so);
  r.nonpositive_scaled_jacobian = sj.inverted + sj.invalid;
  const core::HexBoundary b = core::boundary(mesh);
  const core::TriMesh tris = quality::triangulate(b.surface);
  r.boundary_triangles = tris.num_cells();
  std::vector<std::array<int, 2>> pairs;
  r.boundary_self_intersections = count_self_intersections(tris, options.max_reported_intersections, &pairs);
  auto centroid = [&tris](int f) {
    const auto& t = tris.cells[f];
    return core::Vec3((tris.points[t[0]] + tris.points[t[1]] + tris.points[t[2]]) / 3.0);
  };
  for (const auto& pr : pairs) r.crossings.push_back(0.5 * (centroid(pr[0]) + centroid(pr[1])));
  return r;
}

}  // namespace polycube::optimize
