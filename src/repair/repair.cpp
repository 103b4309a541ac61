//! The repairs of an input surface (see repair.h).
#include "repair/repair.h"

#include "core/disjoint_sets.h"
#include "core/topology.h"
#include "repair/geometry_repairs.h"

#include <fmt/format.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace polycube::repair {

namespace {

//! Maps every vertex to the first vertex (in file order) at exactly its coordinates.
std::vector<int> first_at_same_point(const std::vector<core::Vec3>& points, RepairReport& report) {
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
      ++report.merged_vertices;
      RepairReport::note(report.sites.merged, points[cur]);
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

//! Steps 1-4 of repair.h: weld exactly equal vertices, drop degenerate and repeated triangles
//! and unused vertices.
void weld(core::TriMesh& mesh, RepairReport& report) {
  const std::vector<int> to = first_at_same_point(mesh.points, report);
  const bool labelled = mesh.labels.size() == mesh.cells.size();
  std::vector<core::Tri> cells;
  std::vector<int> labels;
  std::set<core::Tri> seen;
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    core::Tri c = mesh.cells[t];
    for (int& v : c) v = to[static_cast<std::size_t>(v)];
    if (c[0] == c[1] || c[1] == c[2] || c[2] == c[0]) {
      ++report.degenerate_triangles;
      RepairReport::note(report.sites.degenerate, detail::centre(mesh.points, mesh.cells[t]));
      continue;
    }
    if (!seen.insert(canonical(c)).second) {
      ++report.duplicate_triangles;
      RepairReport::note(report.sites.duplicate, detail::centre(mesh.points, c));
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
  report.unused_vertices = static_cast<int>(mesh.points.size() - points.size()) - report.merged_vertices;
  if (!report.changed()) return;
  for (core::Tri& c : cells)
    for (int& v : c) v = index[static_cast<std::size_t>(v)];
  mesh.points = std::move(points);
  mesh.cells = std::move(cells);
  if (labelled) mesh.labels = std::move(labels);
}

//! Step 5: a vertex whose triangles form several fans (sheets touching at it) gets a copy per
//! fan after the first (fans in the order of their lowest triangle), at the same place.
int split_pinched_vertices(core::TriMesh& mesh, RepairReport::Sites& sites) {
  const std::size_t nv = mesh.points.size();
  std::vector<std::vector<int>> around(nv);
  for (std::size_t t = 0; t < mesh.cells.size(); ++t)
    for (const int v : mesh.cells[t]) around[static_cast<std::size_t>(v)].push_back(static_cast<int>(t));
  int split = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    const std::vector<int>& tris = around[v];
    if (tris.size() < 2) continue;
    // Two triangles around v are in one fan when they share an edge at v (a second vertex).
    core::DisjointSets fans(tris.size());
    std::map<int, int> first_with;  // other vertex -> first triangle (index in tris) using it
    for (std::size_t i = 0; i < tris.size(); ++i)
      for (const int w : mesh.cells[static_cast<std::size_t>(tris[i])]) {
        if (w == static_cast<int>(v)) continue;
        const auto [it, fresh] = first_with.emplace(w, static_cast<int>(i));
        if (!fresh) fans.unite(it->second, static_cast<int>(i));
      }
    std::map<int, int> copy_of_fan;  // fan root -> vertex number (the first fan keeps v)
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const int root = fans.find(static_cast<int>(i));
      auto it = copy_of_fan.find(root);
      if (it == copy_of_fan.end()) {
        const int id = copy_of_fan.empty() ? static_cast<int>(v) : static_cast<int>(mesh.points.size());
        if (id != static_cast<int>(v)) {
          mesh.points.push_back(mesh.points[v]);
          RepairReport::note(sites.split, mesh.points[v]);
          ++split;
        }
        it = copy_of_fan.emplace(root, id).first;
      }
      for (int& w : mesh.cells[static_cast<std::size_t>(tris[i])])
        if (w == static_cast<int>(v)) w = it->second;
    }
  }
  return split;
}

//! Keep the component (through shared vertices) of largest area.
void keep_largest_component(core::TriMesh& mesh, RepairReport& report) {
  core::DisjointSets sets(mesh.points.size());
  for (const core::Tri& t : mesh.cells) {
    sets.unite(t[0], t[1]);
    sets.unite(t[0], t[2]);
  }
  std::map<int, double> area;
  for (const core::Tri& t : mesh.cells) {
    const core::Vec3 &a = mesh.points[t[0]], &b = mesh.points[t[1]], &c = mesh.points[t[2]];
    area[sets.find(t[0])] += 0.5 * (b - a).cross(c - a).norm();
  }
  if (area.size() < 2) return;
  const int keep = std::max_element(area.begin(), area.end(), [](const auto& x, const auto& y) {
                     return x.second < y.second;
                   })->first;
  const bool labelled = mesh.labels.size() == mesh.cells.size();
  std::vector<core::Tri> cells;
  std::vector<int> labels;
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    if (sets.find(mesh.cells[t][0]) != keep) {
      ++report.dropped_triangles;
      continue;
    }
    cells.push_back(mesh.cells[t]);
    if (labelled) labels.push_back(mesh.labels[t]);
  }
  report.dropped_components = static_cast<int>(area.size()) - 1;
  mesh.cells = std::move(cells);
  if (labelled) mesh.labels = std::move(labels);
  core::remove_unreferenced_points(mesh);
}

}  // namespace

