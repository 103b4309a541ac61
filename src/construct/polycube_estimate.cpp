//! Fast polycube estimate of a labeled surface (see polycube_estimate.h).
#include "construct/polycube_estimate.h"

#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "core/log.h"
#include "solve/sparse_solver.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace polycube::construct {

namespace {


}  // namespace

PolycubeEstimate estimate_polycube(const core::TriMesh& surface, const std::vector<int>& labels) {
  const int nv = surface.num_points();
  const int nt = surface.num_cells();
  if (static_cast<int>(labels.size()) != nt)
    throw core::InputError(fmt::format("polycube estimate: {} labels for {} triangles", labels.size(), nt));
  for (int l : labels)
    if (l < 0 || l >= kNumLabels) throw core::InputError(fmt::format("polycube estimate: label {} out of range", l));

  // Unique edges (sorted, deterministic).
  std::vector<std::array<int, 2>> edges;
  edges.reserve(3 * static_cast<std::size_t>(nt));
  for (const auto& t : surface.cells)
    for (int e = 0; e < 3; ++e) edges.push_back({std::min(t[e], t[(e + 1) % 3]), std::max(t[e], t[(e + 1) % 3])});
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double mean_len = 0;
  for (const auto& e : edges) mean_len += (surface.points[e[0]] - surface.points[e[1]]).norm();
  mean_len /= std::max<std::size_t>(1, edges.size());

  PolycubeEstimate out;
  out.points = surface.points;
  for (int a = 0; a < 3; ++a) {
    // Chart-of-axis-a vertices share one unknown per connected group (vertex-connected).
    core::DisjointSets uf(static_cast<std::size_t>(nv));
    std::vector<char> on(static_cast<std::size_t>(nv), 0);
    for (int t = 0; t < nt; ++t) {
      if (label_axis(labels[t]) != a) continue;
      const auto& c = surface.cells[t];
      for (int v : c) on[v] = 1;
      uf.unite(c[0], c[1]);
      uf.unite(c[0], c[2]);
    }
    std::vector<int> var(static_cast<std::size_t>(nv), -1);
    int n = 0;
    std::vector<int> root_var(static_cast<std::size_t>(nv), -1);
    for (int v = 0; v < nv; ++v) {
      if (on[v]) {
        int& r = root_var[uf.find(v)];
        if (r < 0) r = n++;
        var[v] = r;
      } else {
        var[v] = n++;
      }
    }
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(4 * edges.size() + static_cast<std::size_t>(nv));
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    constexpr double kRho = 1e-6;
    for (const auto& e : edges) {
      const int i = var[e[0]], j = var[e[1]];
      if (i == j) continue;
      const double d = surface.points[e[0]][a] - surface.points[e[1]][a];
      // w (z_i - z_j - d)^2
      trip.emplace_back(std::min(i, j), std::max(i, j), -1.0);
      trip.emplace_back(i, i, 1.0);
      trip.emplace_back(j, j, 1.0);
      rhs[i] += d;
      rhs[j] -= d;
    }
    for (int v = 0; v < nv; ++v) {
      trip.emplace_back(var[v], var[v], kRho);
      rhs[var[v]] += kRho * surface.points[v][a];
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(trip.begin(), trip.end());
    A.makeCompressed();
    const Eigen::VectorXd z = solve::solve_spd(A, rhs);
    for (int v = 0; v < nv; ++v) out.points[v][a] = z[var[v]];
  }

  double total = 0, flipped = 0;
  for (int t = 0; t < nt; ++t) {
    const auto& c = surface.cells[t];
    const auto& p = surface.points;
    const double area = 0.5 * (p[c[1]] - p[c[0]]).cross(p[c[2]] - p[c[0]]).norm();
    total += area;
    const auto& q = out.points;
    const core::Vec3 n = (q[c[1]] - q[c[0]]).cross(q[c[2]] - q[c[0]]);
    if (!(n.dot(label_direction(labels[t])) > 0)) {
      out.flipped.push_back(t);
      flipped += area;
    }
  }
  out.flipped_area = total > 0 ? flipped / total : 0.0;
  double sum = 0;
  for (const auto& e : edges) {
    const double len = std::max((surface.points[e[0]] - surface.points[e[1]]).norm(), 1e-12 * mean_len);
    const core::Vec3 de = (out.points[e[0]] - out.points[e[1]]) - (surface.points[e[0]] - surface.points[e[1]]);
    sum += de.squaredNorm() / (len * len);
  }
  out.edge_distortion = edges.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(edges.size()));
  return out;
}

