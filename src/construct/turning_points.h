#pragma once
//! \file turning_points.h
//! \brief Turning points of a labeling's chart boundaries, and their removal by local
//! relabelling (ARCHITECTURE §6.2 step 3; the monotone boundaries of PolyCut, Livesu et al. 2013).
//!
//! A chart boundary between charts of labels a and b becomes a polycube edge parallel to the
//! third axis c. Its chain of vertices between two corners must be monotone along c in the
//! polycube; where the chain runs backwards along c on the (model or pre-deformed) surface, the
//! deformation has to reverse it, which folds the chart triangles next to it. Such backward
//! steps sit mostly next to corners, where the untangling then stays stuck (a corner's fan
//! facing away from its label). The backward length of a chain is the sum of its steps that go
//! against the chain's overall direction (from its first corner to its last).

#include "core/types.h"

#include <vector>

namespace polycube::construct {

//! One backward step of a chart-boundary chain.
struct BackwardStep {
  int from = -1, to = -1;    //!< surface vertices of the step (chain order)
  int left = -1, right = -1; //!< the two triangles sharing the step's edge
  double length = 0;         //!< how far the step goes backwards along the chain's axis
};

//! Result of boundary_turning().
struct BoundaryTurning {
  std::vector<BackwardStep> steps;  //!< backward steps, longest first
  double backward_length = 0;       //!< sum of their lengths
  int chains = 0;                   //!< chains between corners examined
};

//! Backward steps of every chart-boundary chain between two corners (closed chains and chains
//! between two charts of one axis are skipped).
//! \param surface  closed, edge-manifold surface (#V, #T)
//! \param points   #V positions to measure on (the model's or a pre-deformation's)
//! \param labels   #T labels in {0..5}
BoundaryTurning boundary_turning(const core::TriMesh& surface, const std::vector<core::Vec3>& points,
                                 const std::vector<int>& labels);

//! Result of straighten_boundaries().
struct StraightenResult {
  std::vector<int> labels;       //!< #T labels, valid whenever the input was
  int moves = 0;                 //!< accepted relabellings
  double backward_before = 0;    //!< backward length before
  double backward_after = 0;     //!< ... and after
  int steps_before = 0;          //!< backward steps before
  int steps_after = 0;           //!< ... and after
};

//! Remove backward steps by local relabelling: for the longest step first, give one of the two
//! triangles along it (alone, then with the triangles of its label around the step's ends) the
//! other chart's label; a move is kept when the labeling stays valid (labeling_check.h) and the
//! total backward length falls. Stops when no step is left, no move helps, or after max_moves.
StraightenResult straighten_boundaries(const core::TriMesh& surface, const std::vector<core::Vec3>& points,
                                       std::vector<int> labels, int max_moves = 50);

}  // namespace polycube::construct
