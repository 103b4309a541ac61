#include "padding/padding_topology.h"

#include "core/elements.h"
#include "core/topology.h"

#include <algorithm>
#include <map>

namespace polycube::padding::detail {

Topology build_topology(const core::HexMesh& mesh) {
  Topology tp;
  tp.t = quality::hex_topology(mesh);
  tp.num_hexes = mesh.num_cells();
  const int nv = mesh.num_points();
  const int nf = tp.t.num_faces();
  const int ne = tp.t.num_edges();
  std::vector<std::pair<int, int>> vf, ve, vh;
  for (int f = 0; f < nf; ++f)
    for (int v : tp.t.faces.faces[f]) vf.emplace_back(v, f);
  for (int e = 0; e < ne; ++e)
    for (int v : tp.t.edges.edges[e]) ve.emplace_back(v, e);
  for (int h = 0; h < tp.num_hexes; ++h)
    for (int v : mesh.cells[h]) vh.emplace_back(v, h);
  tp.vertex_faces = core::adjacency_from_pairs(nv, std::move(vf));
  tp.vertex_edges = core::adjacency_from_pairs(nv, std::move(ve));
  tp.vertex_hexes = core::adjacency_from_pairs(nv, std::move(vh));
  tp.edge_boundary.assign(ne, {-1, -1});
  for (int e = 0; e < ne; ++e) {
    int k = 0;
    for (int f : tp.t.edge_faces[e])
      if (tp.t.faces.is_boundary(f) && k < 2) tp.edge_boundary[e][k++] = f;
  }
  return tp;
}

std::vector<int> cells_around(const core::HexMesh& mesh, const Topology& tp, int e) {
  const auto [v, w] = tp.t.edges.edges[e];
  std::map<int, std::array<int, 2>> entry_exit;  // hex -> {entry facet, exit facet}
  for (int h : tp.t.edge_cells[e]) {
    std::array<int, 2> ee{-1, -1};
    for (int lf = 0; lf < 6; ++lf) {
      const auto& q = core::kHexFaces[lf];
      for (int k = 0; k < 4; ++k) {
        const int a = mesh.cells[h][q[k]], b = mesh.cells[h][q[(k + 1) % 4]];
        if (a == v && b == w) ee[1] = tp.t.faces.cell_faces[h][lf];
        if (a == w && b == v) ee[0] = tp.t.faces.cell_faces[h][lf];
      }
    }
    entry_exit[h] = ee;
  }
  int start = entry_exit.begin()->first;
  for (const auto& [h, ee] : entry_exit)
    if (tp.t.faces.is_boundary(ee[0])) start = h;
  std::vector<int> cycle;
  int h = start;
  const int first_entry = entry_exit[start][0];
  if (tp.t.faces.is_boundary(first_entry)) cycle.push_back(tp.ghost(first_entry));
  for (std::size_t guard = 0; guard <= entry_exit.size(); ++guard) {
    cycle.push_back(h);
    const int exit = entry_exit[h][1];
    const auto [c0, c1] = tp.t.faces.face_cells[exit];
    if (c1 < 0) {
      cycle.push_back(tp.ghost(exit));
      break;
    }
    h = c0 == h ? c1 : c0;
    if (h == start) break;
  }
  return cycle;
}


std::vector<int> facets_around(const core::HexMesh& mesh, const Topology& tp, int e) {
  const std::vector<int> cycle = cells_around(mesh, tp, e);
  const bool boundary = tp.t.edge_on_boundary[e] != 0;
  const int n = static_cast<int>(cycle.size());
  std::vector<int> facets;
  for (int k = 0; k + 1 < n || (!boundary && k < n); ++k) {
    const int a = cycle[k], b = cycle[(k + 1) % n];
    // A ghost meets its hex through its own facet; two hexes through the facet they share.
    if (a >= tp.num_hexes) { facets.push_back(a - tp.num_hexes); continue; }
    if (b >= tp.num_hexes) { facets.push_back(b - tp.num_hexes); continue; }
    for (int f : tp.t.edge_faces[e]) {
      const auto& c = tp.t.faces.face_cells[f];
      if ((c[0] == a && c[1] == b) || (c[0] == b && c[1] == a)) {
        facets.push_back(f);
        break;
      }
    }
  }
  return facets;
}

}  // namespace polycube::padding::detail
