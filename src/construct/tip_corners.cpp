#include "construct/tip_corners.h"

#include "construct/labeling.h"
#include "construct/surface_graph.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <numbers>

namespace polycube::construct {

namespace {

//! Angle at vertex `k` of triangle t.
double corner_angle(const core::TriMesh& s, int t, int k) {
  const auto& c = s.cells[t];
  const core::Vec3 u = s.points[c[(k + 1) % 3]] - s.points[c[k]];
  const core::Vec3 w = s.points[c[(k + 2) % 3]] - s.points[c[k]];
  return std::atan2(u.cross(w).norm(), u.dot(w));
}

int position_in(const core::Tri& c, int v) { return c[0] == v ? 0 : c[1] == v ? 1 : 2; }

//! The angle sum at every vertex.
std::vector<double> angle_sums(const core::TriMesh& s) {
  std::vector<double> sum(s.points.size(), 0.0);
  for (int t = 0; t < s.num_cells(); ++t)
    for (int k = 0; k < 3; ++k) sum[s.cells[t][k]] += corner_angle(s, t, k);
  return sum;
}

//! v's triangles counter-clockwise seen from outside: after triangle (v, w, u) comes the one
//! that continues across edge v-u, i.e. (v, u, x). Empty when the fan is not one cycle.
std::vector<int> ordered_ring(const core::TriMesh& s, const core::Adjacency& vertex_triangles,
                              int v) {
  const auto around = vertex_triangles[v];
  std::vector<int> ring{*std::min_element(around.begin(), around.end())};
  while (ring.size() < around.size()) {
    const core::Tri& c = s.cells[ring.back()];
    const int u = c[(position_in(c, v) + 2) % 3];
    int next = -1;
    for (int t : around) {
      const core::Tri& d = s.cells[t];
      if (d[(position_in(d, v) + 1) % 3] == u) next = t;
    }
    if (next < 0 || next == ring.front()) return {};
    ring.push_back(next);
  }
  return ring;
}

//! The labels of the best corner for a ring (see find_tip_corners()).
std::vector<int> best_corner_labels(const core::TriMesh& s, const std::vector<int>& ring, int v,
                                    const std::vector<core::Vec3>& normals) {
  const int k = static_cast<int>(ring.size());
  std::vector<std::array<double, 6>> fit(ring.size());
  core::Vec3 pointing = core::Vec3::Zero();  // where the tip points: its faces' normals, by angle
  for (int i = 0; i < k; ++i) {
    const double w = corner_angle(s, ring[i], position_in(s.cells[ring[i]], v));
    pointing += w * normals[ring[i]];
    for (int l = 0; l < kNumLabels; ++l) fit[i][l] = w * normals[ring[i]].dot(label_direction(l));
  }
  // Faces that tie several axes (a tetrahedron's, on the diagonals of a cube's faces) fit several
  // corners equally: then the corner whose diagonal is closest to where the tip points wins, so
  // the tips of one solid take different corners.
  constexpr double kTie = 1e-9;
  double best = -std::numeric_limits<double>::infinity();
  double best_agreement = -std::numeric_limits<double>::infinity();
  std::vector<int> labels;
  for (int signs = 0; signs < 8; ++signs) {
    // label of axis a: 2a, +1 when that axis's sign is negative (bit a of `signs`).
    std::array<int, 3> label{};
    double agreement = 0.0;
    for (int a = 0; a < 3; ++a) {
      label[a] = 2 * a + ((signs >> a) & 1);
      agreement += pointing.dot(label_direction(label[a]));
    }
    const bool even = (__builtin_popcount(static_cast<unsigned>(signs)) % 2) == 0;
    const std::array<int, 3> order =
        even ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{0, 2, 1};
    for (int start = 0; start < k; ++start)
      for (int a = 1; a < k - 1; ++a)
        for (int b = 1; a + b < k; ++b) {
          double score = 0.0;
          for (int i = 0; i < k; ++i) {
            const int sector = i < a ? 0 : i < a + b ? 1 : 2;
            score += fit[(start + i) % k][label[order[sector]]];
          }
          const bool better =
              score > best + kTie || (score >= best - kTie && agreement > best_agreement + kTie);
          if (!better) continue;
          best = std::max(best, score);
          best_agreement = agreement;
          labels.assign(ring.size(), 0);
          for (int i = 0; i < k; ++i) {
            const int sector = i < a ? 0 : i < a + b ? 1 : 2;
            labels[(start + i) % k] = label[order[sector]];
          }
        }
  }
  return labels;
}

//! A third of the distance from v to the nearest other vertex that is not flat, found by
//! growing edge rings around v (the first ring holding one); infinity when there is none.
double tip_radius(const core::TriMesh& s, const detail::SurfaceGraph& g,
                  const std::vector<bool>& flat, int v) {
  std::vector<int> seen{v};
  std::vector<int> layer{v};
  std::vector<bool> visited(s.points.size(), false);
  visited[v] = true;
  while (!layer.empty()) {
    std::vector<int> next;
    double nearest = std::numeric_limits<double>::infinity();
    for (int u : layer)
      for (int e : g.vertex_edges[u]) {
        const int w = g.edges[e][0] == u ? g.edges[e][1] : g.edges[e][0];
        if (visited[w]) continue;
        visited[w] = true;
        next.push_back(w);
        if (!flat[w]) nearest = std::min(nearest, (s.points[w] - s.points[v]).norm());
      }
    if (nearest < std::numeric_limits<double>::infinity()) return nearest / 3.0;
    layer = std::move(next);
  }
  return std::numeric_limits<double>::infinity();
}

}  // namespace

std::vector<TipCorner> find_tip_corners(const core::TriMesh& surface, int max_ring) {
  constexpr double kCubeCorner = 1.5 * std::numbers::pi;
  constexpr double kSlack = 1e-9;  // radians: a cube's own corners count
  const std::vector<double> sums = angle_sums(surface);
  const core::Adjacency vertex_triangles = core::vertex_cells(surface);
  std::vector<core::Vec3> normals(surface.cells.size());
  for (int t = 0; t < surface.num_cells(); ++t) {
    const auto& c = surface.cells[t];
    normals[t] = (surface.points[c[1]] - surface.points[c[0]])
                     .cross(surface.points[c[2]] - surface.points[c[0]])
                     .normalized();
  }
  std::vector<TipCorner> tips;
  for (int v = 0; v < surface.num_points(); ++v) {
    const auto around = vertex_triangles[v];
    if (around.size() < 3 || static_cast<int>(around.size()) > max_ring ||
        sums[v] > kCubeCorner + kSlack)
      continue;
    TipCorner tip;
    tip.vertex = v;
    tip.angle_sum = sums[v];
    tip.ring = ordered_ring(surface, vertex_triangles, v);
    if (tip.ring.empty()) continue;
    tip.ring_labels = best_corner_labels(surface, tip.ring, v, normals);
    tips.push_back(std::move(tip));
  }
  return tips;
}

std::vector<int> tip_corner_labels(const core::TriMesh& surface, std::vector<TipCorner>& tips) {
  std::vector<int> steered(surface.cells.size(), -1);
  if (tips.empty()) return steered;
  const detail::SurfaceGraph g = detail::build_surface_graph(surface);
  const std::vector<double> sums = angle_sums(surface);
  std::vector<bool> flat(sums.size());
  constexpr double kFlat =
      1e-6;  // radians from 2π: the new vertices of a planar split are flat to rounding
  for (std::size_t v = 0; v < sums.size(); ++v)
    flat[v] = std::abs(sums[v] - 2.0 * std::numbers::pi) < kFlat;
  constexpr double kCoplanar = 1e-9;
  for (TipCorner& tip : tips) {
    tip.radius = tip_radius(surface, g, flat, tip.vertex);
    const core::Vec3& p = surface.points[tip.vertex];
    for (std::size_t i = 0; i < tip.ring.size(); ++i) {
      const int seed = tip.ring[i];
      const core::Vec3& n = g.normals[seed];
      if (steered[seed] >= 0) continue;  // a coplanar ring triangle before it took its plane
      steered[seed] = tip.ring_labels[i];
      std::deque<int> queue{seed};
      while (!queue.empty()) {
        const int t = queue.front();
        queue.pop_front();
        for (int e : g.triangle_edges[t]) {
          const int o = g.other(e, t);
          if (steered[o] >= 0 || g.normals[o].dot(n) < 1.0 - kCoplanar ||
              (g.centroids[o] - p).norm() > tip.radius)
            continue;
          steered[o] = tip.ring_labels[i];
          queue.push_back(o);
        }
      }
    }
  }
  return steered;
}

std::vector<std::array<double, 6>> steering_penalty(const std::vector<int>& steered,
                                                    double weight) {
  if (std::all_of(steered.begin(), steered.end(), [](int l) { return l < 0; })) return {};
  std::vector<std::array<double, 6>> penalty(steered.size(), std::array<double, 6>{});
  for (std::size_t t = 0; t < steered.size(); ++t)
    if (steered[t] >= 0)
      for (int l = 0; l < kNumLabels; ++l) penalty[t][l] = l == steered[t] ? 0.0 : weight;
  return penalty;
}

}  // namespace polycube::construct
