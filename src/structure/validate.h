#pragma once
//! \file validate.h
//! \brief Validation of a polycube map (ARCHITECTURE §4, §6.2 step 5).
//!
//! A map is valid when
//! 1. no tet is inverted or flat in model space nor in polycube space (exact orientation
//!    predicates: CGAL::orientation with the Exact_predicates_inexact_constructions_kernel);
//! 2. every polycube boundary triangle is axis-aligned: along the dominant axis of its normal its
//!    three vertex coordinates differ by at most the tolerance (ValidateOptions::axis_tolerance
//!    times the diagonal of the polycube's bounding box);
//! 3. the polycube surface (the tet faces of exactly one tet) is a closed 2-manifold: no tet face
//!    is shared by more than two tets, every boundary edge has exactly two boundary triangles,
//!    and the boundary triangles around every boundary vertex form one fan.
//! That the two position arrays share one connectivity is guaranteed by core::PolycubeMap itself;
//! io::read_polycube_map checks it when reading the two files.

#include "core/polycube_map.h"

#include <string>
#include <vector>

namespace polycube::structure {

//! Options of the validation.
struct ValidateOptions {
  //! Axis-alignment tolerance of polycube boundary triangles, relative to the polycube's
  //! bounding-box diagonal (unitless; default 1e-6).
  double axis_tolerance = 1e-6;
  //! Check model-space orientation too (polycube space is always checked).
  bool check_model = true;
  //! How many offending elements each failure message names.
  int max_listed = 5;
};

//! What diagnose_map found. Every count is 0 for a valid map.
struct MapDiagnosis {
  int tets = 0;                  //!< #T
  int vertices = 0;              //!< #V
  int boundary_triangles = 0;    //!< tet faces of exactly one tet
  int inverted_model = 0;        //!< tets with negative orientation in model space
  int flat_model = 0;            //!< tets with zero orientation (coplanar) in model space
  int inverted_polycube = 0;     //!< same in polycube space
  int flat_polycube = 0;         //!< same in polycube space
  int non_axis_aligned = 0;      //!< polycube boundary triangles not axis-aligned
  int overshared_faces = 0;      //!< tet faces shared by three or more tets
  int open_edges = 0;            //!< boundary edges with an odd number of boundary triangles
  int nonmanifold_edges = 0;     //!< boundary edges with four or more boundary triangles
  int nonmanifold_vertices = 0;  //!< boundary vertices whose triangles form several fans
  double axis_tolerance = 0.0;   //!< the absolute axis-alignment tolerance used (polycube units)
  double max_axis_deviation =
      0.0;  //!< largest coordinate span of a boundary triangle along its axis
  //! One message per failed check, naming the failure and the first offending elements.
  std::vector<std::string> failures;

  [[nodiscard]] bool valid() const { return failures.empty(); }
};

//! Run every check and report all failures (does not throw on an invalid map).
//! \throw core::InputError when sizes or indices are inconsistent (core::check_map_indices)
MapDiagnosis diagnose_map(const core::PolycubeMap& map, const ValidateOptions& options = {});

//! Validate a map.
//! \throw core::InputError "invalid polycube map: <failure>; <failure>..." naming each failure
void validate_map(const core::PolycubeMap& map, const ValidateOptions& options = {});

}  // namespace polycube::structure