std::string places_text(const std::vector<core::Vec3>& places, int count) {
  if (places.empty()) return {};
  std::string s = count > static_cast<int>(places.size()) ? " (first at " : " (at ";
  for (std::size_t i = 0; i < places.size(); ++i)
    s += fmt::format("{}({:.6g}, {:.6g}, {:.6g})", i ? ", " : "", places[i].x(), places[i].y(), places[i].z());
  return s + ")";
}

std::vector<std::string> RepairReport::lines(bool where) const {
  std::vector<std::string> out;
  // One line per kind that happened; with `where`, followed by its first places.
  const auto add = [&](int count, std::string line, const std::vector<core::Vec3>& places) {
    if (count > 0) out.push_back(where ? line + places_text(places, count) : std::move(line));
  };
  add(merged_vertices, fmt::format("merged {} vertices at the same coordinates as another", merged_vertices),
      sites.merged);
  add(degenerate_triangles, fmt::format("dropped {} triangles using a vertex twice", degenerate_triangles),
      sites.degenerate);
  add(duplicate_triangles, fmt::format("dropped {} triangles repeating another", duplicate_triangles),
      sites.duplicate);
  add(unused_vertices, fmt::format("dropped {} vertices of no triangle", unused_vertices), {});
  add(dropped_components,
      fmt::format("kept the largest component: dropped {} other component(s), {} triangles", dropped_components,
                  dropped_triangles),
      {});
  add(split_vertices,
      fmt::format("split {} vertices where separate sheets touched (one copy per sheet)", split_vertices),
      sites.split);
  add(filled_holes, fmt::format("filled {} hole(s) with {} triangles", filled_holes, hole_triangles), sites.filled);
  add(open_holes, fmt::format("left {} hole(s) open: larger than --max-hole", open_holes), sites.open);
  add(turned_triangles, fmt::format("turned {} triangles to face consistently and outward", turned_triangles),
      sites.turned);
  add(wrapped ? 1 : 0,
      fmt::format("replaced the surface by its alpha wrap ({} triangles; alpha {:.4g}, offset {:.4g})", wrap_triangles,
                  wrap_alpha, wrap_offset),
      {});
  return out;
}

RepairReport repair_surface(core::TriMesh& mesh, const RepairOptions& options) {
  RepairReport report;
  weld(mesh, report);
  if (options.wrap) {
    // The wrap replaces the surface: nothing else is needed, and it works on soups.
    const double diagonal = core::bounding_box(mesh.points).diagonal();
    detail::alpha_wrap(mesh, options.wrap_alpha * diagonal, options.wrap_offset * diagonal, report);
    mesh.labels.clear();
    return report;
  }
  if (options.largest_component) keep_largest_component(mesh, report);
  report.split_vertices = split_pinched_vertices(mesh, report.sites);
  if (options.fill_holes) {
    detail::fill_holes(mesh, options.max_hole_edges, report);
    if (report.filled_holes > 0) mesh.labels.clear();
  }
  detail::orient_to_bound_volume(mesh, report);
  return report;
}

}  // namespace polycube::repair
