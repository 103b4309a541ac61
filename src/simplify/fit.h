#pragma once
//! \file fit.h
//! \brief Fit the input polycube (tet mesh) to the aligned structure (thesis §3.5) and certify
//! the result (ARCHITECTURE §6.3: the thesis accepted flipped elements here; we do not).
//!
//! Every boundary vertex keeps the chart planes it lies on: corners are fixed in 3
//! coordinates, edge vertices in 2, chart vertices in 1, interior vertices are free. Start:
//! edge vertices are placed along their edge by linear interpolation between its corners,
//! chart vertices by the chart's monotone piecewise-linear maps of its in-plane coordinates
//! (through its corners' old and new coordinates), interior vertices by a harmonic (graph
//! Laplacian) extension of the boundary displacement. Then the free coordinates are
//! untangled and optimized with the foldover-free elliptic energy (solve/untangle.h), the
//! reference shape of every tet being its scaled input polycube shape. The map is certified
//! with exact predicates (structure::diagnose_map): no inverted or flat tet in either space,
//! axis-aligned, closed manifold boundary; the aligned structure is checked to be embedded like
//! the input (find_contacts) and the fitted map's structure to be the input's.

#include "core/polycube_map.h"
#include "simplify/corner_alignment.h"
#include "solve/untangle.h"
#include "structure/structure.h"

#include <string>
#include <vector>

namespace polycube::simplify {

//! Options of fit_polycube().
struct FitOptions {
  solve::UntangleOptions untangling;  //!< the untangling of the free coordinates
  bool untangle = true;       //!< false: only the initial placement (for tests)
  //! When tets stay inverted after the untangling, place the boundary first
  //! (mapping/boundary_first.h) and untangle again from there.
  bool boundary_first = true;
};

//! Result of fit_polycube().
struct FitResult {
  core::PolycubeMap map;            //!< model positions unchanged; polycube in lattice units
  bool certified = false;           //!< passed structure::diagnose_map and has the same structure
  std::vector<std::string> failures;  //!< why not certified
  int inverted_initial = 0;         //!< tets with non-positive volume after the initial placement
  int inverted_final = 0;           //!< ... after untangling (exact orientation)
  int untangle_iterations = 0;
  double seconds_place = 0.0;
  double seconds_untangle = 0.0;
  double seconds_certify = 0.0;
};

//! Fit the map's polycube to the aligned corners.
//! \param map        the input map (validated)
//! \param structure  its structure
//! \param aligned    align_corners(structure) result
//! \throw core::SolverError when a linear solve fails
FitResult fit_polycube(const core::PolycubeMap& map, const structure::PolycubeStructure& structure,
                       const AlignResult& aligned, const FitOptions& options = {});

//! Compare two structures of one tet mesh: same corners (vertices), same edges (corner pairs,
//! axis, convexity), same charts (label, corners). Returns the differences (empty: same).
std::vector<std::string> compare_structures(const structure::PolycubeStructure& a,
                                            const structure::PolycubeStructure& b);

}  // namespace polycube::simplify
