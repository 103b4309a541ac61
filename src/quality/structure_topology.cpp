#include "quality/structure_topology.h"

#include "core/elements.h"

#include <algorithm>

namespace polycube::quality {

namespace {

//! Local edge index (kHexEdges) of each side of each hex face (kHexFaces), side k joining
//! face corners k and k+1.
constexpr std::array<std::array<int, 4>, 6> make_hex_face_edges() {
  std::array<std::array<int, 4>, 6> t{};
  for (int f = 0; f < 6; ++f)
    for (int k = 0; k < 4; ++k) {
      const int a = core::kHexFaces[f][k], b = core::kHexFaces[f][(k + 1) % 4];
      for (int e = 0; e < 12; ++e) {
        const auto& le = core::kHexEdges[e];
        if ((le[0] == a && le[1] == b) || (le[0] == b && le[1] == a)) t[f][k] = e;
      }
    }
  return t;
}
constexpr auto kHexFaceEdges = make_hex_face_edges();


}  // namespace

HexTopology hex_topology(const core::HexMesh& mesh) {
  HexTopology t;
  t.edges = core::unique_edges(mesh);
  t.faces = core::unique_faces(mesh);
  t.edge_cells = core::edge_cells(t.edges);

  const int nf = t.faces.num_faces();
  const int ne = t.edges.num_edges();
  t.face_edges.resize(nf);
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(static_cast<std::size_t>(nf) * 4);
  t.edge_on_boundary.assign(ne, 0);
  for (int f = 0; f < nf; ++f) {
    const int c = t.faces.face_cells[f][0];
    const int lf = t.faces.face_local[f][0];
    for (int k = 0; k < 4; ++k) {
      const int e = t.edges.cell_edges[c][kHexFaceEdges[lf][k]];
      t.face_edges[f][k] = e;
      pairs.emplace_back(e, f);
      if (t.faces.is_boundary(f)) t.edge_on_boundary[e] = 1;
    }
  }
  t.edge_faces = core::adjacency_from_pairs(ne, std::move(pairs));
  return t;
}

QuadTopology quad_topology(const core::QuadMesh& mesh) {
  QuadTopology t;
  t.edges = core::unique_edges(mesh);
  t.edge_cells = core::edge_cells(t.edges);
  const int nv = mesh.num_points();
  const int ne = t.edges.num_edges();

  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(static_cast<std::size_t>(ne) * 2);
  t.edge_on_boundary.assign(ne, 0);
  t.vertex_on_boundary.assign(nv, 0);
  for (int e = 0; e < ne; ++e) {
    const auto& ab = t.edges.edges[e];
    pairs.emplace_back(ab[0], e);
    if (ab[1] != ab[0]) pairs.emplace_back(ab[1], e);
    if (t.edge_cells.degree(e) != 2) {
      t.edge_on_boundary[e] = 1;
      t.vertex_on_boundary[ab[0]] = 1;
      t.vertex_on_boundary[ab[1]] = 1;
    }
  }
  t.vertex_edges = core::adjacency_from_pairs(nv, std::move(pairs));

  t.vertex_quads.assign(nv, 0);
  for (const auto& q : mesh.cells) {
    // Count each quad once per distinct vertex (a degenerate quad may repeat one).
    std::array<int, 4> v = q;
    std::sort(v.begin(), v.end());
    for (int i = 0; i < 4; ++i)
      if (i == 0 || v[i] != v[i - 1]) ++t.vertex_quads[v[i]];
  }
  return t;
}

}  // namespace polycube::quality
