//! Exact certification of polycube maps (see certify.h).
#include "construct/certify.h"

#include "core/errors.h"
#include "core/topology.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace polycube::construct {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P3 = K::Point_3;
using P2 = K::Point_2;

P3 p3(const core::Vec3& p) { return {p.x(), p.y(), p.z()}; }

std::string list(const std::vector<int>& ids) {
  std::string s;
  for (std::size_t i = 0; i < ids.size(); ++i) s += (i ? ", " : "") + std::to_string(ids[i]);
  return s;
}

//! Count tets with negative / zero exact orientation; collect the first few.
void orientation_counts(const std::vector<core::Tet>& tets, const std::vector<core::Vec3>& pts, int& inverted,
                        int& flat, std::vector<int>& first, int max_listed) {
  inverted = flat = 0;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& c = tets[t];
    const CGAL::Orientation o = CGAL::orientation(p3(pts[c[0]]), p3(pts[c[1]]), p3(pts[c[2]]), p3(pts[c[3]]));
    if (o == CGAL::POSITIVE) continue;
    (o == CGAL::NEGATIVE ? inverted : flat)++;
    if (static_cast<int>(first.size()) < max_listed) first.push_back(static_cast<int>(t));
  }
}

}  // namespace

std::string Certificate::reason() const {
  if (failures.empty()) return "certified";
  std::string s;
  for (std::size_t i = 0; i < failures.size(); ++i) s += (i ? "; " : "") + failures[i];
  return s;
}

Certificate certify_polycube_map(const core::PolycubeMap& map, const std::vector<core::Tri>& boundary,
                                 const std::vector<int>& labels, const CertifyOptions& o) {
  core::check_map_indices(map);
  if (labels.size() != boundary.size())
    throw core::InputError(fmt::format("certify: {} labels for {} triangles", labels.size(), boundary.size()));
  for (const auto& t : boundary)
    for (int v : t)
      if (v < 0 || v >= map.num_vertices()) throw core::InputError("certify: boundary triangle index out of range");
  for (int l : labels)
    if (l < 0 || l > 5) throw core::InputError(fmt::format("certify: label {} not in 0..5", l));

  Certificate c;
  c.tets = map.num_tets();
  c.boundary_triangles = static_cast<int>(boundary.size());

  // 1. Orientation in both spaces.
  {
    std::vector<int> first;
    orientation_counts(map.tets, map.model, c.inverted_model, c.flat_model, first, o.max_listed);
    if (c.inverted_model + c.flat_model > 0)
      c.failures.push_back(fmt::format("{} inverted and {} flat tets in model space (first: {})", c.inverted_model,
                                       c.flat_model, list(first)));
    first.clear();
    orientation_counts(map.tets, map.polycube, c.inverted_polycube, c.flat_polycube, first, o.max_listed);
    if (c.inverted_polycube + c.flat_polycube > 0)
      c.failures.push_back(fmt::format("{} inverted and {} flat tets in polycube space (first: {})",
                                       c.inverted_polycube, c.flat_polycube, list(first)));
  }

  // 2. The labeled triangles are the boundary faces; the boundary is a closed manifold.
  const core::TetMesh pm = map.polycube_mesh();
  const core::TetBoundary b = core::boundary(pm);
  const core::SurfaceReport sr = core::analyze_surface(b.surface);
  c.closed_manifold = sr.closed && sr.manifold;
  if (!c.closed_manifold)
    c.failures.push_back(fmt::format("the boundary is not a closed manifold surface ({} open edges, {} non-manifold "
                                     "edges, {} non-manifold vertices)",
                                     sr.boundary_edges, sr.nonmanifold_edges, sr.nonmanifold_vertices));
  std::vector<std::pair<std::array<int, 3>, int>> keys(boundary.size());
  for (std::size_t i = 0; i < boundary.size(); ++i) {
    std::array<int, 3> k{boundary[i][0], boundary[i][1], boundary[i][2]};
    std::sort(k.begin(), k.end());
    keys[i] = {k, static_cast<int>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> used(boundary.size(), 0);
  std::vector<int> off_first, facing_first;
  const std::vector<core::Tri> outward = core::boundary_triangles(b);
  for (std::size_t f = 0; f < outward.size(); ++f) {
    const core::Tri& tri = outward[f];
    std::array<int, 3> k = tri;
    std::sort(k.begin(), k.end());
    auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    if (it == keys.end() || it->first != k || used[it->second]) {
      ++c.unmatched_triangles;
      continue;
    }
    used[it->second] = 1;
    const int label = labels[it->second];
    const int a = label / 2;
    // 3. Exactly on an axis plane, facing the label's direction.
    const auto& q0 = map.polycube[tri[0]];
    const auto& q1 = map.polycube[tri[1]];
    const auto& q2 = map.polycube[tri[2]];
    if (!(q0[a] == q1[a] && q1[a] == q2[a])) {
      ++c.off_plane;
      if (static_cast<int>(off_first.size()) < o.max_listed) off_first.push_back(it->second);
      continue;
    }
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const CGAL::Orientation or2 = CGAL::orientation(P2(q0[u], q0[v]), P2(q1[u], q1[v]), P2(q2[u], q2[v]));
    const CGAL::Orientation want = (label % 2 == 0) ? CGAL::POSITIVE : CGAL::NEGATIVE;
    if (or2 != want) {
      ++c.wrong_facing;
      if (static_cast<int>(facing_first.size()) < o.max_listed) facing_first.push_back(it->second);
    }
  }
  for (char u : used) c.unmatched_triangles += u ? 0 : 1;
  if (c.unmatched_triangles > 0)
    c.failures.push_back(fmt::format("{} labeled triangles do not match the boundary faces of the tet mesh",
                                     c.unmatched_triangles));
  if (c.off_plane > 0)
    c.failures.push_back(fmt::format("{} boundary triangles are not exactly on an axis plane of their label (first: {})",
                                     c.off_plane, list(off_first)));
  if (c.wrong_facing > 0)
    c.failures.push_back(fmt::format("{} boundary triangles do not face their label's direction (first: {})",
                                     c.wrong_facing, list(facing_first)));

  // 4. No self-intersection of the polycube boundary.
  if (o.check_self_intersection && c.closed_manifold) {
    CGAL::Surface_mesh<P3> sm;
    std::vector<CGAL::Surface_mesh<P3>::Vertex_index> vid(b.vertex_map.size());
    for (std::size_t i = 0; i < b.vertex_map.size(); ++i) vid[i] = sm.add_vertex(p3(map.polycube[b.vertex_map[i]]));
    bool built = true;
    for (const auto& s : b.surface.cells)
      if (sm.add_face(vid[s[0]], vid[s[1]], vid[s[2]]) == CGAL::Surface_mesh<P3>::null_face()) built = false;
    c.self_intersection_checked = built;
    if (!built) {
      c.failures.push_back("the polycube boundary could not be built as a halfedge surface");
    } else {
      c.self_intersecting = CGAL::Polygon_mesh_processing::does_self_intersect(sm);
      if (c.self_intersecting) c.failures.push_back("the polycube boundary surface intersects itself");
    }
  }
  return c;
}

void require_certified(const Certificate& certificate) {
  if (!certificate.certified())
    throw core::GeometryError("polycube map not certified: " + certificate.reason());
}

}  // namespace polycube::construct
