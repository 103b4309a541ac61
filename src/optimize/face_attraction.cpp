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
  const auto rows = static_cast<Eigen::Index>(r.B.rows());
  const auto extra = static_cast<Eigen::Index>(3 * quads.size());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(r.B.nonZeros()) + 12 * quads.size());
  for (Eigen::Index i = 0; i < rows; ++i)
    for (decltype(r.B)::InnerIterator it(r.B, i); it; ++it) trip.emplace_back(i, it.col(), it.value());
  solve::LinearReduction out;
  out.x0 = Eigen::VectorXd::Zero(rows + extra);
  out.x0.head(rows) = r.x0;
  for (std::size_t k = 0; k < quads.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Index dst = rows + 3 * static_cast<Eigen::Index>(k) + d;
      for (int v : quads[k]) {
        const Eigen::Index src = 3 * static_cast<Eigen::Index>(v) + d;
        for (decltype(r.B)::InnerIterator it(r.B, src); it; ++it) trip.emplace_back(dst, it.col(), 0.25 * it.value());
        out.x0[dst] += 0.25 * r.x0[src];
      }
    }
  out.B.resize(rows + extra, r.B.cols());
  out.B.setFromTriplets(trip.begin(), trip.end());  // duplicates (a shared variable) are summed
  return out;
}

}  // namespace polycube::optimize
