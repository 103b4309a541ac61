//! Quad-centre points of the hex boundary (see face_attraction.h).
#include "optimize/face_attraction.h"

#include "core/topology.h"

namespace polycube::optimize {

std::vector<std::array<int, 4>> boundary_quads(const core::HexMesh& mesh) {
  const core::HexBoundary b = core::boundary(mesh);
  std::vector<std::array<int, 4>> out;
  out.reserve(b.surface.cells.size());
  for (const auto& q : b.surface.cells)
    out.push_back({b.vertex_map[q[0]], b.vertex_map[q[1]], b.vertex_map[q[2]], b.vertex_map[q[3]]});
  return out;
}

solve::LinearReduction with_quad_centres(const solve::LinearReduction& r, const std::vector<std::array<int, 4>>& quads) {
  std::vector<solve::DerivedPoint> centres(quads.size());
  for (std::size_t k = 0; k < quads.size(); ++k) {
    centres[k].vertex = quads[k];
    centres[k].weight = {0.25, 0.25, 0.25, 0.25};
  }
  return solve::with_derived_points(r, centres);
}

}  // namespace polycube::optimize
