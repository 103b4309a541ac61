//! Repairs that never move a surface (see repair.h).
#include "repair/repair.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <set>

namespace polycube::repair {

namespace {

//! Maps every vertex to the first vertex (in file order) at exactly its coordinates.
std::vector<int> first_at_same_point(const std::vector<core::Vec3>& points, int& merged) {
  std::vector<int> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  const auto less = [&](int a, int b) {
    const core::Vec3 &p = points[static_cast<std::size_t>(a)],
                     &q = points[static_cast<std::size_t>(b)];
    if (p.x() != q.x()) return p.x() < q.x();
    if (p.y() != q.y()) return p.y() < q.y();
    if (p.z() != q.z()) return p.z() < q.z();
    return a < b;  // equal points: the earlier one first
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<int> to(points.size());
  std::iota(to.begin(), to.end(), 0);
  for (std::size_t i = 1; i < order.size(); ++i) {
    const auto prev = static_cast<std::size_t>(order[i - 1]),
               cur = static_cast<std::size_t>(order[i]);
    if (points[prev] == points[cur]) {
      to[cur] = to[prev];
      ++merged;
    }
  }
  return to;
}

//! The triangle turned so that its smallest vertex comes first: equal for the same triangle in
//! the same turning order.
core::Tri canonical(const core::Tri& t) {
  const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  return {t[static_cast<std::size_t>(k)], t[static_cast<std::size_t>((k + 1) % 3)],
          t[static_cast<std::size_t>((k + 2) % 3)]};
}

}  // namespace

std::vector<std::string> RepairReport::lines() const {
  std::vector<std::string> out;
  if (merged_vertices > 0)
    out.push_back(
        fmt::format("merged {} vertices at the same coordinates as another", merged_vertices));
  if (degenerate_triangles > 0)
    out.push_back(fmt::format("dropped {} triangles using a vertex twice", degenerate_triangles));
  if (duplicate_triangles > 0)
    out.push_back(fmt::format("dropped {} triangles repeating another", duplicate_triangles));
  if (unused_vertices > 0)
    out.push_back(fmt::format("dropped {} vertices of no triangle", unused_vertices));
  return out;
}

RepairReport repair_surface(core::TriMesh& mesh) {
  RepairReport report;
  const std::vector<int> to = first_at_same_point(mesh.points, report.merged_vertices);
  const bool labelled = mesh.labels.size() == mesh.cells.size();
  std::vector<core::Tri> cells;
  std::vector<int> labels;
  std::set<core::Tri> seen;
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    core::Tri c = mesh.cells[t];
    for (int& v : c) v = to[static_cast<std::size_t>(v)];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      ++report.degenerate_triangles;
      continue;
    }
    if (!seen.insert(canonical(c)).second) {
      ++report.duplicate_triangles;
      continue;
    }
    cells.push_back(c);
    if (labelled) labels.push_back(mesh.labels[t]);
  }
  // Keep the used vertices in their order: a mesh that needed nothing keeps its numbering.
  std::vector<int> index(mesh.points.size(), -1);
  for (const core::Tri& c : cells)
    for (const int v : c) index[static_cast<std::size_t>(v)] = 0;
  std::vector<core::Vec3> points;
  for (std::size_t v = 0; v < mesh.points.size(); ++v) {
    if (index[v] < 0) continue;
    index[v] = static_cast<int>(points.size());
    points.push_back(mesh.points[v]);
  }
  report.unused_vertices =
      static_cast<int>(mesh.points.size() - points.size()) - report.merged_vertices;
  if (!report.changed()) return report;
  for (core::Tri& c : cells)
    for (int& v : c) v = index[static_cast<std::size_t>(v)];
  mesh.points = std::move(points);
  mesh.cells = std::move(cells);
  if (labelled) mesh.labels = std::move(labels);
  return report;
}

}  // namespace polycube::repair
