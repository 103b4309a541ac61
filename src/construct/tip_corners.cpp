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

//! A face's plane and the label a tip gave it.
struct HeldFace {
  core::Vec3 normal;
  double offset = 0.0;  //!< normal · (a point of the plane)
  int label = -1;
};

//! How well a corner fits a tip, compared in this order: the fit of the labels to the faces,
//! how close the corner's diagonal is to where the tip points, and the angle of faces whose
//! plane an earlier tip gave the same label.
struct CornerRank {
  double fit = -std::numeric_limits<double>::infinity();
  double pointing = -std::numeric_limits<double>::infinity();
  double consistency = -std::numeric_limits<double>::infinity();
};

bool ahead(const CornerRank& a, const CornerRank& b) {
  constexpr double kTie = 1e-9;  // sums of a few products of unit vectors and angles
  if (std::abs(a.fit - b.fit) > kTie) return a.fit > b.fit;
  if (std::abs(a.pointing - b.pointing) > kTie) return a.pointing > b.pointing;
  return a.consistency > b.consistency + kTie;
}

//! The labels of the best corner for a ring (see find_tip_corners()). Faces that tie several
//! axes fit several corners equally: a tetrahedron's on the diagonals of a cube's faces fit all
//! eight, and the corner the tip points to keeps its four tips on four corners; a wedge's ridge
//! points between two corners, and the labels its other end gave the same faces keep the
//! ridge one polycube edge instead of a twisted one.
std::vector<int> best_corner_labels(const core::TriMesh& s, const std::vector<int>& ring, int v,
                                    const std::vector<core::Vec3>& normals,
                                    const std::vector<HeldFace>& held, double plane_tolerance) {
  const int k = static_cast<int>(ring.size());
  std::vector<std::array<double, 6>> fit(ring.size());
  std::vector<double> weight(ring.size());
  std::vector<std::array<bool, 6>> held_before(ring.size(), std::array<bool, 6>{});
  core::Vec3 pointing = core::Vec3::Zero();  // where the tip points: its faces' normals, by angle
  for (int i = 0; i < k; ++i) {
    const core::Vec3& n = normals[ring[i]];
    weight[i] = corner_angle(s, ring[i], position_in(s.cells[ring[i]], v));
    pointing += weight[i] * n;
    for (int l = 0; l < kNumLabels; ++l) fit[i][l] = weight[i] * n.dot(label_direction(l));
    for (const HeldFace& h : held)
      if (h.normal.dot(n) > 1.0 - 1e-9 &&
          std::abs(h.offset - n.dot(s.points[v])) <= plane_tolerance)
        held_before[i][h.label] = true;
  }
  CornerRank best;
  std::vector<int> labels, candidate(ring.size());
  for (int signs = 0; signs < 8; ++signs) {
    // label of axis a: 2a, +1 when that axis's sign is negative (bit a of `signs`).
    std::array<int, 3> label{};
    CornerRank rank{0.0, 0.0, 0.0};
    for (int a = 0; a < 3; ++a) {
      label[a] = 2 * a + ((signs >> a) & 1);
      rank.pointing += pointing.dot(label_direction(label[a]));
    }
    const bool even = (__builtin_popcount(static_cast<unsigned>(signs)) % 2) == 0;
    const std::array<int, 3> order =
        even ? std::array<int, 3>{0, 1, 2} : std::array<int, 3>{0, 2, 1};
    for (int start = 0; start < k; ++start)
      for (int a = 1; a < k - 1; ++a)
        for (int b = 1; a + b < k; ++b) {
          rank.fit = rank.consistency = 0.0;
          for (int i = 0; i < k; ++i) {
            const int sector = i < a ? 0 : i < a + b ? 1 : 2;
            const int j = (start + i) % k;
            candidate[j] = label[order[sector]];
            rank.fit += fit[j][candidate[j]];
            if (held_before[j][candidate[j]]) rank.consistency += weight[j];
          }
          if (!ahead(rank, best)) continue;
          best = rank;
          labels = candidate;
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
  std::vector<HeldFace> held;  // the faces' labels the tips so far chose
  const double plane_tolerance = 1e-9 * core::bounding_box(surface.points).extent().norm();
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
    tip.ring_labels = best_corner_labels(surface, tip.ring, v, normals, held, plane_tolerance);
    for (std::size_t i = 0; i < tip.ring.size(); ++i) {
      const core::Vec3& n = normals[tip.ring[i]];
      held.push_back({n, n.dot(surface.points[v]), tip.ring_labels[i]});
    }
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
