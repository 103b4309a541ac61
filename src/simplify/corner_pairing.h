#pragma once
//! \file corner_pairing.h
//! \brief Corner pairing (thesis §3.3): which corners should try to share a coordinate.
//!
//! Candidates are neighbours in the Voronoi diagram of the corners, i.e. the edges of their
//! Delaunay triangulation (CGAL Delaunay_triangulation_3, exact predicates; degenerate,
//! cospherical configurations are resolved by CGAL's symbolic perturbation, deterministically
//! for a given input order). They are pruned by the thesis's three rules:
//! 1. the two corners are the end points of one polycube edge;
//! 2. the two corners are end points of two edges sharing a corner;
//! 3. "external" neighbours: the midpoint of the two corners' original positions lies outside
//!    the polycube (they are neighbours only through empty space: their planes never meet
//!    inside the solid, so aligning them does not reduce the number of domains).
//! Each remaining pair is assigned to the axis along which it can align (the caller's
//! feasibility test: different classes, no strict constraint path) with the smallest current
//! coordinate difference; then, for each corner and axis, only its closest partner along that
//! axis is kept (a pair survives when it is the closest for either of its corners).

#include "structure/structure.h"

#include <array>
#include <functional>
#include <vector>

namespace polycube::simplify {

//! A pair of corners to align along one axis.
struct CornerPair {
  int a = -1;               //!< corner id (a < b)
  int b = -1;               //!< corner id
  int axis = -1;            //!< 0, 1, 2
  double distance = 0.0;    //!< |difference of their current coordinates along axis|
  friend bool operator==(const CornerPair&, const CornerPair&) = default;
};

//! Edges of the Delaunay triangulation of the points, as sorted pairs (i < j) in increasing
//! order. Duplicate points are represented by their lowest index (the others get no pair).
std::vector<std::array<int, 2>> delaunay_pairs(const std::vector<core::Vec3>& points);

//! Statistics of one pairing.
struct PairingStats {
  int delaunay = 0;        //!< Delaunay edges
  int same_edge = 0;       //!< removed by rule 1
  int adjacent_edges = 0;  //!< removed by rule 2
  int exterior = 0;        //!< removed by rule 3
  int infeasible = 0;      //!< no axis along which they can align
  int not_closest = 0;     //!< dropped: a closer partner along the same axis exists
  int kept = 0;
};

//! Feasibility test: can corners a and b align along axis?
using CanAlign = std::function<bool(int axis, int a, int b)>;
//! Rule 3: is the pair external (true drops it)? May be empty (rule 3 off).
using IsExterior = std::function<bool(int a, int b)>;

//! Compute the candidate pairs of one iteration.
//! \param structure  the polycube structure (edges give rules 1 and 2)
//! \param positions  #corners current corner positions (lattice units)
//! \param can_align  feasibility per axis
//! \param exterior   rule 3 (may be empty)
//! \param stats      optional statistics
//! \return pairs sorted by (axis, a, b)
std::vector<CornerPair> pair_corners(const structure::PolycubeStructure& structure,
                                     const std::vector<core::Vec3>& positions, const CanAlign& can_align,
                                     const IsExterior& exterior, PairingStats* stats = nullptr);

}  // namespace polycube::simplify
