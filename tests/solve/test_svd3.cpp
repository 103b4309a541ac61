//! Tests of the 3 × 3 signed singular value decomposition (solve/svd3.h) against Eigen's
//! JacobiSVD, on random matrices and on the untangler's hard cases: flat, inverted, needles,
//! repeated and zero singular values.
#include "solve/rotation.h"
#include "solve/svd3.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <random>
#include <vector>

namespace polycube {
namespace {

std::vector<Eigen::Matrix3d> hard_and_random_matrices() {
  std::mt19937 rng(7);
  std::normal_distribution<double> N;
  auto rotation = [&] { return Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix(); };
  std::vector<Eigen::Matrix3d> out;
  const std::vector<Eigen::Vector3d> values{
      {1, 1, 1},      {1, 1, -1},      {2, 0.5, 0},     {1, 1e-6, -1e-8}, {1, 1e-9, 1e-9},
      {1, 0, 0},      {0, 0, 0},       {1e3, 1e3, 1e3}, {0.5, 0.5, -0.5 + 1e-8}, {1, 1 + 1e-7, 1 - 1e-7},
      {3, 2, -1e-12}, {1e-8, 1e-8, -1e-8}};
  for (const Eigen::Vector3d& v : values) {
    out.push_back(v.asDiagonal());
    for (int k = 0; k < 20; ++k) out.push_back(rotation() * v.asDiagonal() * rotation().transpose());
  }
  for (int k = 0; k < 2000; ++k) {
    Eigen::Matrix3d J;
    for (int i = 0; i < 9; ++i) J(i) = N(rng);
    out.push_back(J);
  }
  return out;
}

TEST(SignedSvd3, RotationsAndOrderedValuesThatRebuildTheMatrixToRoundingError) {
  for (const Eigen::Matrix3d& J : hard_and_random_matrices()) {
    Eigen::Matrix3d U, V;
    Eigen::Vector3d s;
    solve::signed_svd3(J, U, s, V);
    const double scale = std::max(J.norm(), 1e-300);
    EXPECT_LE((U * s.asDiagonal() * V.transpose() - J).norm(), 1e-14 * scale) << J;
    EXPECT_LE((U.transpose() * U - Eigen::Matrix3d::Identity()).norm(), 1e-14) << J;
    EXPECT_LE((V.transpose() * V - Eigen::Matrix3d::Identity()).norm(), 1e-14) << J;
    EXPECT_NEAR(U.determinant(), 1.0, 1e-14) << J;
    EXPECT_NEAR(V.determinant(), 1.0, 1e-14) << J;
    EXPECT_GE(s[0], s[1] - 1e-15 * scale) << J;  // equal values may come out in either order
    EXPECT_GE(s[1], std::abs(s[2]) - 1e-15 * scale) << J;
    // The same values as Eigen's, the last with det J's sign.
    const Eigen::JacobiSVD<Eigen::Matrix3d> ref(J);
    const Eigen::Vector3d expected = ref.singularValues();
    EXPECT_LE((s.cwiseAbs() - expected).norm(), 1e-14 * scale) << J;
    if (std::abs(J.determinant()) > 1e-12 * scale * scale * scale) {
      EXPECT_EQ(s[2] < 0, J.determinant() < 0) << J;
    }
  }
}

TEST(SignedSvd3, SmallValuesOfNearlyFlatMatricesToRelativeAccuracy) {
  // Flat and inverted: singular values 1, 0.5 and -1e-10, rotated on both sides.
  std::mt19937 rng(3);
  std::normal_distribution<double> N;
  for (int k = 0; k < 200; ++k) {
    const Eigen::Matrix3d R1 = Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix();
    const Eigen::Matrix3d R2 = Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix();
    const Eigen::Matrix3d J = R1 * Eigen::Vector3d(1.0, 0.5, -1e-10).asDiagonal() * R2.transpose();
    Eigen::Matrix3d U, V;
    Eigen::Vector3d s;
    solve::signed_svd3(J, U, s, V);
    // J's rounding alone moves its smallest value by about 1e-16, 1e-6 of it; a value derived
    // from JᵀJ would be off by its whole size (its square is below JᵀJ's rounding).
    EXPECT_NEAR(s[2], -1e-10, 1e-5 * 1e-10) << J;
    EXPECT_NEAR(-s[2], Eigen::JacobiSVD<Eigen::Matrix3d>(J).singularValues()[2], 1e-5 * 1e-10) << J;
  }
}

// closest_rotation (solve/rotation.h), from the signed SVD: a rotation, no farther from J than
// any other (random rotations and small turns of it), and Eigen's polar factor where J's two
// smallest singular values differ (elsewhere the closest rotation is not unique).
TEST(ClosestRotation, IsTheNearestRotationForInvertedAndFlatMatricesToo) {
  std::mt19937 rng(11);
  std::normal_distribution<double> N;
  auto rotation = [&] { return Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix(); };
  int compared = 0;
  for (const Eigen::Matrix3d& J : hard_and_random_matrices()) {
    const Eigen::Matrix3d R = solve::closest_rotation(J);
    EXPECT_LE((R.transpose() * R - Eigen::Matrix3d::Identity()).norm(), 1e-14) << J;
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14) << J;
    const double d = (J - R).norm();
    const double slack = 1e-12 * std::max(1.0, J.norm());
    for (int k = 0; k < 5; ++k) {
      EXPECT_LE(d, (J - rotation()).norm() + slack) << J;
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(1e-3, Eigen::Vector3d(N(rng), N(rng), N(rng)).normalized()).toRotationMatrix();
      EXPECT_LE(d, (J - turn * R).norm() + slack) << J;
    }
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::Vector3d sv = svd.singularValues();
    if (sv[1] - sv[2] < 1e-6 * std::max(sv[0], 1e-300) || sv[1] < 1e-6 * sv[0]) continue;
    Eigen::Matrix3d U = svd.matrixU();
    if ((U * svd.matrixV().transpose()).determinant() < 0) U.col(2) = -U.col(2);
    EXPECT_LE((R - U * svd.matrixV().transpose()).norm(), 1e-9) << J;
    ++compared;
  }
  EXPECT_GT(compared, 2000);
}

}  // namespace
}  // namespace polycube
