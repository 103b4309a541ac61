//! Canonical form of the samples' CSG surfaces (see canonicalize in cgal_mesh.h): facet
//! outlines reduced to their essential vertices and re-triangulated in a fixed order.
#include "samples/cgal_mesh.h"

#include "core/errors.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <list>
#include <map>
#include <string>
#include <vector>

namespace polycube::samples::detail {

namespace {

using Halfedge = SurfaceMesh::Halfedge_index;
using Vertex = SurfaceMesh::Vertex_index;

using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, Kernel>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, Kernel>;
using Fb = CGAL::Constrained_triangulation_face_base_2<Kernel, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

//! Snapping grid: 2^-24 mm. Coordinates of the essential vertices are exact in double for
//! shapes this size, and snapping absorbs last-bit differences between construction paths.
constexpr double kGrid = 16777216.0;

//! Sine of the largest angle at which two facet-outline edges still count as collinear
//! (corefinement splits straight outlines at rounded intersection points).
constexpr double kCollinearSine = 1e-7;

//! Corners closer than this (mm) are one corner: real features of the samples are millimetres
//! apart, rounding artefacts of the corefinement are ~1e-14 mm apart.
constexpr double kMergeDistance = 1e-6;

core::Vec3 position(const SurfaceMesh& m, Vertex v) {
  const Point3& p = m.point(v);
  return {p.x(), p.y(), p.z()};
}

core::Vec3 snap(const core::Vec3& p) {
  return {std::nearbyint(p.x() * kGrid) / kGrid, std::nearbyint(p.y() * kGrid) / kGrid,
          std::nearbyint(p.z() * kGrid) / kGrid};
}

bool lex_less(const core::Vec3& a, const core::Vec3& b) {
  return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
}

[[noreturn]] void fail(const std::string& what) {
  throw core::InternalError("sample CSG: cannot rebuild the boolean result: " + what);
}

//! Nesting level of every face of a CDT: 0 outside, odd inside the outlined domain
//! (the classic flood fill across constrained edges).
void mark_domains(Cdt& cdt) {
  for (auto f : cdt.all_face_handles()) f->info() = -1;
  std::list<Cdt::Edge> border;
  auto flood = [&](Cdt::Face_handle start, int level) {
    if (start->info() != -1) return;
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      auto fh = queue.front();
      queue.pop_front();
      if (fh->info() != -1) continue;
      fh->info() = level;
      for (int i = 0; i < 3; ++i) {
        auto n = fh->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained(Cdt::Edge(fh, i)))
          border.emplace_back(fh, i);
        else
          queue.push_back(n);
      }
    }
  };
  flood(cdt.infinite_face(), 0);
  while (!border.empty()) {
    const Cdt::Edge e = border.front();
    border.pop_front();
    auto n = e.first->neighbor(e.second);
    if (n->info() == -1) flood(n, e.first->info() + 1);
  }
}

//! One facet: its id and its outline loops as canonical vertex ids.
struct Region {
  int facet = -1;
  std::vector<std::vector<int>> loops;  //!< each rotated to start at its smallest id; sorted
};

}  // namespace

