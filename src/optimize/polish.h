#pragma once
//! \file polish.h
//! \brief The last step of the hex optimization: interior vertices of the worst hexes moved,
//! one at a time, to raise the lowest scaled Jacobian around them.
//!
//! The quality rounds (hex_optimize.h) minimize a smooth energy whose weights favour the worst
//! hexes, but the mesh's minimum scaled Jacobian (mSJ) is a max-min figure of single hexes that
//! a smooth energy only approaches: on a mechanical model the worst hexes are often interior,
//! held by a vertex that the whole mesh's balance left a little off (bench/RESULTS.md, stop 63:
//! S3's two worst hexes, 0.471, have no boundary vertex). Here each interior vertex of a hex
//! within `band` of the current minimum gets a pattern search (±x, ±y, ±z, the step halved when
//! no direction helps), and a move is kept only when it raises the minimum of the hexes around
//! the vertex and does not lower their sum. So the mesh's mSJ never falls and its average SJ
//! never falls. Boundary vertices stay, unless a projector is given: each trial position is
//! then put back on the target first (the optimizer checks the distance and the boundary's
//! crossings after, hex_optimize.h). Sweeps repeat while they raise the mesh's minimum.
//! Sequential and in vertex order: the same result on any number of threads.

#include "core/types.h"

#include <functional>
#include <vector>

namespace polycube::optimize {

//! Options of polish_worst_hexes().
struct PolishOptions {
  //! Hexes whose scaled Jacobian is within this of the mesh's minimum are polished.
  double band = 0.1;
  int max_sweeps = 5;  //!< sweeps at most (each stops the next when it does not raise the minimum)
  //! First and last step of the pattern search, as fractions of the vertex's mean hex edge.
  double first_step = 0.05;
  double last_step = 1e-3;
};

//! What polish_worst_hexes() did.
struct PolishResult {
  int sweeps = 0;         //!< sweeps run
  int moved = 0;          //!< vertex moves kept (a vertex moved in two sweeps counts twice)
  double min_before = 0;  //!< minimum scaled Jacobian before
  double min_after = 0;   //!< ... after
  double seconds = 0;
};

//! How a boundary vertex moves: given the vertex and a trial position, put the position back on
//! the target (its surface, or its feature line) and return true, or return false when the
//! vertex may not move (a corner).
using BoundaryProjector = std::function<bool(int vertex, core::Vec3& position)>;

//! Polish `mesh` in place (see the file comment). Vertices flagged in `fixed` (empty or #V
//! flags) never move; boundary vertices move only through `boundary` (empty: they stay), each
//! trial position put back on the target by it. A mesh with an inverted or degenerate hex is
//! left as it is: polishing is for valid meshes.
PolishResult polish_worst_hexes(core::HexMesh& mesh, const std::vector<char>& fixed = {},
                                const PolishOptions& options = {}, const BoundaryProjector& boundary = {});

}  // namespace polycube::optimize
