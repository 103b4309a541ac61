//! Planar sides of a surface (see flat_sides.h).
#include "fabricate/flat_sides.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace polycube::fabricate {

std::vector<FlatSide> planar_sides(const core::TriMesh& mesh, std::vector<int>& triangle_side,
                                   double min_area_fraction) {
  triangle_side.assign(mesh.cells.size(), -1);
  if (mesh.points.empty()) return {};
  const double diagonal = core::bounding_box(mesh.points).extent().norm();
  const double step = 1e-6 * std::max(diagonal, 1e-300);
  // Planes keyed by their quantized normal and offset (std::map: a deterministic order).
  std::map<std::array<long long, 4>, int> plane_of;
  std::vector<FlatSide> planes;
  std::vector<int> plane(mesh.cells.size(), -1);
  double total = 0.0;
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    const auto& c = mesh.cells[t];
    const core::Vec3 an =
        0.5 * (mesh.points[c[1]] - mesh.points[c[0]]).cross(mesh.points[c[2]] - mesh.points[c[0]]);
    const double area = an.norm();
    total += area;
    if (area == 0.0) continue;
    const core::Vec3 n = an / area;
    const std::array<long long, 4> key{std::llround(n.x() * 1e6), std::llround(n.y() * 1e6),
                                       std::llround(n.z() * 1e6),
                                       std::llround(n.dot(mesh.points[c[0]]) / step)};
    const auto [it, added] = plane_of.emplace(key, static_cast<int>(planes.size()));
    if (added) planes.push_back({-1, n, 0.0});
    planes[static_cast<std::size_t>(it->second)].area += area;
    plane[t] = it->second;
  }
  std::vector<int> order;
  for (std::size_t p = 0; p < planes.size(); ++p)
    if (planes[p].area >= min_area_fraction * total) order.push_back(static_cast<int>(p));
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return planes[a].area > planes[b].area; });
  std::vector<int> side_of(planes.size(), -1);
  std::vector<FlatSide> out;
  for (std::size_t k = 0; k < order.size(); ++k) {
    side_of[order[k]] = static_cast<int>(k);
    out.push_back(planes[order[k]]);
  }
  for (std::size_t t = 0; t < mesh.cells.size(); ++t)
    if (plane[t] >= 0) triangle_side[t] = side_of[plane[t]];
  return out;
}

}  // namespace polycube::fabricate
