#include "padding/analysis.h"

#include "core/elements.h"
#include "core/errors.h"
#include "core/stopwatch.h"
#include "quality/scaled_jacobian.h"
#include "quality/structure_topology.h"
#include "solve/max_flow.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace polycube::padding {

namespace {

using core::Vec3;

//! Unit normal of facet f, outward of hex `cell` (the facet's stored order is outward of its
//! first cell; flipped for the other).
Vec3 outward_normal(const core::HexMesh& mesh, const quality::HexTopology& t, int f, int cell) {
  const core::Quad& q = t.faces.faces[f];
  Vec3 n = (mesh.points[q[2]] - mesh.points[q[0]]).cross(mesh.points[q[3]] - mesh.points[q[1]]);
  const double len = n.norm();
  if (len <= 0) return Vec3::Zero();
  n /= len;
  return t.faces.face_cells[f][0] == cell ? n : Vec3(-n);
}

//! The hexes below the threshold (inverted and degenerate ones included).
std::vector<std::uint8_t> poor_hexes(const core::HexMesh& mesh, double threshold) {
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(mesh);
  std::vector<std::uint8_t> poor(mesh.cells.size(), 0);
  for (std::size_t h = 0; h < poor.size(); ++h) poor[h] = sj.values[h] < threshold ? 1 : 0;
  return poor;
}

//! D(e) of boundary edge e (file comment of analysis.h), 0 for E2H and other edges.
double edge_distortion(const core::HexMesh& mesh, const quality::HexTopology& t, int e) {
  const auto hexes = t.edge_cells[e];
  std::vector<int> boundary, inner;
  for (int f : t.edge_faces[e]) (t.faces.is_boundary(f) ? boundary : inner).push_back(f);
  if (hexes.size() == 1 && boundary.size() == 2) {
    const double theta = outward_normal(mesh, t, boundary[0], hexes[0]).dot(outward_normal(mesh, t, boundary[1], hexes[0]));
    return theta >= 0.5 ? std::min(theta, 1.0) : 0.0;
  }
  if (hexes.size() == 3 && boundary.size() == 2 && inner.size() == 2) {
    // The middle hex is the one both inner facets belong to.
    for (int h : hexes) {
      const auto& c0 = t.faces.face_cells[inner[0]];
      const auto& c1 = t.faces.face_cells[inner[1]];
      if ((c0[0] == h || c0[1] == h) && (c1[0] == h || c1[1] == h)) {
        const double theta = outward_normal(mesh, t, inner[0], h).dot(outward_normal(mesh, t, inner[1], h));
        return theta <= -0.5 ? std::min(-theta, 1.0) : 0.0;
      }
    }
  }
  return 0.0;
}

//! Boundary facets sharing an edge with each boundary facet.
std::vector<std::vector<int>> boundary_neighbours(const quality::HexTopology& t) {
  std::vector<std::vector<int>> nb(t.num_faces());
  for (int e = 0; e < t.num_edges(); ++e) {
    if (!t.edge_on_boundary[e]) continue;
    std::vector<int> b;
    for (int f : t.edge_faces[e])
      if (t.faces.is_boundary(f)) b.push_back(f);
    for (int p : b)
      for (int q : b)
        if (p != q) nb[p].push_back(q);
  }
  return nb;
}

//! Equation 4.8: k synchronous steps; facets already non-zero keep their value.
std::vector<double> propagate(const std::vector<double>& d, const std::vector<std::vector<int>>& nb, int steps) {
  std::vector<double> cur = d;
  for (int n = 0; n < steps; ++n) {
    std::vector<double> next = cur;
    const double decay = std::exp(-0.5 * n);
    for (std::size_t f = 0; f < cur.size(); ++f) {
      if (cur[f] != 0.0) continue;
      double best = 0.0;
      for (int g : nb[f]) best = std::max(best, cur[g]);
      next[f] = best * decay;
    }
    cur = std::move(next);
  }
  return cur;
}

//! Equations 4.9–4.11 on the boundary facets: sink side = HF.
std::vector<std::uint8_t> hard_set(const quality::HexTopology& t, const std::vector<double>& d,
                                   const std::vector<std::vector<int>>& nb) {
  std::vector<int> node(t.num_faces(), -1), facet;
  for (int f = 0; f < t.num_faces(); ++f)
    if (t.faces.is_boundary(f)) {
      node[f] = static_cast<int>(facet.size());
      facet.push_back(f);
    }
  solve::FlowNetwork net(static_cast<int>(facet.size()));
  for (std::size_t i = 0; i < facet.size(); ++i) {
    const double df = d[facet[i]];
    net.add_unary(static_cast<int>(i), df, 1.0 - df);  // outside HF costs D, inside 1 - D
    for (int g : nb[facet[i]]) {
      if (g < facet[i]) continue;
      const double w = (1.0 - std::abs(df - d[g])) * (df + d[g]);
      if (w > 0) net.add_edge(static_cast<int>(i), node[g], w, w);
    }
  }
  const solve::MaxFlowResult cut = solve::max_flow(net);
  std::vector<std::uint8_t> hard(t.num_faces(), 0);
  for (std::size_t i = 0; i < facet.size(); ++i) hard[facet[i]] = cut.on_sink[i] ? 1 : 0;
  return hard;
}

}  // namespace

Analysis analyze_mapping(const core::HexMesh& mesh, const AnalysisOptions& options) {
  const core::Stopwatch clock;
  if (mesh.empty()) throw core::InputError("mapping analysis: the hex mesh is empty");
  if (!(options.threshold > -1.0 && options.threshold <= 1.0) || options.propagation < 0)
    throw core::InputError(fmt::format("mapping analysis: threshold must be in (-1, 1] and propagation >= 0 (got {}, {})",
                                       options.threshold, options.propagation));
  const quality::HexTopology t = quality::hex_topology(mesh);
  const std::vector<std::uint8_t> poor = poor_hexes(mesh, options.threshold);
  Analysis a;
  a.distortion.assign(t.num_faces(), 0.0);
  std::vector<std::uint8_t> counted(mesh.cells.size(), 0);
  for (int e = 0; e < t.num_edges(); ++e) {
    if (!t.edge_on_boundary[e]) continue;
    const auto hexes = t.edge_cells[e];
    if (std::none_of(hexes.begin(), hexes.end(), [&](int h) { return poor[h] != 0; })) continue;
    for (int h : hexes) counted[h] = poor[h];
    const double d = edge_distortion(mesh, t, e);
    if (d <= 0) continue;
    ++a.distorted_edges;
    for (int f : t.edge_faces[e])
      if (t.faces.is_boundary(f)) a.distortion[f] = std::max(a.distortion[f], d);
  }
  a.analysed_hexes = static_cast<int>(std::count(counted.begin(), counted.end(), 1));
  const auto nb = boundary_neighbours(t);
  a.propagated = propagate(a.distortion, nb, options.propagation);
  a.hard = hard_set(t, a.propagated, nb);
  a.hard_facets = static_cast<int>(std::count(a.hard.begin(), a.hard.end(), 1));
  a.seconds = clock.seconds();
  return a;
}

}  // namespace polycube::padding
