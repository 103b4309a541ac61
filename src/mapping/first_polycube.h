#pragma once
//! \file first_polycube.h
//! \brief The first polycube of a labeled tet mesh (ARCHITECTURE §6.2 step 4): positions with
//! every chart exactly on its plane, from which the untangling starts.

#include "mapping/labeled_mesh.h"
#include "mapping/planarity_flow.h"

#include <vector>

namespace polycube::mapping {

//! How the first polycube is found.
enum class FirstPolycubeMethod {
  //! As-rigid-as-possible least squares under the chart constraints: minimize
  //! Σ_t w_t |J_t − R_t|² with R_t the rotation closest to the current J_t (one sparse
  //! factorization, several local/global iterations). Imposes the planes at once and may fold
  //! tets, which the untangling then unfolds.
  Arap,
  //! The foldover-free planarity flow (planarity_flow.h), snapped onto exact planes: starts the
  //! untangling almost untangled.
  PlanarityFlow,
};

//! Options of first_polycube().
struct FirstPolycubeOptions {
  FirstPolycubeMethod method = FirstPolycubeMethod::Arap;
  int arap_iterations = 15;    //!< local/global iterations of Arap (0: the start's chart means only)
  PlanarityFlowOptions flow;   //!< PlanarityFlow's options
};

//! Result of first_polycube().
struct FirstPolycube {
  std::vector<core::Vec3> points;  //!< #V polycube positions, chart coordinates exactly shared
  int inverted = 0;                //!< tets with det <= 0 in points
  int flow_iterations = 0;         //!< outer iterations of the planarity flow (0: Arap)
  double flow_residual = 0;        //!< its final plane residual (local edge lengths)
};

//! The first polycube of lm from start positions X0 (#V: the model, or a pre-deformation).
//! \param X0               #V start positions: each chart coordinate starts at the mean of its vertices'
//! \param ghost_height     apex height of the planarity flow's ghost tets (model length; 0: none)
//! \param start_rotations  Arap's first rotations are those of X0 (a pre-deformation); else the identity
FirstPolycube first_polycube(const LabeledTetMesh& lm, const std::vector<core::Vec3>& X0, double ghost_height,
                             bool start_rotations, const FirstPolycubeOptions& options = {});

}  // namespace polycube::mapping
