//! Exact cuts of the solid into parts (see parts.h).
#include "fabricate/parts.h"

#include "core/errors.h"
#include "core/stopwatch.h"
#include "mesh/tet_locator.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>
#include <fmt/format.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <memory>

namespace polycube::fabricate {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<EK::Point_3>;
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vec3 = core::Vec3;

//! Distance from a cut plane, relative to the solid's size, within which a point is on it: the
//! snap before each cut, and a flat side's vertices after rounding.
constexpr double kOnPlane = 1e-9;

ExactMesh to_exact(const core::TriMesh& m) {
  ExactMesh out;
  std::vector<ExactMesh::Vertex_index> v;
  v.reserve(m.points.size());
  for (const Vec3& p : m.points) v.push_back(out.add_vertex(EK::Point_3(p.x(), p.y(), p.z())));
  for (const auto& t : m.cells)
    if (out.add_face(v[t[0]], v[t[1]], v[t[2]]) == ExactMesh::null_face())
      throw core::InputError(
          "fabricate: the solid's surface is not manifold (a triangle cannot be attached)");
  return out;
}

Vec3 rounded(const EK::Point_3& p) {
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

//! Collapse the edges whose two ends round to the same point. An exact cut makes a new vertex
//! wherever a plane crosses an edge, however close to an existing vertex (a plane through a
//! vertex of the input, snapped onto it, and an edge beside it): the two are distinct exactly
//! and one double apart or less, so rounding merges them, folding the triangles between them
//! into slivers that cross their neighbours. Collapsing those edges first (where the link
//! condition keeps the surface a manifold) moves the surface by less than a rounding step.
//! Returns the number of edges collapsed.
int collapse_subrounding_edges(ExactMesh& m) {
  int collapsed = 0;
  for (bool again = true; again;) {
    again = false;
    for (auto e : m.edges()) {
      if (m.is_removed(e)) continue;
      const auto h = m.halfedge(e);
      if (rounded(m.point(m.source(h))) != rounded(m.point(m.target(h)))) continue;
      if (!CGAL::Euler::does_satisfy_link_condition(e, m)) continue;
      CGAL::Euler::collapse_edge(e, m);
      ++collapsed;
      again = true;
    }
  }
  if (collapsed > 0) m.collect_garbage();
  return collapsed;
}

core::TriMesh to_double(const ExactMesh& m) {
  core::TriMesh out;
  std::map<ExactMesh::Vertex_index, int> id;
  for (auto v : m.vertices()) {
    id[v] = static_cast<int>(out.points.size());
    out.points.push_back(rounded(m.point(v)));
  }
  for (auto f : m.faces()) {
    std::array<int, 3> t{};
    int k = 0;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) t[k++] = id[v];
    out.cells.push_back(t);
  }
  return out;
}

//! A box of side 2 R around `centre` whose face on the plane separates the two half-boxes: the
//! 4 corners on the plane are exact projections, so the two sides of a cut share them.
ExactMesh half_box(const CutPlane& plane, const Vec3& centre, double R, bool above) {
  const EK::Plane_3 h(plane.normal.x(), plane.normal.y(), plane.normal.z(), -plane.offset);
  const Vec3 n = plane.normal;
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 c = centre - (n.dot(centre) - plane.offset) * n;
  std::array<EK::Point_3, 8> p;
  const double su[4] = {-1, 1, 1, -1}, sv[4] = {-1, -1, 1, 1};
  const Vec3 far = (above ? R : -R) * n;
  for (int i = 0; i < 4; ++i) {
    const Vec3 q = c + R * (su[i] * u + sv[i] * v);
    p[i] = h.projection(EK::Point_3(q.x(), q.y(), q.z()));
    const Vec3 f = q + far;
    p[i + 4] = EK::Point_3(f.x(), f.y(), f.z());
  }
  ExactMesh box;
  std::array<ExactMesh::Vertex_index, 8> id;
  for (int i = 0; i < 8; ++i) id[i] = box.add_vertex(p[i]);
  // (u, v, n) is right-handed: the face on the plane turns clockwise seen from +n for the box
  // above it (its outside is below), counter-clockwise for the box below.
  const std::array<std::array<int, 4>, 6> quads{
      {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}}};
  for (auto q : quads) {
    if (!above) std::reverse(q.begin(), q.end());
    box.add_face(id[q[0]], id[q[1]], id[q[2]]);
    box.add_face(id[q[0]], id[q[2]], id[q[3]]);
  }
  return box;
}

