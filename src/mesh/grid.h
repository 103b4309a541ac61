#pragma once
//! \file grid.h
//! \brief Gridding a polycube map into hex and quad meshes (ARCHITECTURE §6.4; thesis §2.1).
//!
//! The polycube is scaled by s and fitted to the integer lattice: a lattice cell (unit cube) is
//! a hex when it lies inside the scaled polycube; each lattice point of those cells is located
//! in a polycube tet and mapped to model space with its barycentric coordinates. The quad mesh
//! is the boundary of the hex lattice.
//!
//! Corners must be at integer positions after scaling. The polycube's boundary lies on
//! per-axis coordinate *levels* (the chart planes); every level is rounded to the nearest
//! integer (halves away from zero) — the naive snapping of the state of the art (thesis §3.2):
//! - when rounding keeps the levels of every axis distinct, the snapping map is the per-axis
//!   piecewise-linear map sending each level to its integer; it maps the polycube onto the
//!   snapped polycube bijectively and the lattice points are located through its inverse (exact,
//!   no defect possible);
//! - when two levels of one axis round to the same integer, the polycube is deformed instead
//!   (each chart moved to its rounded plane, the displacement extended harmonically to the
//!   interior) and the topological defects this causes are detected and reported (thesis
//!   fig. 3.2): corners merged into one lattice point, a corner pushed onto a facet it does not
//!   belong to, a polycube edge or a chart collapsed, tets of the deformed polycube flattened
//!   or inverted. The mesh is still built; it is the caller's decision to refuse it.

#include "core/polycube_map.h"
#include "core/types.h"

#include <array>
#include <string>
#include <vector>

namespace polycube::mesh {

//! How many lattice cells each interval between consecutive chart planes gets.
enum class GridSizing {
  //! Proportional to its polycube length (one scale for the whole polycube; thesis §2.1): hexes
  //! are cubes in polycube space and inherit the map's distortion in model space.
  Uniform,
  //! Proportional to its length in model space: the interval's polycube length times the map's
  //! stretch along that axis over the slab between the two planes (95th percentile over the
  //! slab's tets, weighted by volume), at least one cell. Where the map compresses the model
  //! the slab gets more cells, where it expands it fewer, so hexes are closer to one size in
  //! model space. Every chart plane still lands on an integer: no snapping, no defect.
  Map
};

//! Options of the gridding. Exactly one way of choosing the resolution applies: scale when
//! > 0, else target_hexes when > 0, else target_quads when > 0, else scale 1.
struct GridOptions {
  //! Uniform, or cells per interval following the map (GridSizing::Map; then scale is the
  //! number of cells per unit of model length and the hex/quad targets choose it).
  GridSizing sizing = GridSizing::Uniform;
  double scale = 0.0;    //!< lattice cells per polycube unit (> 0), or 0 to choose it
  //! Choose the scale whose hex count is closest to this. A polycube whose chart planes are all
  //! at integers (a simplified one) is then never scaled below 1: at any scale >= 1 its planes
  //! stay distinct and its alignments exact.
  int target_hexes = 0;
  int target_quads = 0;  //!< choose the scale whose boundary quad count is closest to this
  //! Locate every lattice point (hex and quad meshes); false: only the boundary lattice points
  //! (quad meshes only; hex_model is then left empty, hex_polycube is still filled).
  bool volume = true;
  //! Lattice points outside the polycube by at most this, relative to the polycube's
  //! bounding-box diagonal, are located in the nearest tet (clamped). Also the tolerance under
  //! which two chart coordinates are one level.
  double tolerance = 1e-6;
  //! Largest lattice (bounding box of the scaled polycube, in lattice points) accepted.
  long long max_lattice_points = 400'000'000;
  //! Polycube-space points the lattice is finer around: on each axis, the interval between
  //! consecutive chart planes that holds a point's coordinate (both, on a plane) gets
  //! refine_factor times the cells the resolution above gives it, so the hexes there are that
  //! much shorter along the axis. The other intervals keep their cells: a feature thinner than
  //! the hexes gets more of them without multiplying the hexes everywhere.
  std::vector<core::Vec3> refine_near;
  int refine_factor = 2;  //!< >= 1
};

//! Kinds of snapping defects (thesis fig. 3.2).
enum class DefectKind {
  CornersMerged,   //!< distinct corners rounded to one lattice point
  CornerOnFacet,   //!< a corner rounded onto a chart (facet or its border) it does not belong to
  EdgeCollapsed,   //!< a polycube edge rounded to zero length
  ChartCollapsed,  //!< a chart rounded to zero area
  TetsDegenerated  //!< the snapped polycube has flat or inverted tets
};

//! Name of a defect kind ("corners merged", ...).
const char* defect_name(DefectKind k);

//! One snapping defect.
struct SnapDefect {
  DefectKind kind = DefectKind::CornersMerged;
  std::vector<int> corners;                 //!< corner ids involved (structure::PolycubeStructure)
  std::vector<core::Vec3> positions;        //!< their scaled polycube positions before snapping
  core::Vec3 lattice = core::Vec3::Zero();  //!< where they end up (lattice units)
  int edge = -1;                            //!< EdgeCollapsed: the polycube edge
  int chart = -1;                           //!< ChartCollapsed, CornerOnFacet: the chart
  int count = 0;                            //!< TetsDegenerated: number of tets; else 0
  std::string description;                  //!< one line naming the defect
};

//! What snapping did.
struct SnapReport {
  bool needed = false;            //!< some level was not an integer after scaling
  std::array<int, 3> levels{};    //!< distinct coordinate levels per axis
  int collapsed_levels = 0;       //!< levels rounded onto the integer of their predecessor
  int corners_moved = 0;          //!< corners not already at an integer position
  double max_displacement = 0.0;  //!< largest level move, lattice units
  bool deformed = false;          //!< the polycube was deformed (levels collapsed)
  std::vector<SnapDefect> defects;

