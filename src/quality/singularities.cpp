#include "quality/singularities.h"

namespace polycube::quality {

HexSingularities hex_singularities(const core::HexMesh& mesh) {
  return hex_singularities(mesh, hex_topology(mesh));
}

HexSingularities hex_singularities(const core::HexMesh& mesh, const HexTopology& topology) {
  HexSingularities s;
  const int ne = topology.num_edges();
  s.edge_singular.assign(ne, 0);
  std::vector<int> singular_around(mesh.points.size(), 0);
  for (int e = 0; e < ne; ++e) {
    const int valence = topology.edge_valence(e);
    const bool boundary = topology.edge_on_boundary[e] != 0;
    const bool singular = boundary ? valence != 2 : valence != 4;
    if (!singular) continue;
    s.edge_singular[e] = 1;
    ++s.singular_edges;
    if (boundary) {
      ++s.boundary_singular_edges;
      ++s.boundary_valence[valence];
    } else {
      ++s.interior_singular_edges;
      ++s.interior_valence[valence];
    }
    const auto& ab = topology.edges.edges[e];
    ++singular_around[ab[0]];
    if (ab[1] != ab[0]) ++singular_around[ab[1]];
  }
  s.vertex_singular.assign(mesh.points.size(), 0);
  for (std::size_t v = 0; v < singular_around.size(); ++v)
    if (singular_around[v] != 0 && singular_around[v] != 2) {
      s.vertex_singular[v] = 1;
      ++s.singular_vertices;
    }
  return s;
}

QuadSingularities quad_singularities(const core::QuadMesh& mesh) {
  return quad_singularities(mesh, quad_topology(mesh));
}

QuadSingularities quad_singularities(const core::QuadMesh& mesh, const QuadTopology& topology) {
  QuadSingularities s;
  const std::size_t nv = mesh.points.size();
  s.vertex_singular.assign(nv, 0);
  for (std::size_t v = 0; v < nv; ++v) {
    const int quads = topology.vertex_quads[v];
    if (quads == 0) continue;  // unreferenced point
    const bool boundary = topology.vertex_on_boundary[v] != 0;
    const bool singular = boundary ? quads != 2 : quads != 4;
    if (!singular) continue;
    s.vertex_singular[v] = 1;
    ++s.singular_vertices;
    if (boundary) {
      ++s.boundary_singular_vertices;
      ++s.boundary_valence[quads];
    } else {
      ++s.interior_valence[quads];
    }
  }
  return s;
}

}  // namespace polycube::quality
