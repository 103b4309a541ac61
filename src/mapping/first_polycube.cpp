//! The first polycube of a labeled tet mesh (see first_polycube.h).
#include "mapping/first_polycube.h"

#include "core/errors.h"
#include "core/log.h"
#include "solve/rotation.h"
#include "solve/sparse_solver.h"
#include "solve/untangle.h"

#include <Eigen/LU>
#include <Eigen/SparseCore>

namespace polycube::mapping {

namespace {

using core::Vec3;

//! Variables from positions X: free coordinates as they are, chart coordinates the mean of
//! their vertices' coordinates.
Eigen::VectorXd variables_from(const LabeledTetMesh& lm, const MapVariables& mv, const std::vector<Vec3>& X) {
  const int num_groups = lm.charts.num_groups;
  Eigen::VectorXd y = Eigen::VectorXd::Zero(mv.count);
  std::vector<double> count(static_cast<std::size_t>(num_groups), 0.0);
  for (int v = 0; v < lm.mesh.num_points(); ++v)
    for (int d = 0; d < 3; ++d) {
      const int j = mv.var[3 * static_cast<std::size_t>(v) + d];
      y[j] += X[v][d];
      if (j < num_groups) count[j] += 1.0;
    }
  for (int j = 0; j < num_groups; ++j) y[j] /= count[j];
  return y;
}

//! Positions from variables (chart coordinates copied from their variable, hence exactly shared).
std::vector<Vec3> positions_from(const MapVariables& mv, const Eigen::VectorXd& y) {
  const std::size_t nv = mv.var.size() / 3;
  std::vector<Vec3> P(nv);
  for (std::size_t v = 0; v < nv; ++v)
    for (int d = 0; d < 3; ++d) P[v][d] = y[mv.var[3 * v + d]];
  return P;
}

int count_inverted(const core::TetMesh& mesh, const std::vector<Vec3>& P) {
  int n = 0;
  for (const auto& c : mesh.cells) n += !core::positive_tet(P, c);
  return n;
}

//! Rotation closest to the Jacobian of element t in positions x (flattened).
template <typename Positions>
Eigen::Matrix3d closest_rotation_of(const solve::TetElements& el, int t, const Positions& position) {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) J += position(el.tets[t][i]) * el.gradients[t].row(i);
  return solve::closest_rotation(J);
}

//! As-rigid-as-possible local/global iterations from the variables y (updated in place).
//! Returns the number of tets with det J <= 0 at the end.
int arap(const LabeledTetMesh& lm, const MapVariables& mv, const std::vector<Vec3>& X0, bool start_rotations,
         int iterations, Eigen::VectorXd& y) {
  const core::TetMesh& mesh = lm.mesh;
  const std::vector<int>& var = mv.var;
  const int nvar = mv.count;
  const int nv = mesh.num_points();
  const solve::TetElements el = solve::reference_elements(mesh.points, mesh.cells);
  const solve::LinearReduction R = solve::index_reduction(var, nvar, Eigen::VectorXd::Zero(3 * nv));
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(el.tets.size() * 16 * 3 / 2 + nvar);
  for (int t = 0; t < el.size(); ++t) {
    const Eigen::Matrix4d L = el.weights[t] * el.gradients[t] * el.gradients[t].transpose();
    for (int d = 0; d < 3; ++d)
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
          const int vi = var[3 * static_cast<std::size_t>(el.tets[t][i]) + d];
          const int vj = var[3 * static_cast<std::size_t>(el.tets[t][j]) + d];
          if (vi <= vj) trip.emplace_back(vi, vj, L(i, j));
        }
  }
  const double reg = solve::add_tiny_diagonal(trip, nvar);  // removes the translations' null space
  Eigen::SparseMatrix<double> A(nvar, nvar);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  trip.clear();
  solve::SparseSpdSolver solver;
  if (!solver.factorize(A)) throw core::SolverError("deform: the least-squares system is not positive definite");
  Eigen::VectorXd x = R.apply(y);
  auto at_x = [&](int v) { return x.segment<3>(3 * v); };
  std::vector<Eigen::Matrix3d> rot(el.tets.size(), Eigen::Matrix3d::Identity());
  if (start_rotations)
    for (int t = 0; t < el.size(); ++t) rot[t] = closest_rotation_of(el, t, [&](int v) { return X0[v]; });
  for (int it = 0; it < iterations; ++it) {
    if (it > 0)
      for (int t = 0; t < el.size(); ++t) rot[t] = closest_rotation_of(el, t, at_x);
    Eigen::VectorXd rhs = reg * y;
    for (int t = 0; t < el.size(); ++t) {
      // d/dx of w |X^T G - R|²: rhs_(i,d) += w (G R^T)_(i,d)
      const Eigen::Matrix<double, 4, 3> b = el.weights[t] * el.gradients[t] * rot[t].transpose();
      for (int i = 0; i < 4; ++i)
        for (int d = 0; d < 3; ++d) rhs[var[3 * static_cast<std::size_t>(el.tets[t][i]) + d]] += b(i, d);
    }
    y = solver.solve(rhs);
    x = R.apply(y);
  }
  int inverted = 0;
  for (int t = 0; t < el.size(); ++t) {
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 4; ++i) J += x.segment<3>(3 * el.tets[t][i]) * el.gradients[t].row(i);
    inverted += J.determinant() <= 0;
  }
  return inverted;
}

}  // namespace

FirstPolycube first_polycube(const LabeledTetMesh& lm, const std::vector<Vec3>& X0, double ghost_height,
                             bool start_rotations, const FirstPolycubeOptions& o) {
  const MapVariables mv = map_variables(lm);
  FirstPolycube res;
  Eigen::VectorXd y = variables_from(lm, mv, X0);
  if (o.method == FirstPolycubeMethod::PlanarityFlow) {
    const PlanarityFlowResult fr = planarity_flow(lm.mesh, X0, lm.charts.vertex_group, lm.charts.num_groups,
                                                  lm.boundary, lm.labels, ghost_height, o.flow);
    y = variables_from(lm, mv, fr.points);
    res.flow_iterations = fr.iterations;
    res.flow_residual = fr.residual;
    res.points = positions_from(mv, y);
    res.inverted = count_inverted(lm.mesh, res.points);
    core::logger().info("deform: planarity flow: {} iterations, plane residual {:.3g} edge lengths, {} inverted "
                        "({} tets inverted and {} boundary triangles facing away after the snap), {:.2f} s",
                        fr.iterations, fr.residual, fr.inverted, res.inverted, facing_away(lm, res.points), fr.seconds);
    return res;
  }
  if (o.arap_iterations > 0) res.inverted = arap(lm, mv, X0, start_rotations, o.arap_iterations, y);
  res.points = positions_from(mv, y);
  return res;
}

}  // namespace polycube::mapping