UnfoldResult unfold_labeling(const core::TriMesh& surface, std::vector<int> labels, int max_moves,
                             const std::vector<int>& held) {
  const auto moves_held = [&](const std::vector<int>& region, int l) {
    return !held.empty() && std::any_of(region.begin(), region.end(), [&](int u) { return held[u] >= 0 && held[u] != l; });
  };
  UnfoldResult r;
  const int nt = surface.num_cells();
  std::vector<std::vector<int>> vertex_tris(static_cast<std::size_t>(surface.num_points()));
  for (int t = 0; t < nt; ++t)
    for (int v : surface.cells[t]) vertex_tris[v].push_back(t);
  auto edge_neighbours = [&](int t) {
    std::vector<int> out;
    const auto& c = surface.cells[t];
    for (int e = 0; e < 3; ++e) {
      const int a = c[e], b = c[(e + 1) % 3];
      for (int u : vertex_tris[a])
        if (u != t && std::find(surface.cells[u].begin(), surface.cells[u].end(), b) != surface.cells[u].end())
          out.push_back(u);
    }
    return out;
  };
  PolycubeEstimate est = estimate_polycube(surface, labels);
  r.folded_before = static_cast<int>(est.flipped.size());
  while (!est.flipped.empty() && r.moves < max_moves) {
    bool moved = false;
    for (const int t : est.flipped) {
      // Targets: the labels of the edge neighbours first, then every other label.
      std::vector<int> targets;
      for (int u : edge_neighbours(t))
        if (labels[u] != labels[t] && std::find(targets.begin(), targets.end(), labels[u]) == targets.end())
          targets.push_back(labels[u]);
      for (int l = 0; l < kNumLabels; ++l)
        if (l != labels[t] && std::find(targets.begin(), targets.end(), l) == targets.end()) targets.push_back(l);
      // Regions: the triangle alone, then with the triangles of its label around its vertices.
      std::vector<std::vector<int>> regions{{t}};
      std::vector<int> ring;
      for (int v : surface.cells[t])
        for (int u : vertex_tris[v])
          if (labels[u] == labels[t] && std::find(ring.begin(), ring.end(), u) == ring.end()) ring.push_back(u);
      std::sort(ring.begin(), ring.end());
      regions.push_back(ring);
      for (const auto& region : regions) {
        for (int l : targets) {
          if (moves_held(region, l)) continue;
          std::vector<int> trial = labels;
          for (int u : region) trial[u] = l;
          if (!check_labeling(surface, trial).valid()) {
            core::logger().debug("unfold: triangle {} ({} triangles) -> label {}: invalid", t, region.size(), l);
            continue;
          }
          PolycubeEstimate e = estimate_polycube(surface, trial);
          core::logger().debug("unfold: triangle {} ({} triangles) -> label {}: folds {} triangles", t, region.size(), l,
                               e.flipped.size());
          if (e.flipped_area < est.flipped_area) {
            labels.swap(trial);
            est = std::move(e);
            ++r.moves;
            moved = true;
            break;
          }
        }
        if (moved) break;
      }
      if (moved) break;
    }
    if (!moved) break;
  }
  r.folded_after = static_cast<int>(est.flipped.size());
  r.labels = std::move(labels);
  return r;
}

}  // namespace polycube::construct