//! Vertices within eps of the plane put exactly on it: faces that were meant to lie on the
//! plane (a CAD face at a concave edge, a polycube-like model) become exactly coplanar with the
//! cut instead of crossing it at a grazing angle, which leaves slivers that rounding folds.
void snap_to_plane(ExactMesh& m, const CutPlane& plane, double eps) {
  const EK::Plane_3 h(plane.normal.x(), plane.normal.y(), plane.normal.z(), -plane.offset);
  for (auto v : m.vertices()) {
    const Vec3 x = rounded(m.point(v));
    if (std::abs(plane.normal.dot(x) - plane.offset) < eps) m.point(v) = h.projection(m.point(v));
  }
}

//! The part of the piece on one side of the plane (exact corefinement with a half-box: faces
//! of the piece lying on the plane, common on CAD shapes, are classified exactly).
ExactMesh clip_side(const ExactMesh& piece, const CutPlane& plane, const Vec3& centre, double R,
                    bool above) {
  ExactMesh a = piece;
  snap_to_plane(a, plane, kOnPlane * R);
  ExactMesh box = half_box(plane, centre, R, above);
  ExactMesh out;
  if (!PMP::corefine_and_compute_intersection(a, box, out))
    throw core::GeometryError("fabricate: an exact cut failed (the piece is not a closed solid)");
  return out;
}

//! The connected components of a piece as separate meshes.
std::vector<ExactMesh> components(const ExactMesh& piece) {
  std::vector<ExactMesh> out;
  PMP::split_connected_components(piece, out);
  return out;
}

//! Majority box of a component's vertices (sampled), -1 when none maps into a box.
int owner(const ExactMesh& c, const BoxOf& box_of) {
  std::map<int, int> votes;
  const std::size_t n = c.number_of_vertices();
  const std::size_t step = std::max<std::size_t>(1, n / 64);
  std::size_t i = 0;
  for (auto v : c.vertices())
    if (i++ % step == 0) {
      const int b = box_of(rounded(c.point(v)));
      if (b >= 0) ++votes[b];
    }
  int best = -1, count = 0;
  for (const auto& [b, k] : votes)
    if (k > count) {
      best = b;
      count = k;
    }
  return best;
}

//! Every cut plane with both orientations: a part lies on its ancestors' planes and, where a
//! stray component was joined to it (return_strays), on a few others.
std::vector<FlatSide> cut_sides(const CutPlan& plan, const std::vector<CutPlane>& planes) {
  std::vector<FlatSide> out;
  for (std::size_t c = 0; c < plan.cuts.size(); ++c)
    if (plan.cuts[c].axis >= 0)
      for (const double sign : {1.0, -1.0})
        out.push_back({static_cast<int>(c), sign * planes[c].normal});
  return out;
}

//! The part's triangles lying on a cut plane (all three vertices within eps, facing the same way
//! as the candidate side), grouped into flat sides; candidates it does not touch are dropped.
void find_flat_sides(Part& p, std::vector<FlatSide> candidates, const std::vector<CutPlane>& planes,
                     double eps) {
  p.triangle_side.assign(p.mesh.cells.size(), -1);
  for (std::size_t t = 0; t < p.mesh.cells.size(); ++t) {
    const auto& tri = p.mesh.cells[t];
    const Vec3 a = p.mesh.points[tri[0]], b = p.mesh.points[tri[1]], c = p.mesh.points[tri[2]];
    const Vec3 area_normal = 0.5 * (b - a).cross(c - a);
    for (std::size_t s = 0; s < candidates.size(); ++s) {
      const CutPlane& plane = planes[static_cast<std::size_t>(candidates[s].cut)];
      const auto on = [&](const Vec3& x) {
        return std::abs(plane.normal.dot(x) - plane.offset) <= eps;
      };
      if (on(a) && on(b) && on(c) && area_normal.dot(candidates[s].normal) > 0) {
        p.triangle_side[t] = static_cast<int>(s);
        candidates[s].area += area_normal.norm();
        break;
      }
    }
  }
  // Keep the sides with area, largest first, and renumber the triangles' sides.
  std::vector<int> order;
  for (std::size_t s = 0; s < candidates.size(); ++s)
    if (candidates[s].area > 0) order.push_back(static_cast<int>(s));
  std::stable_sort(order.begin(), order.end(),
                   [&](int x, int y) { return candidates[x].area > candidates[y].area; });
  std::vector<int> renumber(candidates.size(), -1);
  for (std::size_t k = 0; k < order.size(); ++k) {
    renumber[order[k]] = static_cast<int>(k);
    p.sides.push_back(candidates[order[k]]);
  }
  for (int& s : p.triangle_side)
    if (s >= 0) s = renumber[s];
}

