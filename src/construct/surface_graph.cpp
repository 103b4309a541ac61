#include "construct/surface_graph.h"

#include "core/errors.h"

#include <fmt/format.h>
#include <Eigen/Geometry>

namespace polycube::construct::detail {

SurfaceGraph build_surface_graph(const core::TriMesh& s) {
  SurfaceGraph g;
  g.num_triangles = s.num_cells();
  g.num_vertices = s.num_points();
  g.triangles.assign(s.cells.begin(), s.cells.end());
  const auto et = core::unique_edges(s);
  g.edges = et.edges;
  g.triangle_edges.resize(et.cell_edges.size());
  for (std::size_t t = 0; t < et.cell_edges.size(); ++t)
    for (int k = 0; k < 3; ++k) g.triangle_edges[t][k] = et.cell_edges[t][k];
  const auto ec = core::edge_cells(et);
  g.edge_triangles.resize(g.edges.size());
  for (int e = 0; e < et.num_edges(); ++e) {
    if (ec.degree(e) != 2)
      throw core::InputError(fmt::format(
          "the surface is not a closed manifold: edge {}-{} has {} triangle(s)", g.edges[e][0],
          g.edges[e][1], ec.degree(e)));
    g.edge_triangles[e] = {ec[e][0], ec[e][1]};
  }
  g.vertex_triangles = core::vertex_cells(s);
  // vertex -> edges
  std::vector<int> count(static_cast<std::size_t>(g.num_vertices) + 1, 0);
  for (const auto& e : g.edges) {
    ++count[e[0] + 1];
    ++count[e[1] + 1];
  }
  for (int v = 0; v < g.num_vertices; ++v) count[v + 1] += count[v];
  g.vertex_edges.offsets = count;
  g.vertex_edges.items.resize(static_cast<std::size_t>(count.back()));
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int e = 0; e < static_cast<int>(g.edges.size()); ++e) {
    g.vertex_edges.items[fill[g.edges[e][0]]++] = e;
    g.vertex_edges.items[fill[g.edges[e][1]]++] = e;
  }
  g.normals.resize(s.cells.size());
  g.centroids.resize(s.cells.size());
  g.areas.resize(s.cells.size());
  for (int t = 0; t < g.num_triangles; ++t) {
    const auto& c = s.cells[t];
    const core::Vec3 n = (s.points[c[1]] - s.points[c[0]]).cross(s.points[c[2]] - s.points[c[0]]);
    const double len = n.norm();
    g.areas[t] = 0.5 * len;
    g.normals[t] = len > 0.0 ? core::Vec3(n / len) : core::Vec3::Zero();
    g.centroids[t] = (s.points[c[0]] + s.points[c[1]] + s.points[c[2]]) / 3.0;
    g.total_area += g.areas[t];
  }
  g.edge_lengths.resize(g.edges.size());
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    g.edge_lengths[e] = (s.points[g.edges[e][1]] - s.points[g.edges[e][0]]).norm();
  return g;
}

}  // namespace polycube::construct::detail