SurfaceMesh canonicalize(SurfaceMesh& m) {
  const auto found = m.property_map<FaceIndex, int>(kFacetProperty);
  if (!found.second) fail("faces carry no facet ids");
  const FacetMap facet = found.first;
  for (Halfedge h : m.halfedges())
    if (m.is_border(h)) fail("the surface is not closed");

  auto is_outline = [&](Halfedge h) { return facet[m.face(h)] != facet[m.face(m.opposite(h))]; };

  // 1. Essential vertices: on three or more facet outlines, or where an outline bends. A vertex
  //    within kMergeDistance of an outline neighbour is a rounding artefact of a near-degenerate
  //    intersection (an edge grazing another), never a corner of the shape.
  std::vector<char> essential(m.number_of_vertices(), 0);
  for (Vertex v : m.vertices()) {
    std::vector<Vertex> ends;
    for (Halfedge h : CGAL::halfedges_around_target(v, m))
      if (is_outline(h)) ends.push_back(m.source(h));
    if (ends.size() == 1) fail("a facet outline ends at a vertex");
    if (ends.size() >= 3) essential[v.idx()] = 1;
    if (ends.size() == 2) {
      const core::Vec3 p = position(m, v);
      const core::Vec3 d1 = position(m, ends[0]) - p, d2 = position(m, ends[1]) - p;
      const bool artefact = std::min(d1.norm(), d2.norm()) < kMergeDistance;
      const bool straight =
          d1.dot(d2) < 0.0 && d1.cross(d2).norm() <= kCollinearSine * d1.norm() * d2.norm();
      essential[v.idx()] = (artefact || straight) ? 0 : 1;
    }
  }

  // 2. Canonical numbering: essential vertices in lexicographic order of snapped coordinates;
  //    vertices closer than kMergeDistance share the number of the smallest of them.
  std::vector<std::pair<core::Vec3, int>> keyed;  // snapped position, old index
  for (Vertex v : m.vertices())
    if (essential[v.idx()]) keyed.emplace_back(snap(position(m, v)), static_cast<int>(v.idx()));
  std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
    return lex_less(a.first, b.first) || (a.first == b.first && a.second < b.second);
  });
  std::vector<int> new_id(m.number_of_vertices(), -1);
  std::vector<core::Vec3> points;
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    int id = -1;
    // Candidates are within kMergeDistance in x, i.e. just before i in lexicographic order.
    for (std::size_t j = i; j-- > 0 && keyed[i].first.x() - keyed[j].first.x() < kMergeDistance;)
      if ((keyed[i].first - keyed[j].first).norm() < kMergeDistance)
        id = new_id[static_cast<std::size_t>(keyed[j].second)];
    if (id < 0) {
      id = static_cast<int>(points.size());
      points.push_back(keyed[i].first);
    }
    new_id[static_cast<std::size_t>(keyed[i].second)] = id;
  }

  // 3. Outline loops of every facet (facet on the left), reduced to essential vertices.
  std::map<int, Region> by_facet;  // grouping only: regions are re-ordered geometrically below
  std::vector<char> visited(m.number_of_halfedges(), 0);
  for (Halfedge start : m.halfedges()) {
    if (visited[start.idx()] || !is_outline(start)) continue;
    std::vector<int> loop;
    Halfedge h = start;
    do {
      visited[h.idx()] = 1;
      const int id = new_id[m.target(h).idx()];
      if (id >= 0 && (loop.empty() || loop.back() != id)) loop.push_back(id);
      Halfedge g = m.next(h);  // next outline halfedge around the same facet
      while (!is_outline(g)) g = m.next(m.opposite(g));
      h = g;
    } while (h != start);
    if (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
    if (loop.size() < 3) fail("a facet outline has fewer than three corners");
    std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
    Region& r = by_facet[facet[m.face(start)]];
    r.facet = facet[m.face(start)];
    r.loops.push_back(std::move(loop));
  }
  std::vector<Region> regions;
  for (auto& [id, r] : by_facet) {
    std::sort(r.loops.begin(), r.loops.end());
    regions.push_back(std::move(r));
  }
  std::sort(regions.begin(), regions.end(),
            [](const Region& a, const Region& b) { return a.loops < b.loops; });

  // 4. Triangulate each facet in its own plane (constrained Delaunay of its outlines).
  std::vector<std::array<int, 3>> triangles;
  std::vector<int> triangle_facet;
  for (const Region& r : regions) {
    const core::Vec3& o = points[static_cast<std::size_t>(r.loops.front().front())];
    core::Vec3 n = core::Vec3::Zero();  // Newell normal: outer loops CCW, holes CW
    for (const auto& loop : r.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const core::Vec3 p = points[static_cast<std::size_t>(loop[i])] - o;
        const core::Vec3 q = points[static_cast<std::size_t>(loop[(i + 1) % loop.size()])] - o;
        n += p.cross(q);
      }
    if (n.norm() == 0.0) fail("a facet has no area");
    n.normalize();
    int k = 0;
    for (int j = 1; j < 3; ++j)
      if (std::abs(n[j]) < std::abs(n[k])) k = j;
    const core::Vec3 u = core::Vec3::Unit(k).cross(n).normalized();
    const core::Vec3 w = n.cross(u);

    Cdt cdt;
    std::map<int, Cdt::Vertex_handle> handle;
    std::vector<int> ids;
    for (const auto& loop : r.loops) ids.insert(ids.end(), loop.begin(), loop.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (int id : ids) {
      const core::Vec3 d = points[static_cast<std::size_t>(id)] - o;
      auto vh = cdt.insert(Kernel::Point_2(d.dot(u), d.dot(w)));
      vh->info() = id;
      handle[id] = vh;
    }
    for (const auto& loop : r.loops)
      for (std::size_t i = 0; i < loop.size(); ++i)
        cdt.insert_constraint(handle[loop[i]], handle[loop[(i + 1) % loop.size()]]);
    if (cdt.number_of_vertices() != ids.size()) fail("facet outlines cross");
    mark_domains(cdt);
    std::vector<std::array<int, 3>> local;
    for (auto f : cdt.finite_face_handles()) {
      if (f->info() % 2 != 1) continue;
      std::array<int, 3> t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      local.push_back(t);
    }
    std::sort(local.begin(), local.end());
    for (const auto& t : local) {
      triangles.push_back(t);
      triangle_facet.push_back(r.facet);
    }
  }

  // 5. Assemble.
  SurfaceMesh out;
  FacetMap out_facet = facet_map(out);
  for (const core::Vec3& p : points) out.add_vertex(Point3(p.x(), p.y(), p.z()));
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    const FaceIndex f = out.add_face(Vertex(t[0]), Vertex(t[1]), Vertex(t[2]));
    if (f == SurfaceMesh::null_face()) fail("the re-triangulated facets are not manifold");
    out_facet[f] = triangle_facet[i];
  }
  for (Halfedge h : out.halfedges())
    if (out.is_border(h)) fail("the re-triangulated facets do not close up");
  for (Vertex v : out.vertices())
    if (out.is_isolated(v)) fail("a corner belongs to no triangle");
  return out;
}

}  // namespace polycube::samples::detail
