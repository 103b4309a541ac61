#pragma once
//! \file corner_alignment.h
//! \brief Corner alignment (thesis §3.4) and finalization of the structure (thesis §3.5).
//!
//! The polycube is scaled by s (lattice units per polycube unit) and every class of corners
//! (corner_system.h) gets an integer coordinate X per axis. One iteration, for λ = 1, 1/2,
//! 1/4, ...: pair corners (corner_pairing.h) at their current positions, then for each axis
//! solve exactly
//! \f[ \min_{X\in\mathbb{Z}} \sum_{(c,c')\in A_a} |X(c) - X(c')| \;+\;
//!     \lambda \sum_c \tilde g_c(X(c)) \quad\text{s.t. the axis's difference constraints and}
//!     \; X(c)=X(c')\;\forall (c,c')\in A^*_a, \f]
//! where \f$\tilde g_c\f$ is the L1 shape term \f$|X - s\,x_c|\f$ interpolated between the
//! integers around \f$s\,x_c\f$ (equal to it at every integer, so the integer problem is
//! unchanged). E_align is the L1 distance of the candidate pairs: a convex surrogate of "number
//! of unaligned pairs" (an unaligned pair costs at least 1). Pairs that end equal join A*
//! (their classes merge for good); a merge is offered only when feasible (corner_system.h).
//! The axis problems are independent: the anti-collapse separation is imposed on one chosen
//! axis per pair of boxes (ARCHITECTURE §6.3), so this is the exact optimum of the coupled
//! problem under that choice.
//!
//! Exact solver: every term is a convex piecewise-linear function of a variable or of a
//! difference of two, with integer breakpoints, so the LP in hinge form has the constraint
//! matrix [network matrix | I], totally unimodular: its vertex optimum (CLP dual simplex,
//! solve/milp.h) is integral and is the integer optimum. The solution is rounded (it is
//! integral up to the LP tolerance) and every constraint is re-checked exactly.
//!
//! Stopping: when no feasible candidate pair is left (convergence), when the next λ would be
//! below lambda_min, or after max_iterations. An iteration that aligns nothing does not stop
//! the loop: the next, smaller λ may align those pairs. Finalization: one more solve with
//! E_shape only (λ = 1, no pairs) under all alignments.

#include "simplify/corner_pairing.h"
#include "simplify/corner_system.h"
#include "structure/structure.h"

#include <array>
#include <string>
#include <vector>

namespace polycube::simplify {

//! Options of align_corners().
struct AlignOptions {
  //! Lattice units per polycube unit; 0 = automatic: the longest side of the corners' bounding
  //! box becomes auto_resolution units.
  double scale = 0.0;
  double auto_resolution = 32.0;  //!< lattice units along the longest side when scale = 0
  //! Stop before an iteration whose λ is below this (1: one iteration; 0: until convergence).
  double lambda_min = 0.0;
  int max_iterations = 16;        //!< at most this many alignment iterations (λ ≥ 2^(1-max))
  bool exterior_rule = true;      //!< apply pairing rule 3 (drop pairs whose midpoint is outside)
  //! #corners (or empty): corners never paired (they keep their own planes; the
  //! simplification's fallback after a fit that left tets inverted near them).
  std::vector<char> frozen_corners;
  CornerSystemOptions system;     //!< tolerances of the classes
};

//! One alignment iteration.
struct AlignIteration {
  double lambda = 1.0;
  int candidates = 0;             //!< pairs offered (after pruning)
  int aligned = 0;                //!< of which aligned (new in A*)
  int aligned_total = 0;          //!< |A*| after the iteration
  std::array<int, 3> planes{};    //!< distinct coordinates per axis after the iteration
  double shape_energy = 0.0;      //!< Σ_c Σ_axes |X − s x| (lattice units)
  PairingStats pairing;
  double seconds = 0.0;
};

//! A pair of corners aligned along an axis.
struct AlignedPair {
  int a = -1, b = -1, axis = -1;
  int iteration = -1;
};

//! Result of align_corners().
struct AlignResult {
  double scale = 1.0;                       //!< the lattice units per polycube unit used
  std::vector<core::Vec3> corners;          //!< #corners new positions (integers, lattice units)
  std::array<std::vector<int>, 3> class_value;  //!< per axis, #classes: the new integer coordinate
  std::array<int, 3> planes_before{};       //!< distinct class coordinates per axis in the input
  std::array<int, 3> planes_after{};        //!< distinct coordinates per axis in the output
  std::vector<AlignIteration> iterations;
  std::vector<AlignedPair> aligned;         //!< A* in order of alignment
  double shape_energy = 0.0;                //!< final Σ_c Σ_axes |X − s x| (lattice units)
  double max_displacement = 0.0;            //!< final max over corners and axes of |X − s x|
  bool converged = false;                   //!< stopped because no feasible candidate was left
  std::string stop_reason;                  //!< "converged", "lambda_min", "max_iterations"
  std::string solver;                       //!< the exact solver used
  int lp_solves = 0;                        //!< number of LPs solved
  CornerSystem system;                      //!< classes and constraints
  double seconds_system = 0.0;              //!< building classes and constraints
  double seconds_pairing = 0.0;             //!< all pairings
  double seconds_solve = 0.0;               //!< all alignment solves
  double seconds_finalize = 0.0;            //!< the final shape-only solve
};

//! Align the corners of a polycube structure on the integer lattice.
//! \throw core::GeometryError for a structure the method cannot handle (corner_system.h)
//! \throw core::SolverError when an LP fails (should not happen: the systems are feasible)
AlignResult align_corners(const structure::PolycubeStructure& structure, const AlignOptions& options = {});

//! The scale align_corners() uses for options.scale = 0.
double auto_scale(const structure::PolycubeStructure& structure, double resolution);

}  // namespace polycube::simplify
