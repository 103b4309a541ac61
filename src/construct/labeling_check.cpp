#include "construct/labeling_check.h"

#include "construct/labeling.h"
#include "construct/labeling_check_detail.h"
#include "core/errors.h"

#include <fmt/format.h>

#include <algorithm>

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

namespace detail {

LabelingCheck check_labeling(const SurfaceGraph& g, const std::vector<int>& labels,
                             bool with_reasons) {
  LabelingCheck out;
  ChartLayout& L = out.layout;
  const int nt = g.num_triangles;
  // Charts: flood fill across edges with equal labels.
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
  // Chart adjacency and boundary edges.
  const int ne = static_cast<int>(g.edges.size());
  std::vector<char> is_bedge(static_cast<std::size_t>(ne), 0);
  std::vector<std::pair<int, int>> pairs;
  for (int e = 0; e < ne; ++e) {
    const int c0 = L.triangle_chart[g.edge_triangles[e][0]];
    const int c1 = L.triangle_chart[g.edge_triangles[e][1]];
    if (c0 == c1) continue;
    is_bedge[e] = 1;
    pairs.emplace_back(std::min(c0, c1), std::max(c0, c1));
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  L.chart_neighbors.assign(static_cast<std::size_t>(L.num_charts()), {});
  for (const auto& [a, b] : pairs) {
    L.chart_neighbors[a].push_back(b);
    L.chart_neighbors[b].push_back(a);
  }
  for (auto& n : L.chart_neighbors) std::sort(n.begin(), n.end());

  // Valence of vertices.
  std::vector<int> valence(static_cast<std::size_t>(g.num_vertices), 0);
  for (int e = 0; e < ne; ++e)
    if (is_bedge[e]) {
      ++valence[g.edges[e][0]];
      ++valence[g.edges[e][1]];
    }
  for (int v = 0; v < g.num_vertices; ++v)
    if (valence[v] >= 3) L.corners.push_back(v);

  // Boundaries: chains between corners.
  std::vector<char> seen(static_cast<std::size_t>(ne), 0);
  for (int e0 = 0; e0 < ne; ++e0) {
    if (!is_bedge[e0] || seen[e0]) continue;
    ++L.num_boundaries;
    seen[e0] = 1;
    for (int side = 0; side < 2; ++side) {
      int v = g.edges[e0][side];
      int e = e0;
      while (valence[v] == 2) {
        int next = -1;
        for (const int f : g.vertex_edges[v])
          if (f != e && is_bedge[f]) next = f;
        if (next < 0 || seen[next]) break;
        seen[next] = 1;
        e = next;
        v = g.edges[e][0] == v ? g.edges[e][1] : g.edges[e][0];
      }
    }
  }

  // Rule 1: at least 4 neighbouring charts.
  for (int c = 0; c < L.num_charts(); ++c) {
    const int k = static_cast<int>(L.chart_neighbors[c].size());
    if (k >= 4) continue;
    Defect d{DefectKind::TooFewNeighbors, {c}, -1, {}};
    if (with_reasons)
      d.reason = fmt::format("chart {} ({}, {} triangles) has {} neighbouring chart(s), needs at least 4",
                             c, label_name(L.chart_label[c]), L.chart_triangles[c], k);
    out.defects.push_back(std::move(d));
  }
  // Rule 2: no opposite labels across a boundary.
  for (const auto& [a, b] : pairs) {
    if (L.chart_label[a] != opposite_label(L.chart_label[b])) continue;
    Defect d{DefectKind::OppositeNeighbors, {a, b}, -1, {}};
    if (with_reasons)
      d.reason = fmt::format("charts {} ({}) and {} ({}) have opposite labels and share a boundary",
                             a, label_name(L.chart_label[a]), b, label_name(L.chart_label[b]));
    out.defects.push_back(std::move(d));
  }
  // Rule 3: corners of valence 3 with three distinct charts of distinct axes.
  for (const int v : L.corners) {
    std::vector<int> charts;
    for (const int t : g.vertex_triangles[v]) charts.push_back(L.triangle_chart[t]);
    std::sort(charts.begin(), charts.end());
    charts.erase(std::unique(charts.begin(), charts.end()), charts.end());
    bool ok = valence[v] == 3 && charts.size() == 3;
    if (ok) {
      const int a0 = label_axis(L.chart_label[charts[0]]);
      const int a1 = label_axis(L.chart_label[charts[1]]);
      const int a2 = label_axis(L.chart_label[charts[2]]);
      ok = a0 != a1 && a1 != a2 && a0 != a2;
    }
    if (ok) continue;
    Defect d{DefectKind::InvalidCorner, charts, v, {}};
    if (with_reasons) {
      std::string names;
      for (const int c : charts)
        names += fmt::format("{}{} ({})", names.empty() ? "" : ", ", c, label_name(L.chart_label[c]));
      d.reason = valence[v] != 3
                     ? fmt::format("corner at vertex {} has valence {} (needs 3); charts: {}", v,
                                   valence[v], names)
                 : charts.size() != 3
                     ? fmt::format("corner at vertex {} joins a chart twice; charts: {}", v, names)
                     : fmt::format("corner at vertex {} joins charts with a repeated axis: {}", v, names);
    }
    out.defects.push_back(std::move(d));
  }
  return out;
}

int defect_count(const LabelingCheck& check) { return static_cast<int>(check.defects.size()); }

}  // namespace detail

}  // namespace polycube::construct