//! Whether the component holds the mapped centre of one of the boxes.
bool holds_a_centre(const ExactMesh& comp, const std::vector<int>& boxes,
                    const std::vector<Vec3>& centres) {
  const CGAL::Side_of_triangle_mesh<ExactMesh, EK> inside(comp);
  for (int b : boxes) {
    const Vec3& x = centres[static_cast<std::size_t>(b)];
    if (inside(EK::Point_3(x.x(), x.y(), x.z())) != CGAL::ON_UNBOUNDED_SIDE) return true;
  }
  return false;
}

//! A part may hold a sliver of another part's material: where a plane deviates from the map's
//! interface it slices the tip of a neighbouring arm, which a later cut may leave as a separate
//! component. Such a component (holding no centre of its part's box, its vertices mapping into
//! another box) is joined to that box's part by an exact union: it was cut off that part by an
//! exact plane, so the two touch along the same cut polygon and the union is one closed solid.
//! Moving a closed component from one part to another keeps the parts a partition.
int return_strays(std::vector<std::pair<int, ExactMesh>>& pieces, const BoxOf& box_of,
                  const std::vector<Vec3>& centres) {
  std::map<int, std::size_t> piece_of;
  for (std::size_t i = 0; i < pieces.size(); ++i) piece_of[pieces[i].first] = i;
  int moved = 0;
  for (auto& [box, mesh] : pieces) {
    std::vector<ExactMesh> comps = components(mesh);
    if (comps.size() < 2) continue;
    ExactMesh kept;
    for (ExactMesh& comp : comps) {
      const int b = owner(comp, box_of);
      const auto to = piece_of.find(b);
      ExactMesh joined;
      if (b != box && to != piece_of.end() && !holds_a_centre(comp, {box}, centres) &&
          PMP::corefine_and_compute_union(pieces[to->second].second, comp, joined)) {
        pieces[to->second].second = std::move(joined);
        ++moved;
      } else {
        kept.join(comp);
      }
    }
    mesh = std::move(kept);
  }
  return moved;
}

Part finish(int box, ExactMesh piece) {
  collapse_subrounding_edges(piece);
  Part p;
  p.box = box;
  p.mesh = to_double(piece);
  std::vector<std::size_t> component(piece.num_faces());  // num_faces counts removed ones too
  p.components =
      static_cast<int>(PMP::connected_components(piece, CGAL::make_property_map(component)));
  p.closed = CGAL::is_closed(piece);
  CGAL::Surface_mesh<IK::Point_3> rounded_mesh;
  std::vector<CGAL::Surface_mesh<IK::Point_3>::Vertex_index> v;
  for (const Vec3& x : p.mesh.points)
    v.push_back(rounded_mesh.add_vertex(IK::Point_3(x.x(), x.y(), x.z())));
  for (const auto& t : p.mesh.cells) rounded_mesh.add_face(v[t[0]], v[t[1]], v[t[2]]);
  p.self_intersecting = PMP::does_self_intersect(rounded_mesh);
  p.volume = p.closed ? CGAL::to_double(PMP::volume(piece)) : 0.0;
  p.outward = p.volume > 0;
  return p;
}

}  // namespace

