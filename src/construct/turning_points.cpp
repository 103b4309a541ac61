//! Turning points of chart boundaries (see turning_points.h).
#include "construct/turning_points.h"

#include "construct/labeling_check.h"
#include "construct/surface_graph.h"
#include "core/errors.h"
#include "core/log.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace polycube::construct {

namespace {

BoundaryTurning turning(const detail::SurfaceGraph& g, const std::vector<core::Vec3>& p,
                        const std::vector<int>& labels) {
  BoundaryTurning out;
  const std::size_t nv = static_cast<std::size_t>(g.num_vertices);
  auto on_boundary = [&](int e) { return labels[g.edge_triangles[e][0]] != labels[g.edge_triangles[e][1]]; };
  std::vector<int> valence(nv, 0);
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    if (on_boundary(static_cast<int>(e))) {
      ++valence[g.edges[e][0]];
      ++valence[g.edges[e][1]];
    }
  std::vector<char> used(g.edges.size(), 0);
  for (std::size_t c = 0; c < nv; ++c) {
    if (valence[c] < 3) continue;
    for (int e0 : g.vertex_edges[static_cast<int>(c)]) {
      if (used[e0] || !on_boundary(e0)) continue;
      // Walk the chain from corner c through valence-2 vertices to the next corner.
      std::vector<int> verts{static_cast<int>(c)}, edges;
      int e = e0, cur = static_cast<int>(c);
      for (;;) {
        used[e] = 1;
        edges.push_back(e);
        cur = g.edges[e][0] == cur ? g.edges[e][1] : g.edges[e][0];
        verts.push_back(cur);
        if (valence[cur] != 2) break;
        int next = -1;
        for (int f : g.vertex_edges[cur])
          if (f != e && on_boundary(f)) next = f;
        if (next < 0 || used[next]) break;
        e = next;
      }
      const int la = labels[g.edge_triangles[e0][0]], lb = labels[g.edge_triangles[e0][1]];
      if (la / 2 == lb / 2) continue;
      const int axis = 3 - la / 2 - lb / 2;
      ++out.chains;
      const double total = p[verts.back()][axis] - p[verts.front()][axis];
      if (total == 0.0) continue;
      const double dir = total > 0 ? 1.0 : -1.0;
      for (std::size_t i = 0; i < edges.size(); ++i) {
        const double step = dir * (p[verts[i + 1]][axis] - p[verts[i]][axis]);
        if (step >= 0) continue;
        const auto& tri = g.edge_triangles[edges[i]];
        out.steps.push_back({verts[i], verts[i + 1], tri[0], tri[1], -step});
        out.backward_length -= step;
      }
    }
  }
  std::sort(out.steps.begin(), out.steps.end(), [](const BackwardStep& a, const BackwardStep& b) {
    return a.length != b.length ? a.length > b.length : std::tie(a.from, a.to) < std::tie(b.from, b.to);
  });
  return out;
}

void check_sizes(const core::TriMesh& s, const std::vector<core::Vec3>& points, const std::vector<int>& labels) {
  if (points.size() != s.points.size())
    throw core::InputError(fmt::format("turning points: {} positions for {} vertices", points.size(), s.points.size()));
  if (labels.size() != s.cells.size())
    throw core::InputError(fmt::format("turning points: {} labels for {} triangles", labels.size(), s.cells.size()));
  for (int l : labels)
    if (l < 0 || l > 5) throw core::InputError(fmt::format("turning points: label {} is not in 0..5", l));
}

}  // namespace

BoundaryTurning boundary_turning(const core::TriMesh& surface, const std::vector<core::Vec3>& points,
                                 const std::vector<int>& labels) {
  check_sizes(surface, points, labels);
  return turning(detail::build_surface_graph(surface), points, labels);
}

StraightenResult straighten_boundaries(const core::TriMesh& surface, const std::vector<core::Vec3>& points,
                                       std::vector<int> labels, int max_moves) {
  check_sizes(surface, points, labels);
  const detail::SurfaceGraph g = detail::build_surface_graph(surface);
  StraightenResult r;
  BoundaryTurning cur = turning(g, points, labels);
  r.backward_before = cur.backward_length;
  r.steps_before = static_cast<int>(cur.steps.size());
  const bool valid = check_labeling(surface, labels).valid();
  while (valid && !cur.steps.empty() && r.moves < max_moves) {
    bool moved = false;
    for (const BackwardStep& st : cur.steps) {
      // Candidate regions: each side's triangle alone, then with the triangles of its label
      // around the step's two ends; each takes the other side's label.
      std::vector<std::pair<std::vector<int>, int>> candidates;
      for (const auto& [t, other] : {std::pair{st.left, st.right}, std::pair{st.right, st.left}}) {
        candidates.push_back({{t}, labels[other]});
        std::vector<int> ring;
        for (int v : {st.from, st.to})
          for (int u : g.vertex_triangles[v])
            if (labels[u] == labels[t] && std::find(ring.begin(), ring.end(), u) == ring.end()) ring.push_back(u);
        std::sort(ring.begin(), ring.end());
        candidates.push_back({ring, labels[other]});
      }
      std::vector<int> best;
      double best_length = cur.backward_length;
      for (const auto& [region, label] : candidates) {
        std::vector<int> trial = labels;
        for (int u : region) trial[u] = label;
        const BoundaryTurning tr = turning(g, points, trial);
        if (!(tr.backward_length < best_length)) continue;
        if (!check_labeling(surface, trial).valid()) continue;
        best_length = tr.backward_length;
        best = std::move(trial);
      }
      if (best.empty()) continue;
      labels.swap(best);
      cur = turning(g, points, labels);
      ++r.moves;
      moved = true;
      break;
    }
    if (!moved) break;
  }
  r.backward_after = cur.backward_length;
  r.steps_after = static_cast<int>(cur.steps.size());
  r.labels = std::move(labels);
  return r;
}

}  // namespace polycube::construct
