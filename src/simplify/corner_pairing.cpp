#include "simplify/corner_pairing.h"

#include "core/errors.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>

namespace polycube::simplify {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, Kernel>;
using Tds = CGAL::Triangulation_data_structure_3<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;

}  // namespace

std::vector<std::array<int, 2>> delaunay_pairs(const std::vector<core::Vec3>& points) {
  std::vector<std::array<int, 2>> out;
  const int n = static_cast<int>(points.size());
  if (n < 2) return out;
  // Insert one by one in index order: deterministic, and a duplicate keeps the first index.
  Delaunay dt;
  Delaunay::Vertex_handle hint;
  for (int i = 0; i < n; ++i) {
    const Kernel::Point_3 p(points[i].x(), points[i].y(), points[i].z());
    hint = dt.insert(p, hint);
  }
  // CGAL keeps the first inserted vertex for duplicates; assign ids by position lookup.
  std::map<std::array<double, 3>, int> id;
  for (int i = 0; i < n; ++i) id.emplace(std::array<double, 3>{points[i].x(), points[i].y(), points[i].z()}, i);
  for (auto v = dt.finite_vertices_begin(); v != dt.finite_vertices_end(); ++v) {
    const auto& p = v->point();
    v->info() = id.at({p.x(), p.y(), p.z()});
  }
  if (dt.dimension() < 1) return out;
  for (auto e = dt.finite_edges_begin(); e != dt.finite_edges_end(); ++e) {
    const int i = e->first->vertex(e->second)->info();
    const int j = e->first->vertex(e->third)->info();
    out.push_back({std::min(i, j), std::max(i, j)});
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<CornerPair> pair_corners(const structure::PolycubeStructure& s, const std::vector<core::Vec3>& pos,
                                     const CanAlign& can_align, const IsExterior& exterior, PairingStats* stats) {
  const int nc = static_cast<int>(s.corners.size());
  PC_REQUIRE(static_cast<int>(pos.size()) == nc, "one position per corner");
  PairingStats st;
  // corner adjacency through polycube edges (sorted)
  std::vector<std::vector<int>> adj(static_cast<std::size_t>(nc));
  for (const auto& e : s.edges)
    if (e.corners[0] >= 0 && e.corners[1] >= 0 && e.corners[0] != e.corners[1]) {
      adj[e.corners[0]].push_back(e.corners[1]);
      adj[e.corners[1]].push_back(e.corners[0]);
    }
  for (auto& a : adj) {
    std::sort(a.begin(), a.end());
    a.erase(std::unique(a.begin(), a.end()), a.end());
  }
  auto adjacent = [&](int a, int b) { return std::binary_search(adj[a].begin(), adj[a].end(), b); };
  auto share_neighbour = [&](int a, int b) {
    std::size_t i = 0, j = 0;
    while (i < adj[a].size() && j < adj[b].size()) {
      if (adj[a][i] == adj[b][j]) return true;
      if (adj[a][i] < adj[b][j]) ++i; else ++j;
    }
    return false;
  };

  const auto dp = delaunay_pairs(pos);
  st.delaunay = static_cast<int>(dp.size());
  std::vector<CornerPair> assigned;
  for (const auto& [a, b] : dp) {
    if (adjacent(a, b)) { ++st.same_edge; continue; }          // rule 1
    if (share_neighbour(a, b)) { ++st.adjacent_edges; continue; }  // rule 2
    if (exterior && exterior(a, b)) { ++st.exterior; continue; }   // rule 3
    int best = -1;
    double dist = 0.0;
    for (int ax = 0; ax < 3; ++ax) {
      if (!can_align(ax, a, b)) continue;
      const double d = std::abs(pos[a][ax] - pos[b][ax]);
      if (best < 0 || d < dist) {
        best = ax;
        dist = d;
      }
    }
    if (best < 0) { ++st.infeasible; continue; }
    assigned.push_back({a, b, best, dist});
  }
  // closest partner per (corner, axis)
  std::vector<std::array<int, 3>> closest(static_cast<std::size_t>(nc), {-1, -1, -1});
  auto better = [&](int cur, int cand) {
    if (cur < 0) return true;
    const auto& p = assigned[cur];
    const auto& q = assigned[cand];
    if (q.distance != p.distance) return q.distance < p.distance;
    return std::pair{q.a, q.b} < std::pair{p.a, p.b};
  };
  for (int k = 0; k < static_cast<int>(assigned.size()); ++k) {
    const auto& p = assigned[k];
    for (int c : {p.a, p.b})
      if (better(closest[c][p.axis], k)) closest[c][p.axis] = k;
  }
  std::vector<CornerPair> out;
  for (int k = 0; k < static_cast<int>(assigned.size()); ++k) {
    const auto& p = assigned[k];
    if (closest[p.a][p.axis] == k || closest[p.b][p.axis] == k) out.push_back(p);
    else ++st.not_closest;
  }
  std::sort(out.begin(), out.end(), [](const CornerPair& x, const CornerPair& y) {
    return std::tie(x.axis, x.a, x.b) < std::tie(y.axis, y.a, y.b);
  });
  st.kept = static_cast<int>(out.size());
  if (stats) *stats = st;
  return out;
}

}  // namespace polycube::simplify