BoxOf box_lookup(const core::PolycubeMap& map, const OccupancyGrid& grid,
                 const BoxPartition& partition, double tolerance) {
  auto locator = std::make_shared<mesh::TetLocator>(
      map.tets, map.model, tolerance * core::bounding_box(map.model).diagonal());
  return [locator, &map, &grid, &partition](const Vec3& x) {
    bool located = false;
    const Vec3 q =
        mesh::map_through(map.tets, map.polycube, mesh::locate_or_nearest(*locator, x, located));
    std::array<int, 3> cell{};
    for (int a = 0; a < 3; ++a) {
      const auto& pl = grid.planes[a];
      const auto it = std::upper_bound(pl.begin(), pl.end(), q[a]);
      cell[a] = std::clamp(static_cast<int>(it - pl.begin()) - 1, 0, grid.cells(a) - 1);
    }
    return partition.cell_box[grid.index(cell)];
  };
}

Parts cut_parts(const core::TriMesh& solid, const CutPlan& plan,
                const std::vector<CutPlane>& planes, const BoxOf& box_of,
                const std::vector<core::Vec3>& centres) {
  const core::Stopwatch clock;
  if (planes.size() != plan.cuts.size())
    throw core::InputError(
        fmt::format("fabricate: {} planes for {} cuts", planes.size(), plan.cuts.size()));
  const ExactMesh whole = to_exact(solid);
  if (!CGAL::is_closed(whole))
    throw core::InputError("fabricate: the solid's surface is not closed");
  Parts out;
  out.solid_volume = CGAL::to_double(PMP::volume(whole));
  const core::BoundingBox bb = core::bounding_box(solid.points);
  const Vec3 centre = 0.5 * (bb.min + bb.max);
  const double R = 2.0 * bb.extent().norm();
  if (plan.cuts.empty()) {
    out.parts.push_back(finish(plan.partition.boxes.empty() ? -1 : 0, whole));
    out.volume_sum = out.parts[0].volume;
    out.seconds = clock.seconds();
    return out;
  }
  // sides[c][0 or 1]: the piece below / above cut c.
  std::vector<std::array<ExactMesh, 2>> sides(plan.cuts.size());
  for (std::size_t c = 0; c < plan.cuts.size(); ++c) {
    const Cut& cut = plan.cuts[c];
    const ExactMesh& piece = cut.parent < 0 ? whole : sides[cut.parent][cut.parent_above ? 1 : 0];
    if (cut.axis >= 0) {
      sides[c][0] = clip_side(piece, planes[c], centre, R, false);
      sides[c][1] = clip_side(piece, planes[c], centre, R, true);
      continue;
    }
    for (const ExactMesh& comp : components(piece)) {
      const int b = owner(comp, box_of);
      const bool above = b >= 0 && std::count(cut.above.begin(), cut.above.end(), b) > 0;
      out.unassigned_components +=
          b < 0 || (!above && std::count(cut.below.begin(), cut.below.end(), b) == 0);
      sides[c][above ? 1 : 0].join(comp);
    }
  }
  // The leaves: one piece per box.
  std::vector<std::pair<int, ExactMesh>> pieces;
  for (std::size_t c = 0; c < plan.cuts.size(); ++c)
    for (int s = 0; s < 2; ++s) {
      const auto& group = s ? plan.cuts[c].above : plan.cuts[c].below;
      if (group.size() != 1) continue;
      pieces.emplace_back(group[0], std::move(sides[c][s]));
    }
  out.returned_strays = return_strays(pieces, box_of, centres);
  const std::vector<FlatSide> candidates = cut_sides(plan, planes);
  for (const auto& [box, mesh] : pieces) {
    out.parts.push_back(finish(box, mesh));
    find_flat_sides(out.parts.back(), candidates, planes, kOnPlane * R);
  }
  std::sort(out.parts.begin(), out.parts.end(),
            [](const Part& a, const Part& b) { return a.box < b.box; });
  for (const Part& p : out.parts) out.volume_sum += p.volume;
  out.seconds = clock.seconds();
  return out;
}

}  // namespace polycube::fabricate
