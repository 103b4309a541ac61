//! Vertex roles for hex optimization (see vertex_roles.h).
#include "optimize/vertex_roles.h"

#include "core/elements.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <tuple>

namespace polycube::optimize {

VertexRoles classify_vertices(const core::HexMesh& mesh, const TargetSurface& target, double angle_degrees,
                              double distance) {
  core::check_indices(mesh);
  const int nv = mesh.num_points();
  VertexRoles r;
  r.role.assign(nv, VertexRole::Interior);
  r.corner.assign(nv, -1);
  r.edge_length.assign(nv, 0.0);
  // Local edge length: mean over the vertex's hexes of their mean edge length.
  std::vector<int> count(nv, 0);
  for (const auto& h : mesh.cells) {
    double len = 0;
    for (const auto& e : core::kHexEdges) len += (mesh.points[h[e[0]]] - mesh.points[h[e[1]]]).norm();
    len /= 12.0;
    for (int v : h) {
      r.edge_length[v] += len;
      ++count[v];
    }
  }
  for (int v = 0; v < nv; ++v)
    if (count[v] > 0) r.edge_length[v] /= count[v];

  const core::HexBoundary b = core::boundary(mesh);
  for (int v : b.vertex_map) r.role[v] = VertexRole::Surface;
  if (!target.has_features() || b.surface.cells.empty()) {
    r.surface = static_cast<int>(b.vertex_map.size());
    return r;
  }
  // Sharp boundary edges of the hex mesh near target features.
  const core::QuadMesh& q = b.surface;
  std::vector<core::Vec3> normal(q.cells.size());
  for (std::size_t f = 0; f < q.cells.size(); ++f) {
    const auto& c = q.cells[f];
    const core::Vec3 n = (q.points[c[2]] - q.points[c[0]]).cross(q.points[c[3]] - q.points[c[1]]);
    normal[f] = n.norm() > 0 ? core::Vec3(n.normalized()) : core::Vec3::Zero();
  }
  const int ns = q.num_points();
  std::vector<char> near_feature(ns, 0);
  for (int s = 0; s < ns; ++s) {
    const int v = b.vertex_map[s];
    const core::Vec3& p = mesh.points[v];
    near_feature[s] = (target.closest_feature_point(p) - p).norm() <= distance * r.edge_length[v];
  }
  const auto et = core::unique_edges(q);
  const core::Adjacency ec = core::edge_cells(et);
  const double cos_max = std::cos(angle_degrees * std::numbers::pi / 180.0);
  std::vector<int> valence(ns, 0);
  for (int e = 0; e < et.num_edges(); ++e) {
    const auto cells = ec[e];
    const auto [a, c] = et.edges[e];
    if (cells.size() != 2 || !near_feature[a] || !near_feature[c]) continue;
    if (normal[cells[0]].dot(normal[cells[1]]) < cos_max) {
      ++valence[a];
      ++valence[c];
    }
  }
  // Corners: each target corner goes to its nearest candidate vertex.
  // A vertex where two sharp edges meet takes a corner only when it is a junction of three or
  // more feature lines (a T junction of creases, where the hex boundary follows two of them; not the end
  // of a line, as noise creases on scanned models have), within half the distance, and no
  // vertex where three sharp edges meet is near.
  const auto& tf = target.features();
  std::vector<int> corner_valence(tf.corners.size(), 0);
  for (const auto& e : tf.edges)
    for (int x : e) {
      const auto it = std::lower_bound(tf.corners.begin(), tf.corners.end(), x);
      if (it != tf.corners.end() && *it == x) ++corner_valence[static_cast<std::size_t>(it - tf.corners.begin())];
    }
  std::vector<std::tuple<int, int, double, int>> candidates;  // (target corner, valence < 3, distance, vertex)
  for (int s = 0; s < ns; ++s) {
    if (valence[s] == 0) continue;
    r.role[b.vertex_map[s]] = VertexRole::Feature;
    if (valence[s] < 2) continue;
    const core::Vec3& p = q.points[s];
    const int k = target.nearest_corner(p);
    if (k < 0) continue;
    const double d = (target.corner_position(k) - p).norm();
    if (valence[s] < 3 && corner_valence[static_cast<std::size_t>(k)] < 3) continue;
    const double reach = (valence[s] >= 3 ? distance : 0.5 * distance) * r.edge_length[b.vertex_map[s]];
    if (d <= reach) candidates.emplace_back(k, valence[s] < 3 ? 1 : 0, d, s);
  }
  std::sort(candidates.begin(), candidates.end());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (i > 0 && std::get<0>(candidates[i]) == std::get<0>(candidates[i - 1])) continue;
    const int v = b.vertex_map[std::get<3>(candidates[i])];
    r.role[v] = VertexRole::Corner;
    r.corner[v] = std::get<0>(candidates[i]);
  }
  for (int v : b.vertex_map) {
    r.surface += r.role[v] == VertexRole::Surface;
    r.feature += r.role[v] == VertexRole::Feature;
    r.corners += r.role[v] == VertexRole::Corner;
  }
  return r;
}

}  // namespace polycube::optimize
