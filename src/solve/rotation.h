#pragma once
//! \file rotation.h
//! \brief The rotation closest to a 3 by 3 matrix (polar decomposition), as used by the
//! as-rigid-as-possible local steps of the deformations.

#include "solve/svd3.h"

#include <Eigen/Core>

namespace polycube::solve {

//! Rotation R (det +1) minimizing |J − R| in the Frobenius norm. With J = U diag(s) Vᵀ, U and V
//! rotations and the sign of det J on the smallest value (signed_svd3), it is U Vᵀ: tr(Rᵀ J) is
//! largest for Uᵀ R V = I whatever that sign (Eigen's two-sided SVD took twice as long).
inline Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& J) {
  Eigen::Matrix3d U, V;
  Eigen::Vector3d s;
  signed_svd3(J, U, s, V);
  return U * V.transpose();
}

}  // namespace polycube::solve
