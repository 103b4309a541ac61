#pragma once
//! \file orientation.h
//! \brief The rotation that best aligns a closed surface with the coordinate axes, before the
//! labeling (ARAP-free and rotation-invariant stages after it do not care; the labeling and
//! the pre-deformation do: a polycube of a model given at 30° to the axes is a staircase).
//!
//! The rotation R minimizes the area-weighted L1 norm of the rotated normals,
//! \f$ E(R) = \sum_f A_f \lVert R n_f \rVert_1 \f$, which is smallest when the normals cluster
//! on the six axis directions (Huang, Jiang, Zhang, Sheffer, Bao 2014 use the same measure).
//! Search: a deterministic grid over rotation angles, refined by halving the step around the
//! best.

#include "core/types.h"

#include <Eigen/Core>

namespace polycube::construct {

//! Result of best_axis_rotation().
struct AxisRotation {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  //!< R (det +1)
  double energy_before = 0;  //!< E(I) / total area (1 for an axis-aligned box, up to √3)
  double energy_after = 0;   //!< E(R) / total area (= energy_before when R = I was kept)
  double energy_best = 0;    //!< the lowest E / area found (kept or not)
};

//! The rotation minimizing the area-weighted L1 norm of the normals. The identity is kept
//! unless another rotation lowers the energy by more than `min_gain` (relative), so shapes
//! already aligned (CAD parts) are left as they are.
//! \param surface  closed surface (#V, #T), outward orientation
AxisRotation best_axis_rotation(const core::TriMesh& surface, double min_gain = 0.02);

}  // namespace polycube::construct
