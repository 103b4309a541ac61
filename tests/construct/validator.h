#pragma once
// An independent validator of polycube labelings, written for the tests only: it shares no code
// with construct/labeling_check (plain std::map topology, union-find charts).
#include "core/types.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

namespace polycube::test {

struct IndependentVerdict {
  int charts = 0;
  int corners = 0;
  std::vector<std::string> problems;
  bool valid() const { return problems.empty(); }
};

inline IndependentVerdict validate_labeling(const core::TriMesh& s, const std::vector<int>& labels) {
  IndependentVerdict v;
  const int nt = s.num_cells();
  if (static_cast<int>(labels.size()) != nt) {
    v.problems.push_back("wrong number of labels");
    return v;
  }
  for (int l : labels)
    if (l < 0 || l > 5) {
      v.problems.push_back("label out of range");
      return v;
    }
  std::map<std::pair<int, int>, std::vector<int>> edge_tris;
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      int a = s.cells[t][k], b = s.cells[t][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edge_tris[{a, b}].push_back(t);
    }
  std::vector<int> parent(static_cast<std::size_t>(nt));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& [e, ts] : edge_tris) {
    if (ts.size() != 2) {
      v.problems.push_back("surface not closed manifold");
      return v;
    }
    if (labels[ts[0]] == labels[ts[1]]) parent[find(ts[0])] = find(ts[1]);
  }
  std::map<int, int> root_to_chart;
  std::vector<int> chart(static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    auto [it, fresh] = root_to_chart.emplace(find(t), static_cast<int>(root_to_chart.size()));
    chart[t] = it->second;
  }
  v.charts = static_cast<int>(root_to_chart.size());
  std::vector<int> chart_label(static_cast<std::size_t>(v.charts));
  for (int t = 0; t < nt; ++t) chart_label[chart[t]] = labels[t];
  std::vector<std::set<int>> nbrs(static_cast<std::size_t>(v.charts));
  std::map<int, int> vertex_valence;
  std::map<int, std::set<int>> vertex_charts;
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) vertex_charts[s.cells[t][k]].insert(chart[t]);
  for (const auto& [e, ts] : edge_tris) {
    const int c0 = chart[ts[0]], c1 = chart[ts[1]];
    if (c0 == c1) continue;
    nbrs[c0].insert(c1);
    nbrs[c1].insert(c0);
    ++vertex_valence[e.first];
    ++vertex_valence[e.second];
    if (chart_label[c0] / 2 == chart_label[c1] / 2)
      v.problems.push_back("opposite charts " + std::to_string(c0) + "/" + std::to_string(c1) + " touch");
  }
  for (int c = 0; c < v.charts; ++c)
    if (nbrs[c].size() < 4)
      v.problems.push_back("chart " + std::to_string(c) + " has " + std::to_string(nbrs[c].size()) + " neighbours");
  for (const auto& [vert, val] : vertex_valence) {
    if (val < 3) continue;
    ++v.corners;
    const auto& cs = vertex_charts[vert];
    std::set<int> axes;
    for (int c : cs) axes.insert(chart_label[c] / 2);
    if (val != 3 || cs.size() != 3 || axes.size() != 3)
      v.problems.push_back("bad corner at vertex " + std::to_string(vert));
  }
  return v;
}

}  // namespace polycube::test
