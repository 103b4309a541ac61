//! Normal-driven pre-deformation (see predeform.h).
#include "construct/predeform.h"

#include "core/stopwatch.h"
#include "core/errors.h"
#include "core/log.h"
#include "solve/rotation.h"
#include "solve/sparse_solver.h"
#include "solve/untangle.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

namespace polycube::construct {

namespace {

using core::Vec3;


//! The axis direction (±e_d) closest to n.
Vec3 closest_axis(const Vec3& n) {
  int d = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(n[k]) > std::abs(n[d])) d = k;
  Vec3 a = Vec3::Zero();
  a[d] = n[d] >= 0 ? 1.0 : -1.0;
  return a;
}

//! Rotation of least angle taking unit n onto unit a (identity when they are nearly opposite:
//! the axis is then ambiguous, and the neighbours decide).
Eigen::Matrix3d rotation_onto(const Vec3& n, const Vec3& a) {
  const double c = n.dot(a);
  if (c < -0.999) return Eigen::Matrix3d::Identity();
  const Vec3 v = n.cross(a);
  Eigen::Matrix3d K;
  K << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return Eigen::Matrix3d::Identity() + K + K * K / (1.0 + c);
}

//! Area-weighted normals (unnormalized: length = twice the area) of the boundary triangles.
std::vector<Vec3> area_normals(const std::vector<Vec3>& X, const std::vector<core::Tri>& tris) {
  std::vector<Vec3> n(tris.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto& t = tris[f];
    n[f] = (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]);
  }
  return n;
}

//! Area-weighted mean of 1 − max_d |n·e_d|.
double misalignment(const std::vector<Vec3>& an) {
  double sum = 0, area = 0;
  for (const Vec3& v : an) {
    const double a = v.norm();
    if (a <= 0) continue;
    sum += a * (1.0 - v.cwiseAbs().maxCoeff() / a);
    area += a;
  }
  return area > 0 ? sum / area : 0.0;
}

}  // namespace

std::vector<Vec3> triangle_normals(const std::vector<Vec3>& points, const std::vector<core::Tri>& tris) {
  std::vector<Vec3> n = area_normals(points, tris);
  for (Vec3& v : n)
    if (v.norm() > 0) v.normalize();
  return n;
}

PredeformResult predeform(const core::TetMesh& mesh, const std::vector<core::Tri>& boundary,
                          const PredeformOptions& o) {
  const core::Stopwatch clock;
  PredeformResult res;
  res.points = mesh.points;
  std::vector<Vec3>& X = res.points;
  res.misalignment_before = res.misalignment_after = misalignment(area_normals(X, boundary));
  if (o.iterations <= 0 || boundary.empty()) return res;
  const int nv = mesh.num_points();
  const solve::TetElements el = solve::reference_elements(mesh.points, mesh.cells);

  // Surface weights: β A_f / ē per edge, so the surface term has the units of a volume (a
  // shell one edge thick) like the rigidity term.
  double esum = 0;
  for (const auto& t : boundary)
    for (int e = 0; e < 3; ++e) esum += (X[t[e]] - X[t[(e + 1) % 3]]).norm();
  const double ebar = esum / (3.0 * static_cast<double>(boundary.size()));
  std::vector<double> wf(boundary.size());
  {
    const std::vector<Vec3> an = area_normals(X, boundary);
    for (std::size_t f = 0; f < boundary.size(); ++f) wf[f] = o.surface_weight * 0.5 * an[f].norm() / ebar;
  }

  // The matrix (one scalar Laplacian shared by x, y, z), factorized once.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(el.tets.size() * 10 + boundary.size() * 9 + static_cast<std::size_t>(nv));
  for (int t = 0; t < el.size(); ++t) {
    const Eigen::Matrix4d L = el.weights[t] * el.gradients[t] * el.gradients[t].transpose();
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (el.tets[t][i] <= el.tets[t][j]) trip.emplace_back(el.tets[t][i], el.tets[t][j], L(i, j));
  }
  for (std::size_t f = 0; f < boundary.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int i = boundary[f][e], j = boundary[f][(e + 1) % 3];
      trip.emplace_back(i, i, wf[f]);
      trip.emplace_back(j, j, wf[f]);
      trip.emplace_back(std::min(i, j), std::max(i, j), -wf[f]);
    }
  const double reg = solve::add_tiny_diagonal(trip, nv);  // removes the translations' null space
  Eigen::SparseMatrix<double> A(nv, nv);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  trip = {};
  solve::SparseSpdSolver solver;
  if (!solver.factorize(A)) throw core::SolverError("predeform: the system is not positive definite");

  // Triangle neighbourhoods for the smoothed normals: vertex -> triangles.
  std::vector<std::vector<int>> vtris(static_cast<std::size_t>(nv));
  for (std::size_t f = 0; f < boundary.size(); ++f)
    for (int v : boundary[f]) vtris[v].push_back(static_cast<int>(f));

  Eigen::MatrixXd rhs(nv, 3);
  for (int it = 0; it < o.iterations; ++it) {
    // Local step: tet rotations, triangle rotations onto their axes.
    const std::vector<Vec3> an = area_normals(X, boundary);
    std::vector<Vec3> smooth = an;
    for (int r = 0; r < o.smoothing_rings; ++r) {
      std::vector<Vec3> vn(static_cast<std::size_t>(nv), Vec3::Zero());
      for (std::size_t f = 0; f < boundary.size(); ++f)
        for (int v : boundary[f]) vn[v] += smooth[f];
      for (std::size_t f = 0; f < boundary.size(); ++f)
        smooth[f] = vn[boundary[f][0]] + vn[boundary[f][1]] + vn[boundary[f][2]];
    }
    rhs.setZero();
    for (int v = 0; v < nv; ++v) rhs.row(v) = reg * X[v].transpose();
    for (int t = 0; t < el.size(); ++t) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 4; ++i) J += X[el.tets[t][i]] * el.gradients[t].row(i);
      const Eigen::Matrix<double, 4, 3> b = el.weights[t] * el.gradients[t] * solve::closest_rotation(J).transpose();
      for (int i = 0; i < 4; ++i) rhs.row(el.tets[t][i]) += b.row(i);
    }
    for (std::size_t f = 0; f < boundary.size(); ++f) {
      const double len = an[f].norm(), slen = smooth[f].norm();
      if (len <= 0 || slen <= 0) continue;
      const Eigen::Matrix3d Q = rotation_onto(an[f] / len, closest_axis(smooth[f] / slen));
      for (int e = 0; e < 3; ++e) {
        const int i = boundary[f][e], j = boundary[f][(e + 1) % 3];
        const Vec3 d = wf[f] * (Q * (X[j] - X[i]));
        rhs.row(j) += d.transpose();
        rhs.row(i) -= d.transpose();
      }
    }
    // Global step.
    const Eigen::MatrixXd Y = solver.solve(rhs);
    for (int v = 0; v < nv; ++v) X[v] = Y.row(v).transpose();
    ++res.iterations;
    res.misalignment_after = misalignment(area_normals(X, boundary));
    core::logger().debug("predeform: iteration {}: misalignment {:.4f}", it + 1, res.misalignment_after);
    if (res.misalignment_after < o.tolerance) break;
  }
  for (const auto& c : mesh.cells)
    res.inverted += !core::positive_tet(X, c);
  res.seconds = clock.seconds();
  return res;
}

}  // namespace polycube::construct
