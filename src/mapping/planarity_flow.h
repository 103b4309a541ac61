#pragma once
//! \file planarity_flow.h
//! \brief Foldover-free flow of a labeled tet mesh towards its polycube (ARAP's alternative for
//! the first polycube of deform_to_polycube(), ARCHITECTURE §6.2 step 4).
//!
//! The linear (as-rigid-as-possible) first polycube imposes the chart planes at once and
//! folds many tets, which the elliptic untangling then has to unfold; where it cannot (tets
//! locked between a polycube corner and the chain of its edge), the map is not certified. The
//! flow instead starts from a foldover-free state (the model) and never leaves it: it
//! minimizes the elliptic energy of Garanzha et al. 2021 (solve/untangle.h, a barrier against
//! inversion once every tet is positive) plus soft attractions of every chart vertex to its
//! chart's current plane, along the chart's axis only,
//! \f[ \sum_t w_t\,E(J_t) + \omega_k \sum_{(v,a)} \frac{V_v}{h_v^2} \big(x_{v,a} - c_{g(v,a)}\big)^2 , \f]
//! with c_g the mean coordinate of chart group g (re-evaluated after every outer iteration),
//! V_v and h_v the volume and mean edge length around v, and ω_k growing geometrically. The
//! charts flatten gradually while every tet keeps a positive volume; the result, snapped onto
//! exact planes, starts the constrained untangling almost untangled.
//!
//! As in deform_to_polycube(), every boundary triangle carries a **ghost tet**: the triangle and
//! an apex attracted to the height h above the triangle's chart plane along its label, so that
//! the barrier also keeps the boundary from folding over itself (a triangle turning to face
//! away from its label), which the real tets alone do not see.

#include "core/types.h"

#include <vector>

namespace polycube::mapping {

//! Options of planarity_flow().
struct PlanarityFlowOptions {
  int iterations = 40;          //!< outer iterations at most (each: Newton steps, then ω grows)
  int newton_steps = 2;         //!< Newton steps per outer iteration
  double initial_weight = 1.0;  //!< ω at the first iteration (dimensionless, see the file comment)
  double growth = 1.5;          //!< ω multiplied by this after every outer iteration
  double max_weight = 1e6;      //!< ω never exceeds this
  //! Stop when every chart vertex is within this many local edge lengths of its chart plane.
  double tolerance = 1e-3;
  double volume_weight = 1.0;   //!< λ of the elliptic energy
  //! ε at the start when the start has inverted tets (a valid start uses 1e-3 · min det).
  double initial_epsilon = 0.05;
  //! ε at the start of the constrained untangling that follows the snap onto exact planes.
  double snap_epsilon = 1e-4;
};

//! Result of planarity_flow().
struct PlanarityFlowResult {
  std::vector<core::Vec3> points;  //!< #V positions after the flow (charts nearly planar)
  int iterations = 0;              //!< outer iterations run
  double residual = 0;             //!< max distance of a chart vertex to its plane / local edge length
  int inverted = 0;                //!< tets with det <= 0 at the end (ghost tets included)
  double seconds = 0;
};

//! Flow a tet mesh towards the planes of its charts without folding it.
//! \param mesh          positively oriented tet mesh (#V, #T): the reference shapes
//! \param start         #V starting positions (the model, or a pre-deformation of it)
//! \param vertex_group  3#V chart group of coordinate (v, axis), −1 when free
//! \param num_groups    number of chart groups
//! \param boundary      #B outward boundary triangles (volume indices) and their labels in 0..5
//! \param ghost_height  h of the ghost tets (model length; 0: no ghost tets)
//! \throw core::InputError on sizes that do not match
PlanarityFlowResult planarity_flow(const core::TetMesh& mesh, const std::vector<core::Vec3>& start,
                                   const std::vector<int>& vertex_group, int num_groups,
                                   const std::vector<core::Tri>& boundary, const std::vector<int>& labels,
                                   double ghost_height, const PlanarityFlowOptions& options = {});

}  // namespace polycube::mapping
