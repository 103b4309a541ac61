// Tests of the Newton system untangle() assembles (solve::detail::newton_system), against the
// chain rule written out densely: g_y = Σ_t B_tᵀ g_t and H_y = Σ_t B_tᵀ H_t B_t (+ attractions),
// with B_t the rows of the reduction at element t's points. Elements on derived points (a hex's
// face centroids and the tips built from them) take the assembly's reduced path, the others its
// direct one; shared and fixed coordinates are in both; two elements have the hex optimizer's
// right-angled corner frames (the assembly's scaling path).
#include "solve/untangle.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <random>

namespace polycube::solve {
namespace {

using core::Vec3;

//! The unit cube's corners (core/elements.h order) and its six tets around the 0–6 diagonal.
const std::array<Vec3, 8> kCorners{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                   Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
const std::vector<std::array<int, 4>> kCubeTets{{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6},
                                                {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}};

struct Problem {
  TetElements elements;
  LinearReduction reduction;
  Eigen::VectorXd y;
  std::vector<Attraction> attractions;
};

//! Orient a tet positively in the given reference positions.
std::array<int, 4> oriented(std::array<int, 4> t, const std::vector<Vec3>& p) {
  const double det = (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]]));
  if (det < 0) std::swap(t[2], t[3]);
  return t;
}

//! The cube's tets over a reduction where vertices 0 and 1 share their x variable and vertex 4's
//! z is fixed; with `derived`, the six face centroids, a tip F0 + F3 − F2 built from three of
//! them, and tets on those points. The current positions are the cube's moved at random by
//! `amplitude` (large: some tets inverted, so the Hessians are projected).
Problem make_problem(bool derived, double amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<int> var(24, -1);
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(24);
  int n = 0;
  for (int v = 0; v < 8; ++v)
    for (int d = 0; d < 3; ++d) {
      if (v == 1 && d == 0) var[3 * v + d] = var[0];  // shares vertex 0's x
      else if (v == 4 && d == 2) fixed[3 * v + d] = 1.0;
      else var[3 * v + d] = n++;
    }
  Problem p;
  p.reduction = index_reduction(var, n, fixed);
  std::vector<Vec3> ref(kCorners.begin(), kCorners.end());
  std::vector<std::array<int, 4>> tets;
  for (const auto& t : kCubeTets) tets.push_back(t);
  if (derived) {
    constexpr std::array<std::array<int, 4>, 6> kFaces{
        {{0, 3, 4, 7}, {1, 2, 5, 6}, {0, 1, 4, 5}, {2, 3, 6, 7}, {0, 1, 2, 3}, {4, 5, 6, 7}}};
    std::vector<DerivedPoint> faces;
    for (const auto& f : kFaces) {
      DerivedPoint q;
      Vec3 c = Vec3::Zero();
      for (int i = 0; i < 4; ++i) {
        q.vertex[i] = f[i];
        q.weight[i] = 0.25;
        c += 0.25 * kCorners[f[i]];
      }
      faces.push_back(q);
      ref.push_back(c);
    }
    const LinearReduction with_faces = with_derived_points(p.reduction, faces);
    DerivedPoint tip;
    tip.vertex = {8, 11, 10, -1};
    tip.weight = {1.0, 1.0, -1.0, 0.0};
    ref.push_back(ref[8] + ref[11] - ref[10]);
    p.reduction = with_derived_points(with_faces, {tip});
    for (const auto& t : std::vector<std::array<int, 4>>{{8, 9, 14, 0}, {10, 11, 12, 6}, {12, 13, 8, 3}, {8, 9, 10, 12}})
      tets.push_back(oriented(t, ref));
  }
  p.elements = reference_elements(ref, tets);
  // Two corner tets of the cube with the hex optimizer's right-angled frames (the assembly's
  // scaling path), axes of lengths 0.9, 1.1 and 1.3.
  for (const std::array<int, 4>& corner : {std::array<int, 4>{0, 1, 3, 4}, std::array<int, 4>{6, 7, 5, 2}}) {
    Eigen::Matrix<double, 4, 3> G = Eigen::Matrix<double, 4, 3>::Zero();
    const Vec3 l(0.9, 1.1, 1.3);
    for (int d = 0; d < 3; ++d) {
      G(d + 1, d) = 1.0 / l[d];
      G(0, d) = -1.0 / l[d];
    }
    p.elements.tets.push_back(corner);
    p.elements.gradients.push_back(G);
    p.elements.weights.push_back(l.prod() / 6.0);
  }
  p.y = Eigen::VectorXd::Zero(n);
  for (int v = 0; v < 8; ++v)
    for (int d = 0; d < 3; ++d)
      if (var[3 * v + d] >= 0) p.y[var[3 * v + d]] = kCorners[v][d] + amplitude * u(rng);
  p.attractions.push_back({2, Vec3(1.2, 0.9, -0.1), 3.0, Vec3(1.0, 0.0, 2.0)});
  p.attractions.push_back({static_cast<int>(ref.size()) - 1, Vec3(0.5, 0.5, 0.5), 0.7});
  return p;
}

