#pragma once
//! \file polycube_estimate.h
//! \brief A fast polycube estimate of a labeled surface (ARCHITECTURE §6.2 step 3): scores a
//! labeling by how well a polycube can realize it, long before the volume deformation.
//!
//! Per axis a, every vertex of a chart of axis a takes its chart's coordinate (charts of one
//! axis that touch share it, as in the deformation), every other vertex is free, and the
//! coordinates solve the least-squares problem
//! \f[ \min \sum_{(u,v)} w_{uv} \big( z_u - z_v - (p_u - p_v)_a \big)^2 + \rho \sum_v (z_v - p_{v,a})^2 , \f]
//! i.e. the surface keeps its edge vectors as well as the planar charts allow (ρ tiny: removes
//! the translation). One sparse Cholesky solve per axis. Triangles whose estimated normal faces
//! away from their label are where the deformation will have to fold the surface: the
//! labeling is unlikely to be realized there.

#include "core/types.h"

#include <vector>

namespace polycube::construct {

//! Result of estimate_polycube().
struct PolycubeEstimate {
  std::vector<core::Vec3> points;  //!< #V estimated polycube positions of the surface vertices
  std::vector<int> flipped;        //!< triangles facing away from (or flat along) their label
  double flipped_area = 0;         //!< their model area as a fraction of the total area
  //! Root mean square of |e_estimate − e_model| / |e_model| over the edges (0: no distortion).
  double edge_distortion = 0;
};

//! Estimate the polycube of a labeled surface.
//! \param surface  closed surface (#V, #T), outward orientation
//! \param labels   #T labels in {0..5}
//! \throw core::InputError on a wrong number of labels or a label out of range
PolycubeEstimate estimate_polycube(const core::TriMesh& surface, const std::vector<int>& labels);

//! Result of unfold_labeling().
struct UnfoldResult {
  std::vector<int> labels;   //!< #T labels, valid whenever the input was
  int moves = 0;             //!< accepted relabellings
  int folded_before = 0;     //!< triangles the estimate folded before
  int folded_after = 0;      //!< ... and after
};

//! Local repair of a valid labeling against the folds of its polycube estimate: for each
//! folded triangle, give it (alone, then with the triangles of its label around its vertices)
//! the label of an edge neighbour; a move is kept when the labeling stays valid (all three
//! rules of labeling_check.h) and the estimate folds less area. Stops when nothing folds, no
//! move helps, or after max_moves moves. `held` (empty, or #T labels, -1: free): no move gives
//! a held triangle another label.
//! 	hrow as estimate_polycube
UnfoldResult unfold_labeling(const core::TriMesh& surface, std::vector<int> labels, int max_moves = 50,
                             const std::vector<int>& held = {});

}  // namespace polycube::construct
