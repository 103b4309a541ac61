//! Charts of a labeled triangle surface (see charts.h).
#include "core/charts.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"

#include <algorithm>
#include <array>

namespace polycube::core {

TriangleCharts triangle_charts(const std::vector<Tri>& tris, const std::vector<int>& labels) {
  PC_REQUIRE(labels.size() == tris.size(), "triangle_charts: one label per triangle");
  const int nf = static_cast<int>(tris.size());
  // Edges as (low, high, triangle), sorted: the two triangles of a manifold edge are adjacent.
  std::vector<std::array<int, 3>> edges;
  edges.reserve(3 * tris.size());
  for (int t = 0; t < nf; ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = tris[t][e], b = tris[t][(e + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), t});
    }
  std::sort(edges.begin(), edges.end());
  DisjointSets sets(static_cast<std::size_t>(nf));
  for (std::size_t i = 0; i + 1 < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j == i + 2 && labels[edges[i][2]] == labels[edges[i + 1][2]]) sets.unite(edges[i][2], edges[i + 1][2]);
    i = j;
  }
  TriangleCharts charts;
  charts.triangle_chart.assign(static_cast<std::size_t>(nf), -1);
  std::vector<int> chart_of_root(static_cast<std::size_t>(nf), -1);
  for (int t = 0; t < nf; ++t) {
    const int r = sets.find(t);
    if (chart_of_root[r] < 0) chart_of_root[r] = charts.count++;
    charts.triangle_chart[t] = chart_of_root[r];
  }
  return charts;
}

}  // namespace polycube::core
