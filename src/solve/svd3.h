#pragma once
//! \file svd3.h
//! \brief Signed singular value decomposition of a 3 by 3 matrix by one-sided (Hestenes) Jacobi,
//! for the untangler's per-element Hessian projection, where Eigen's general two-sided
//! JacobiSVD took a tenth of an optimization.
//!
//! One-sided Jacobi rotates pairs of columns of B = J V until they are orthogonal; the singular
//! values are then the column lengths. Each rotation's angle comes from the dot products of the
//! current columns (never from JᵀJ formed once), which keeps the small singular values of nearly
//! flat elements to relative accuracy (Demmel and Veselić 1992), the untangler's hard case
//! (eigenvectors of JᵀJ in closed form were tried there and lost the projection's accuracy:
//! 1e-7 of |H| instead of 1e-9).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>

namespace polycube::solve {

//! J = U diag(s) Vᵀ with U and V rotations (det +1), |s₀| ≥ |s₁| ≥ |s₂|, s₀, s₁ ≥ 0 and s₂
//! carrying det J's sign.
//! \param V_start  a rotation to start the sweeps from (null: the identity), e.g. the V of a
//!                 nearby J: its columns are then nearly orthogonal already and fewer sweeps run
inline void signed_svd3(const Eigen::Matrix3d& J, Eigen::Matrix3d& U, Eigen::Vector3d& s, Eigen::Matrix3d& V,
                        const Eigen::Matrix3d* V_start = nullptr) {
  Eigen::Matrix3d B;
  if (V_start) {
    V = *V_start;
    B.noalias() = J * V;
  } else {
    B = J;
    V.setIdentity();
  }
  // A pair is orthogonal once its cosine is below this (a few units in the last place): from
  // there one more sweep would change nothing.
  constexpr double kOrthogonal = 1e-15;
  constexpr int kMaxSweeps = 12;  // quadratic convergence: 3–5 sweeps in practice
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    bool rotated = false;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        const double alpha = B.col(p).squaredNorm(), beta = B.col(q).squaredNorm();
        const double gamma = B.col(p).dot(B.col(q));
        if (!(gamma * gamma > kOrthogonal * kOrthogonal * (alpha * beta))) continue;
        rotated = true;
        // The rotation that zeroes the pair's dot product, its smaller angle (Rutishauser).
        const double zeta = (beta - alpha) / (2.0 * gamma);
        const double t = std::copysign(1.0, zeta) / (std::abs(zeta) + std::sqrt(1.0 + zeta * zeta));
        const double c = 1.0 / std::sqrt(1.0 + t * t), sn = c * t;
        for (int i = 0; i < 3; ++i) {
          const double bp = B(i, p), bq = B(i, q);
          B(i, p) = c * bp - sn * bq;
          B(i, q) = sn * bp + c * bq;
          const double vp = V(i, p), vq = V(i, q);
          V(i, p) = c * vp - sn * vq;
          V(i, q) = sn * vp + c * vq;
        }
      }
    if (!rotated) break;
  }
  // Columns by decreasing length; V stays a rotation (a swap flips its determinant, and so
  // does negating a column with B's).
  Eigen::Vector3d len(B.col(0).squaredNorm(), B.col(1).squaredNorm(), B.col(2).squaredNorm());
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j + 1 < 3 - pass; ++j)
      if (len[j] < len[j + 1]) {
        std::swap(len[j], len[j + 1]);
        B.col(j).swap(B.col(j + 1));
        V.col(j).swap(V.col(j + 1));
      }
  if (V.determinant() < 0) {
    V.col(2) = -V.col(2);
    B.col(2) = -B.col(2);
  }
  // U: the first column's direction, the second made orthogonal to it, the third their cross
  // product, so U is a rotation whatever J's rank; the third value then takes det J's sign.
  const double n0 = std::sqrt(len[0]);
  U.col(0) = n0 > 0 ? Eigen::Vector3d(B.col(0) / n0) : Eigen::Vector3d::UnitX();
  Eigen::Vector3d u1 = B.col(1) - U.col(0).dot(B.col(1)) * U.col(0);
  if (!(u1.squaredNorm() > 0))  // rank one or zero: any direction orthogonal to the first
    u1 = std::abs(U(0, 0)) < 0.9 ? Eigen::Vector3d::UnitX().cross(U.col(0)) : Eigen::Vector3d::UnitY().cross(U.col(0));
  U.col(1) = u1.normalized();
  U.col(2) = U.col(0).cross(U.col(1));
  s = Eigen::Vector3d(n0, U.col(1).dot(B.col(1)), U.col(2).dot(B.col(2)));
}

}  // namespace polycube::solve
