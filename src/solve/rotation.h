#pragma once
//! \file rotation.h
//! \brief The rotation closest to a 3 by 3 matrix (polar decomposition), as used by the
//! as-rigid-as-possible local steps of the deformations.

#include <Eigen/Core>
#include <Eigen/SVD>

namespace polycube::solve {

//! Rotation R (det +1) minimizing |J − R| in the Frobenius norm.
inline Eigen::Matrix3d closest_rotation(const Eigen::Matrix3d& J) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(J, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d V = svd.matrixV();
  if ((U * V.transpose()).determinant() < 0) U.col(2) = -U.col(2);
  return U * V.transpose();
}

}  // namespace polycube::solve