//! The chain rule, dense.
std::pair<Eigen::MatrixXd, Eigen::VectorXd> dense_system(const Problem& p, double eps, double lambda) {
  const Eigen::MatrixXd B(p.reduction.B);
  const Eigen::VectorXd x = p.reduction.apply(p.y);
  const auto n = B.cols();
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(n);
  for (int t = 0; t < p.elements.size(); ++t) {
    const auto& tet = p.elements.tets[t];
    const auto& G = p.elements.gradients[t];
    const double w = p.elements.weights[t];
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 4; ++i) J += x.segment<3>(3 * tet[i]) * G.row(i);
    const ElementEnergy e = elliptic_energy(J, eps, lambda);
    const Eigen::Matrix<double, 9, 9> HJ = projected_elliptic_hessian(J, eps, lambda);
    // dJ(d,k)/dx(i,d) = G(i,k): local coordinate 3i+d, vec(J) index 3d+k.
    Eigen::Matrix<double, 12, 9> D = Eigen::Matrix<double, 12, 9>::Zero();
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d)
        for (int k = 0; k < 3; ++k) D(3 * i + d, 3 * d + k) = G(i, k);
    Eigen::MatrixXd Bt(12, n);
    for (int i = 0; i < 4; ++i)
      for (int d = 0; d < 3; ++d) Bt.row(3 * i + d) = B.row(3 * tet[i] + d);
    g += Bt.transpose() * (w * D * e.gradient);
    H += Bt.transpose() * (w * D * HJ * D.transpose()) * Bt;
  }
  for (const Attraction& a : p.attractions)
    for (int d = 0; d < 3; ++d) {
      const Eigen::VectorXd b = B.row(3 * a.vertex + d).transpose();
      g += 2.0 * a.weight * a.axis_weights[d] * (x[3 * a.vertex + d] - a.target[d]) * b;
      H += 2.0 * a.weight * a.axis_weights[d] * b * b.transpose();
    }
  return {H, g};
}

void expect_same_system(const Problem& p, double eps, double lambda) {
  const auto [Hs, gs] = detail::newton_system(p.elements, p.reduction, p.y, eps, lambda, p.attractions);
  const auto [H, g] = dense_system(p, eps, lambda);
  const Eigen::MatrixXd upper(Hs);
  ASSERT_EQ(upper.rows(), H.rows());
  const Eigen::MatrixXd full = upper + upper.transpose() - Eigen::MatrixXd(upper.diagonal().asDiagonal());
  const double scale = H.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  for (Eigen::Index i = 0; i < H.rows(); ++i)
    for (Eigen::Index j = 0; j < H.cols(); ++j) {
      if (i > j) {
        EXPECT_EQ(upper(i, j), 0.0) << "lower entry (" << i << "," << j << ")";
      }
      EXPECT_NEAR(full(i, j), H(i, j), 1e-12 * scale) << "H(" << i << "," << j << ")";
    }
  const double gscale = g.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < g.size(); ++i) EXPECT_NEAR(gs[i], g[i], 1e-12 * gscale) << "g[" << i << "]";
}

TEST(NewtonSystem, IsTheChainRuleOverSharedAndFixedCoordinates) {
  for (unsigned seed : {1u, 2u, 3u}) expect_same_system(make_problem(false, 0.05, seed), 1e-3, 1.0);
}

TEST(NewtonSystem, IsTheChainRuleOverDerivedPointsToo) {
  for (unsigned seed : {1u, 2u, 3u}) expect_same_system(make_problem(true, 0.05, seed), 1e-3, 1.0);
}

TEST(NewtonSystem, IsTheChainRuleOnTangledElementsWhoseHessiansAreProjected) {
  for (unsigned seed : {4u, 5u, 6u, 7u}) {
    const Problem p = make_problem(true, 0.6, seed);
    const Eigen::VectorXd x = p.reduction.apply(p.y);
    int inverted = 0;
    for (int t = 0; t < p.elements.size(); ++t) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 4; ++i) J += x.segment<3>(3 * p.elements.tets[t][i]) * p.elements.gradients[t].row(i);
      inverted += J.determinant() <= 0;
    }
    EXPECT_GT(inverted, 0) << "seed " << seed << " left every tet positive";
    expect_same_system(p, 0.1, 0.5);
  }
}

}  // namespace
}  // namespace polycube::solve
