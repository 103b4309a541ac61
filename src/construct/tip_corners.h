#pragma once
//! \file tip_corners.h
//! \brief The sharp tips of a coarse surface made polycube corners (issue 24).
//!
//! A polycube's sharpest point is a convex corner: three faces, 90° each, an angle sum of 3π/2.
//! A tip sharper than that (a tetrahedron's, 3 × 60° = π) that the labeling leaves inside a
//! chart must open out to a half-plane, and on an edge to a quarter-space; the untangling then
//! leaves the tets next to it flat or inverted. Made a corner, it only has to open to a cube's
//! corner. On a coarse CAD-like surface (after coarse_surface.h's refinement) every vertex of
//! the input is such a feature, so its sectors are steered to three labels, one per axis, with
//! the signs and the order around it that fit its faces best; the graph cut does the rest.

#include "core/types.h"

#include <array>
#include <vector>

namespace polycube::construct {

//! One tip and the corner chosen for it.
struct TipCorner {
  int vertex = -1;
  double angle_sum = 0.0;        //!< radians, < 2π
  std::vector<int> ring;         //!< its triangles, counter-clockwise seen from outside
  std::vector<int> ring_labels;  //!< the label each ring triangle's sector gets
  double radius = 0.0;           //!< the steered triangles lie within this distance
};

//! Vertices whose angle sum is at most that of a cube's corner, with the labels of the corner
//! that fits their ring best: for each of the 8 sign choices, the ring split into three
//! contiguous sectors of distinct axes, in the order a convex corner of those signs has
//! (X, Y, Z counter-clockwise seen from outside when the product of the signs is +, X, Z, Y
//! when it is −), maximizing the sum over the ring of (angle at the tip) × n·axis. Between
//! corners that fit equally (to rounding), the one whose diagonal is closest to where the tip
//! points wins, then the one that gives the ring's faces the labels earlier tips gave their
//! planes. Rings of more than `max_ring` triangles are skipped. Deterministic.
//! \param surface  closed, edge-manifold surface with outward orientation
std::vector<TipCorner> find_tip_corners(const core::TriMesh& surface, int max_ring = 12);

//! The label every triangle is steered to (-1: free): the triangles in the plane of a ring
//! triangle and within the tip's radius (reached across edges inside that plane) take the ring
//! triangle's label. The radius is a third of the distance to the nearest other vertex that is
//! not flat (angle sum ≠ 2π), so the sectors of two tips never meet. Sets each tip's radius.
std::vector<int> tip_corner_labels(const core::TriMesh& surface, std::vector<TipCorner>& tips);

//! Labeling penalties (LabelingOptions::penalty, in units of a mean-area triangle's fidelity
//! term) from steered labels: `weight` for each label but the steered one; empty when no
//! triangle is steered.
std::vector<std::array<double, 6>> steering_penalty(const std::vector<int>& steered,
                                                    double weight = 4.0);

}  // namespace polycube::construct
