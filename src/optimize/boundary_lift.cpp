//! Lifted boundary quad corners: an orientation barrier for the hex boundary (see
//! boundary_lift.h).
#include "optimize/boundary_lift.h"

#include "core/errors.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace polycube::optimize {

using core::Vec3;

BoundaryLift lift_boundary(const core::HexMesh& mesh, const TargetSurface& target,
                           const std::vector<double>& edge_length, double weight, bool only_positive) {
  PC_REQUIRE(edge_length.size() == mesh.points.size(), "lift_boundary: one edge length per vertex");
  const core::HexBoundary b = core::boundary(mesh);
  const auto& quads = b.surface.cells;
  // Target normal at each quad's centre (queries in parallel, results in quad order). Only
  // positive quads: the normal of the closest triangle facing the quad's way within the quad's
  // size (TargetSurface::closest_point_facing), so that a quad beside a thin part of the target
  // is not held to the far side's orientation; while untangling a quad's own orientation may be
  // wrong, so it takes the closest triangle's.
  std::vector<Vec3> normal(quads.size());
  tbb::parallel_for(std::size_t{0}, quads.size(), [&](std::size_t f) {
    Vec3 c = Vec3::Zero();
    double h = 0;
    for (int s : quads[f]) {
      c += 0.25 * mesh.points[b.vertex_map[s]];
      h += 0.25 * edge_length[b.vertex_map[s]];
    }
    const auto& q = quads[f];
    const auto at = [&](int i) -> const Vec3& { return mesh.points[b.vertex_map[q[i]]]; };
    normal[f] = only_positive ? target.closest_point_facing(c, (at(2) - at(0)).cross(at(3) - at(1)), h).second
                              : target.normal(c);
  });
  BoundaryLift lift;
  const int nv = mesh.num_points();
  for (std::size_t f = 0; f < quads.size(); ++f)
    for (int i = 0; i < 4; ++i) {
      const int v = b.vertex_map[quads[f][i]];
      const int p = b.vertex_map[quads[f][(i + 1) % 4]];
      const int q = b.vertex_map[quads[f][(i + 3) % 4]];
      const Vec3 ep = mesh.points[p] - mesh.points[v];
      const Vec3 eq = mesh.points[q] - mesh.points[v];
      const double h = edge_length[v] > 0 ? edge_length[v] : std::max(ep.norm(), eq.norm());
      if (!(h > 0)) continue;
      if (only_positive && !(normal[f].dot(ep.cross(eq)) > 0)) {
        ++lift.skipped;
        continue;
      }
      const double lp = std::max(ep.norm(), 0.05 * h);
      const double lq = std::max(eq.norm(), 0.05 * h);
      const int apex = nv + static_cast<int>(lift.base.size());
      lift.base.push_back(v);
      lift.offset.push_back(h * normal[f]);
      Eigen::Matrix<double, 4, 3> G = Eigen::Matrix<double, 4, 3>::Zero();
      const double l[3] = {lp, lq, h};
      for (int d = 0; d < 3; ++d) {
        G(d + 1, d) = 1.0 / l[d];
        G(0, d) = -1.0 / l[d];
      }
      lift.elements.tets.push_back({v, p, q, apex});
      lift.elements.gradients.push_back(G);
      lift.elements.weights.push_back(weight * lp * lq * h / 6.0);
    }
  return lift;
}

solve::LinearReduction with_apexes(const solve::LinearReduction& r, const BoundaryLift& lift) {
  std::vector<solve::DerivedPoint> apexes(lift.base.size());
  for (std::size_t k = 0; k < lift.base.size(); ++k) {
    apexes[k].vertex[0] = lift.base[k];
    apexes[k].weight[0] = 1.0;
    apexes[k].offset = lift.offset[k];
  }
  return solve::with_derived_points(r, apexes);
}

void append(solve::TetElements& to, const solve::TetElements& from) {
  to.tets.insert(to.tets.end(), from.tets.begin(), from.tets.end());
  to.gradients.insert(to.gradients.end(), from.gradients.begin(), from.gradients.end());
  to.weights.insert(to.weights.end(), from.weights.begin(), from.weights.end());
}

}  // namespace polycube::optimize
