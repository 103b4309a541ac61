//! Midpoint subdivision of a coarse surface (see coarse_surface.h).
#include "construct/coarse_surface.h"

#include <algorithm>
#include <array>
#include <map>
#include <utility>

namespace polycube::construct {

double longest_edge(const core::TriMesh& surface) {
  double longest = 0.0;
  for (const core::Tri& t : surface.cells)
    for (int e = 0; e < 3; ++e)
      longest = std::max(longest, (surface.points[t[e]] - surface.points[t[(e + 1) % 3]]).norm());
  return longest;
}

namespace {

//! One level: each triangle (a, b, c) into its three corners and the middle one, in order.
core::TriMesh split_once(const core::TriMesh& m) {
  core::TriMesh out;
  out.points = m.points;
  out.cells.reserve(4 * m.cells.size());
  std::map<std::pair<int, int>, int> midpoint;  // ordered: vertex numbering independent of hashing
  const auto mid = [&](int a, int b) {
    const std::pair<int, int> key = std::minmax(a, b);
    const auto [it, added] = midpoint.try_emplace(key, static_cast<int>(out.points.size()));
    if (added) out.points.push_back(0.5 * (m.points[a] + m.points[b]));
    return it->second;
  };
  for (const core::Tri& t : m.cells) {
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.cells.push_back({t[0], ab, ca});
    out.cells.push_back({ab, t[1], bc});
    out.cells.push_back({ca, bc, t[2]});
    out.cells.push_back({ab, bc, ca});
  }
  return out;
}

}  // namespace

core::TriMesh subdivide_to(const core::TriMesh& surface, double max_edge, int max_triangles,
                           SurfaceRefinement& done) {
  done = {};
  done.triangles_before = surface.num_cells();
  done.longest_edge_before = longest_edge(surface);
  core::TriMesh out = surface;
  double longest = done.longest_edge_before;
  while (longest > max_edge && 4 * static_cast<long>(out.num_cells()) <= max_triangles) {
    out = split_once(out);
    longest *= 0.5;  // every edge is halved
    ++done.levels;
  }
  done.triangles_after = out.num_cells();
  done.longest_edge_after = longest_edge(out);
  return out;
}

}  // namespace polycube::construct
