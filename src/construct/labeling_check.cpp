#include "construct/labeling_check.h"

#include "construct/labeling.h"
#include "construct/labeling_check_detail.h"
#include "core/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace polycube::construct {

const char* defect_kind_name(DefectKind kind) {
  switch (kind) {
    case DefectKind::TooFewNeighbors: return "too-few-neighbors";
    case DefectKind::OppositeNeighbors: return "opposite-neighbors";
    case DefectKind::InvalidCorner: return "invalid-corner";
  }
  return "unknown";
}

LabelingCheck check_labeling(const core::TriMesh& surface, const std::vector<int>& labels) {
  if (labels.size() != surface.cells.size())
    throw core::InputError(fmt::format("the labeling has {} labels for {} boundary triangles",
                                       labels.size(), surface.cells.size()));
  for (std::size_t t = 0; t < labels.size(); ++t)
    if (labels[t] < 0 || labels[t] >= kNumLabels)
      throw core::InputError(fmt::format("label {} of triangle {} is not in 0..5", labels[t], t));
  return detail::check_labeling(detail::build_surface_graph(surface), labels, true);
}

namespace {

//! What the rules read besides the layout: which edges separate two charts, the distinct chart
//! pairs they separate, and the number of such edges at each vertex.
struct ChartBoundaryEdges {
  std::vector<char> is_boundary;             //!< #E 1 when the edge separates two charts
  std::vector<std::pair<int, int>> pairs;    //!< sorted, unique (smaller chart, larger chart)
  std::vector<int> valence;                  //!< #V boundary edges at each vertex
};

//! Charts: flood fill across edges with equal labels, seeded in triangle order (chart ids are
//! therefore in order of their first triangle).
void find_charts(const detail::SurfaceGraph& g, const std::vector<int>& labels, ChartLayout& L) {
  const int nt = g.num_triangles;
  L.triangle_chart.assign(static_cast<std::size_t>(nt), -1);
  std::vector<int> stack;
  for (int seed = 0; seed < nt; ++seed) {
    if (L.triangle_chart[seed] >= 0) continue;
    const int c = L.num_charts();
    L.chart_label.push_back(labels[seed]);
    L.chart_triangles.push_back(0);
    L.chart_area.push_back(0.0);
    L.triangle_chart[seed] = c;
    stack.push_back(seed);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      ++L.chart_triangles[c];
      L.chart_area[c] += g.areas[t];
      for (const int e : g.triangle_edges[t]) {
        const int u = g.other(e, t);
        if (L.triangle_chart[u] < 0 && labels[u] == labels[t]) {
          L.triangle_chart[u] = c;
          stack.push_back(u);
        }
      }
    }
  }
}

//! Chart adjacency (L.chart_neighbors) and the chart-boundary edges.
ChartBoundaryEdges find_chart_adjacency(const detail::SurfaceGraph& g, ChartLayout& L) {
  ChartBoundaryEdges b;
  const int ne = static_cast<int>(g.edges.size());
  b.is_boundary.assign(static_cast<std::size_t>(ne), 0);
  for (int e = 0; e < ne; ++e) {
    const int c0 = L.triangle_chart[g.edge_triangles[e][0]];
    const int c1 = L.triangle_chart[g.edge_triangles[e][1]];
    if (c0 == c1) continue;
    b.is_boundary[e] = 1;
    b.pairs.emplace_back(std::min(c0, c1), std::max(c0, c1));
  }
  std::sort(b.pairs.begin(), b.pairs.end());
  b.pairs.erase(std::unique(b.pairs.begin(), b.pairs.end()), b.pairs.end());
  L.chart_neighbors.assign(static_cast<std::size_t>(L.num_charts()), {});
  for (const auto& [c0, c1] : b.pairs) {
    L.chart_neighbors[c0].push_back(c1);
    L.chart_neighbors[c1].push_back(c0);
  }
  for (auto& n : L.chart_neighbors) std::sort(n.begin(), n.end());
  return b;
}

//! Valence of every vertex (b.valence) and the corners, the vertices of valence >= 3 (L.corners).
void find_corners(const detail::SurfaceGraph& g, ChartBoundaryEdges& b, ChartLayout& L) {
  b.valence.assign(static_cast<std::size_t>(g.num_vertices), 0);
  const int ne = static_cast<int>(g.edges.size());
  for (int e = 0; e < ne; ++e)
    if (b.is_boundary[e]) {
      ++b.valence[g.edges[e][0]];
      ++b.valence[g.edges[e][1]];
    }
  for (int v = 0; v < g.num_vertices; ++v)
    if (b.valence[v] >= 3) L.corners.push_back(v);
}

