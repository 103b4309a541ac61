//! Reopening of flipped corner fans (see corner_fans.h).
#include "mapping/corner_fans.h"

#include "core/polycube_map.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

namespace polycube::mapping {

ReopenedFans reopen_flipped_fans(const std::vector<core::Tri>& tris, const std::vector<int>& labels,
                                 std::vector<core::Vec3>& P) {
  ReopenedFans out;
  std::map<int, std::vector<int>> vertex_tris;  // ordered: deterministic
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int v : tris[f]) vertex_tris[v].push_back(static_cast<int>(f));
  auto label_set = [&](int v) {
    unsigned m = 0;
    for (int f : vertex_tris[v]) m |= 1u << labels[f];
    return m;
  };
  const double two_pi = 2.0 * std::numbers::pi;
  for (const auto& [c, around] : vertex_tris) {
    unsigned axes = 0;
    for (int f : around) axes |= 1u << (labels[f] / 2);
    if (axes != 7u) continue;
    for (int l = 0; l < 6; ++l) {
      // The chart's fan: triangles (c, a, b) in outward (counter-clockwise) order.
      std::map<int, int> next;  // a -> b
      std::map<int, int> prev;  // b -> a
      bool flipped = false;
      for (int f : around) {
        if (labels[f] != l) continue;
        const auto& t = tris[f];
        const int i = static_cast<int>(std::find(t.begin(), t.end(), c) - t.begin());
        next[t[(i + 1) % 3]] = t[(i + 2) % 3];
        prev[t[(i + 2) % 3]] = t[(i + 1) % 3];
        flipped = flipped || !core::faces_label(P, t, labels[f]);
      }
      if (!flipped || next.size() < 2) continue;
      int first = -1;
      for (const auto& [a, b] : next)
        if (!prev.count(a)) first = first < 0 ? a : -2;
      if (first < 0) continue;  // closed fan or several fans of this chart
      std::vector<int> spokes{first};
      while (next.count(spokes.back()) && spokes.size() <= next.size()) spokes.push_back(next[spokes.back()]);
      if (spokes.size() != next.size() + 1) continue;
      // Inner spokes: on this chart only (free in its plane).
      bool free = true;
      for (std::size_t i = 1; i + 1 < spokes.size() && free; ++i) free = label_set(spokes[i]) == (1u << l);
      if (!free) continue;
      const int a = l / 2, u = (a + 1) % 3, w = (a + 2) % 3;
      const double sense = l % 2 == 0 ? 1.0 : -1.0;  // counter-clockwise seen from the label
      auto angle = [&](int v) { return std::atan2(sense * (P[v][w] - P[c][w]), P[v][u] - P[c][u]); };
      const double a0 = angle(spokes.front());
      double sweep = angle(spokes.back()) - a0;
      while (sweep <= 0) sweep += two_pi;
      while (sweep > two_pi) sweep -= two_pi;
      const int k = static_cast<int>(spokes.size()) - 1;
      if (sweep / k >= std::numbers::pi) continue;  // too few triangles for this sweep
      double mean_r = 0;
      for (int v : spokes) mean_r += std::hypot(P[v][u] - P[c][u], P[v][w] - P[c][w]);
      mean_r /= static_cast<double>(spokes.size());
      for (int i = 1; i < k; ++i) {
        const int v = spokes[i];
        const double r = std::max(std::hypot(P[v][u] - P[c][u], P[v][w] - P[c][w]), 0.5 * mean_r);
        const double phi = a0 + sweep * i / k;
        P[v][u] = P[c][u] + r * std::cos(phi);
        P[v][w] = P[c][w] + sense * r * std::sin(phi);
        out.vertices.push_back(v);
      }
      ++out.fans;
    }
  }
  std::sort(out.vertices.begin(), out.vertices.end());
  out.vertices.erase(std::unique(out.vertices.begin(), out.vertices.end()), out.vertices.end());
  return out;
}

}  // namespace polycube::mapping
