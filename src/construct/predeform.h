#pragma once
//! \file predeform.h
//! \brief Normal-driven pre-deformation of a tet mesh towards a polycube-like shape, before the
//! labeling (the volumetric deformation family of Gregson, Sheffer, Zhang 2011 and Fu, Bai,
//! Liu 2016; ARCHITECTURE §6.2).
//!
//! On organic shapes the labeling of the model's own normals is noisy: small charts, turning
//! boundaries, corners in nearly flat regions, which the later deformation cannot realize
//! without folds. Rotating the surface towards the axes first, while the volume stays as rigid
//! as possible, gives normals that already cluster around the six directions, so the graph cut
//! finds compact charts with straight boundaries; the deformed positions also give the final
//! deformation its starting rotations.
//!
//! Each iteration is one linear solve (the matrix is factorized once):
//! \f[ \min_X \sum_t w_t \lVert J_t(X) - R_t \rVert^2
//!   + \beta \sum_f \frac{A_f}{\bar e} \sum_{(i,j) \in f} \lVert X_j - X_i - Q_f (X^k_j - X^k_i) \rVert^2 , \f]
//! with R_t the rotation closest to the current Jacobian of tet t (as-rigid-as-possible) and
//! Q_f the rotation taking the current normal of boundary triangle f onto the axis closest to
//! its smoothed normal.

#include "core/types.h"

#include <vector>

namespace polycube::construct {

//! Options of predeform().
struct PredeformOptions {
  int iterations = 0;              //!< local/global iterations (0: no pre-deformation)
  double surface_weight = 4.0;     //!< β, weight of the normal alignment against rigidity
  int smoothing_rings = 2;         //!< triangle rings averaged to choose each triangle's axis
  //! Stop early when the area-weighted mean of 1 − max_axis |n·axis| falls below this.
  double tolerance = 1e-3;
};

//! Result of predeform().
struct PredeformResult {
  std::vector<core::Vec3> points;  //!< #V deformed positions (same connectivity)
  int iterations = 0;              //!< iterations run
  double misalignment_before = 0;  //!< area-weighted mean of 1 − max |n·axis| of the model
  double misalignment_after = 0;   //!< ... of the deformed surface
  int inverted = 0;                //!< tets with det ≤ 0 in the deformed positions (not repaired)
  double seconds = 0;
};

//! Unit normals of triangles at the given positions (zero for a degenerate triangle), e.g. the
//! pre-deformed normals the labeling's fidelity term reads (LabelingOptions::data_normals).
std::vector<core::Vec3> triangle_normals(const std::vector<core::Vec3>& points, const std::vector<core::Tri>& tris);

//! Pre-deform a tet mesh so that its boundary normals approach the six axis directions.
//! \param mesh      positively oriented tet mesh (#V, #T)
//! \param boundary  its #B boundary triangles (volume vertex indices, outward)
//! \throw core::GeometryError when a tet is flat (reference_elements), core::SolverError when
//!        the system cannot be factorized
PredeformResult predeform(const core::TetMesh& mesh, const std::vector<core::Tri>& boundary,
                          const PredeformOptions& options = {});

}  // namespace polycube::construct