//! Number of chart boundaries: each unvisited boundary edge starts one, which is walked both
//! ways through vertices of valence 2 until a corner (or the start, for a closed chain).
int count_boundaries(const detail::SurfaceGraph& g, const ChartBoundaryEdges& b) {
  const int ne = static_cast<int>(g.edges.size());
  std::vector<char> seen(static_cast<std::size_t>(ne), 0);
  int count = 0;
  for (int e0 = 0; e0 < ne; ++e0) {
    if (!b.is_boundary[e0] || seen[e0]) continue;
    ++count;
    seen[e0] = 1;
    for (int side = 0; side < 2; ++side) {
      int v = g.edges[e0][side];
      int e = e0;
      while (b.valence[v] == 2) {
        int next = -1;
        for (const int f : g.vertex_edges[v])
          if (f != e && b.is_boundary[f]) next = f;
        if (next < 0 || seen[next]) break;
        seen[next] = 1;
        e = next;
        v = g.edges[e][0] == v ? g.edges[e][1] : g.edges[e][0];
      }
    }
  }
  return count;
}

//! Rule 1: at least 4 neighbouring charts.
void check_neighbor_counts(const ChartLayout& L, bool with_reasons, std::vector<Defect>& defects) {
  for (int c = 0; c < L.num_charts(); ++c) {
    const int k = static_cast<int>(L.chart_neighbors[c].size());
    if (k >= 4) continue;
    Defect d{DefectKind::TooFewNeighbors, {c}, -1, {}};
    if (with_reasons)
      d.reason = fmt::format("chart {} ({}, {} triangles) has {} neighbouring chart(s), needs at least 4",
                             c, label_name(L.chart_label[c]), L.chart_triangles[c], k);
    defects.push_back(std::move(d));
  }
}

//! Rule 2: no opposite labels across a boundary.
void check_opposite_neighbors(const ChartLayout& L, const ChartBoundaryEdges& b, bool with_reasons,
                              std::vector<Defect>& defects) {
  for (const auto& [c0, c1] : b.pairs) {
    if (L.chart_label[c0] != opposite_label(L.chart_label[c1])) continue;
    Defect d{DefectKind::OppositeNeighbors, {c0, c1}, -1, {}};
    if (with_reasons)
      d.reason = fmt::format("charts {} ({}) and {} ({}) have opposite labels and share a boundary",
                             c0, label_name(L.chart_label[c0]), c1, label_name(L.chart_label[c1]));
    defects.push_back(std::move(d));
  }
}

//! Why the corner at vertex v, of the given valence and sorted distinct charts, is invalid.
std::string corner_reason(const ChartLayout& L, int v, int valence, const std::vector<int>& charts) {
  std::string names;
  for (const int c : charts)
    names += fmt::format("{}{} ({})", names.empty() ? "" : ", ", c, label_name(L.chart_label[c]));
  if (valence != 3) return fmt::format("corner at vertex {} has valence {} (needs 3); charts: {}", v, valence, names);
  if (charts.size() != 3) return fmt::format("corner at vertex {} joins a chart twice; charts: {}", v, names);
  return fmt::format("corner at vertex {} joins charts with a repeated axis: {}", v, names);
}

//! Rule 3: corners of valence 3 with three distinct charts of distinct axes.
void check_corners(const detail::SurfaceGraph& g, const ChartLayout& L, const ChartBoundaryEdges& b,
                   bool with_reasons, std::vector<Defect>& defects) {
  for (const int v : L.corners) {
    std::vector<int> charts;
    for (const int t : g.vertex_triangles[v]) charts.push_back(L.triangle_chart[t]);
    std::sort(charts.begin(), charts.end());
    charts.erase(std::unique(charts.begin(), charts.end()), charts.end());
    bool ok = b.valence[v] == 3 && charts.size() == 3;
    if (ok) {
      const int a0 = label_axis(L.chart_label[charts[0]]);
      const int a1 = label_axis(L.chart_label[charts[1]]);
      const int a2 = label_axis(L.chart_label[charts[2]]);
      ok = a0 != a1 && a1 != a2 && a0 != a2;
    }
    if (ok) continue;
    Defect d{DefectKind::InvalidCorner, charts, v, {}};
    if (with_reasons) d.reason = corner_reason(L, v, b.valence[v], charts);
    defects.push_back(std::move(d));
  }
}

}  // namespace

namespace detail {

LabelingCheck check_labeling(const SurfaceGraph& g, const std::vector<int>& labels,
                             bool with_reasons) {
  LabelingCheck out;
  ChartLayout& L = out.layout;
  find_charts(g, labels, L);
  ChartBoundaryEdges b = find_chart_adjacency(g, L);
  find_corners(g, b, L);
  L.num_boundaries = count_boundaries(g, b);
  // Defects ordered by rule, as LabelingCheck::defects promises.
  check_neighbor_counts(L, with_reasons, out.defects);
  check_opposite_neighbors(L, b, with_reasons, out.defects);
  check_corners(g, L, b, with_reasons, out.defects);
  return out;
}

int defect_count(const LabelingCheck& check) { return static_cast<int>(check.defects.size()); }

}  // namespace detail

}  // namespace polycube::construct