  [[nodiscard]] bool ok() const { return defects.empty(); }
  //! "no defect" or "2 corners merged: ...; 1 edge collapsed: ..." (at most max_items each kind).
  [[nodiscard]] std::string summary(int max_items = 3) const;
};

//! The gridded meshes.
struct GridResult {
  core::HexMesh hex_model;           //!< #H hexes, model positions of the lattice points
  core::HexMesh hex_polycube;        //!< same connectivity, lattice positions (integer coordinates)
  core::QuadMesh quad_model;         //!< boundary of the hex lattice, model positions
  core::QuadMesh quad_polycube;      //!< same connectivity, lattice positions
  double scale = 0.0;                //!< the scale used (GridSizing::Map: cells per model length)
  std::array<int, 3> lattice_min{};  //!< integer bounding box of the snapped polycube
  std::array<int, 3> lattice_max{};
  SnapReport snapping;
  int points_located = 0;  //!< lattice points located within the tolerance
  int points_failed =
      0;  //!< lattice points found outside every tet (mapped to the nearest, clamped)
  double max_failed_distance =
      0.0;  //!< how far outside the worst failed point was (polycube units)
  int inverted_model_hexes =
      -1;  //!< hexes with a non-positive corner Jacobian in model space (-1: not computed)
  double seconds_locate = 0.0;  //!< wall time of locating and mapping the lattice points
  double seconds_total = 0.0;   //!< wall time of the whole gridding
};

//! The polycube-space images of model-space points (for GridOptions::refine_near): each point
//! is located in the map's model tets (the nearest tet, clamped, when it lies outside, as a
//! point of the input surface may by a rounding) and mapped with its barycentric coordinates.
std::vector<core::Vec3> polycube_points(const core::PolycubeMap& map, const std::vector<core::Vec3>& model_points);

//! Grid a polycube map.
//! \pre the map is valid (structure::validate_map)
//! \throw core::InputError when the resolution options are invalid (negative scale, ...), when
//!        the lattice would exceed max_lattice_points, or on inconsistent map sizes
//! \throw core::GeometryError when the polycube holds no lattice cell at the chosen scale
GridResult grid_polycube(const core::PolycubeMap& map, const GridOptions& options = {});

}  // namespace polycube::mesh
