#pragma once
//! \file corner_system.h
//! \brief The per-axis constraint system of corner alignment (thesis §3.4.1, ARCHITECTURE §6.3).
//!
//! Every structural constraint of the thesis is per axis, so the simplification works on three
//! independent systems. For axis a:
//! - **classes**: corners that must share coordinate a. Corners linked by a polycube edge of
//!   another axis, or lying on one chart of axis a, are in one class (union-find); classes whose
//!   original coordinates agree within the tolerance are merged too (an alignment the input
//!   already has is kept). Class ids are sorted by original coordinate, so every constraint
//!   points from a lower id to a higher one.
//! - **constraints** `X(to) − X(from) ≥ weight` between class coordinates X (integers, lattice
//!   units), weight 1 (strict) or 0 (weak):
//!   1. polycube edges of axis a: length ≥ 1 (thesis eq. 3.3);
//!   2. within each chart, the in-plane order of its corners' coordinates is kept (weak), so
//!      every chart stays the image of its original polygon under a monotone map per axis
//!      (which the fitting uses);
//!   3. **separation** (our exact replacement of the anti-collapse planes, eq. 3.4, and of the
//!      dummy edges, fig. 3.6), for every pair of elements that do not touch in the input:
//!      - two corners/edges (points/segments, i.e. boxes whose bounds are class coordinates):
//!        the axis along which their gap is largest is chosen and their order along it is
//!        kept with a gap ≥ 1;
//!      - a corner/edge E and a chart polygon P it does not touch: either E stays strictly on
//!        its side of P's plane (one constraint along P's axis), or — when E's projection on
//!        P's plane is outside P and its smallest in-plane gap to P's edges is larger than its
//!        distance to the plane, or E crosses the plane — E's projection stays separated from
//!        every edge of P in the plane (one constraint per edge, along its larger gap).
//!   Why this guarantees that no parts collapse or touch: move every class coordinate linearly
//!   from its scaled original value to the solution. Each constraint holds along the whole
//!   path because it holds at both ends. A first contact between two parts of the surface
//!   always involves a corner or an edge touching another element (two polygons start to
//!   overlap at a point of one's boundary), which the constraints exclude: corner/edge pairs
//!   stay separated along their axis; against a chart, E either never reaches the plane, or its
//!   projection never meets the polygon's boundary and therefore stays outside the polygon.
//!   Edges keep length ≥ 1 and their direction. Hence the output surface is embedded and
//!   isotopic to the input: same corners, edges, charts, adjacency and face topology (holes
//!   included). Pairs that touch in the input (sharing a corner) are incident and need no
//!   constraint: their shared corner moves with both.
//!   The constraints are reduced transitively (a constraint implied by a path is dropped).
//! - **alignment** of two corners along a merges their classes: possible exactly when no path
//!   with a strict constraint joins the two classes (the system stays feasible).

#include "structure/structure.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace polycube::simplify {

//! One difference constraint X[to] − X[from] ≥ weight (class ids of one axis).
struct AxisConstraint {
  int from = -1;
  int to = -1;
  int weight = 1;  //!< 1 (strict: gap of one lattice unit at least) or 0 (weak: order kept)
  friend bool operator==(const AxisConstraint&, const AxisConstraint&) = default;
};

//! The classes and constraints of one axis.
struct AxisSystem {
  int axis = 0;
  std::vector<int> corner_class;       //!< #corners: class of each corner along this axis
  std::vector<double> coordinate;      //!< #classes: original coordinate times scale (lattice units)
  std::vector<int> class_size;         //!< #classes: number of corners
  std::vector<int> chart_class;        //!< #charts: class of each chart of this axis, -1 for others
  std::vector<AxisConstraint> constraints;  //!< transitively reduced, sorted (from, to)
  int constraints_before_reduction = 0;     //!< distinct class pairs before the reduction

  [[nodiscard]] int num_classes() const { return static_cast<int>(coordinate.size()); }
};

//! An axis-aligned box of the surface decomposition (bounds are class ids per axis).
struct SurfaceBox {
  enum class Kind : std::uint8_t { Corner, Edge, Rectangle };
  Kind kind = Kind::Corner;
  int id = -1;                     //!< corner, edge or chart id
  std::array<int, 3> lo{}, hi{};   //!< class ids of the lower and upper bound per axis
};

//! Options of build_corner_system().
struct CornerSystemOptions {
  //! Coordinates closer than this (relative to the polycube's bounding-box diagonal) count as
  //! equal: corners linked by the structure must agree within it, classes closer are merged.
  double tolerance = 1e-6;
  //! Linked corners may disagree by up to this (relative to the diagonal) before the structure
  //! is refused as inconsistent.
  double consistency_tolerance = 1e-3;
  //! Impose the separation constraints (rule 3). Only for experiments and tests: without them
  //! parts of the polycube may collapse onto each other (thesis fig. 3.6 b).
  bool separation = true;
};

//! The three axis systems of a polycube structure.
struct CornerSystem {
  double scale = 1.0;                 //!< lattice units per polycube unit
  std::array<AxisSystem, 3> axes;
  //! corners, then edges, then chart rectangles (each chart split into maximal row runs of the
  //! grid of its own corner coordinates; used to classify points, inside_polycube())
  std::vector<SurfaceBox> boxes;
  std::vector<int> x_rectangles;      //!< indices into boxes of the rectangles of x charts
  long long separation_pairs = 0;     //!< element pairs that received separation constraints
};

//! Build the classes and constraints.
//! \param structure  the input structure (every edge must join two corners and have an axis)
//! \param scale      lattice units per polycube unit (> 0)
//! \throw core::GeometryError when an edge has no corners or no axis, a chart has no corner,
//!        or corners that must share a coordinate differ by more than the consistency tolerance
CornerSystem build_corner_system(const structure::PolycubeStructure& structure, double scale,
                                 const CornerSystemOptions& options = {});

//! Independent check of the embedding at the given class coordinates: every pair of elements
//! (corner, edge, chart) that does not touch in the input must be disjoint (exact tests on the
//! boxes and polygons), and every edge must keep a positive length. Returns one message per
//! contact found (at most max_reported), empty when the surface is embedded like the input.
std::vector<std::string> find_contacts(const CornerSystem& system, const structure::PolycubeStructure& structure,
                                       const std::array<std::vector<double>, 3>& values, int max_reported = 10);

//! Point classification against the polycube described by the system's rectangles at the
//! given class coordinates (ray casting along +x over the rectangles of x charts, half-open
//! in y and z: the result is exact for a point infinitesimally displaced by (−δ, δ, δ)).
//! \param values  #classes per axis: the coordinate of each class
bool inside_polycube(const CornerSystem& system, const structure::PolycubeStructure& structure,
                     const std::array<std::vector<double>, 3>& values, const core::Vec3& point);

}  // namespace polycube::simplify
