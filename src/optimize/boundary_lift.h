#pragma once
//! \file boundary_lift.h
//! \brief Orientation barrier for the boundary of a hex mesh being optimized (ARCHITECTURE
//! §6.5, global fold-over): every corner of every boundary quad is lifted to a tet whose apex
//! sits above the corner along the target's outward normal. The tet is positive exactly when
//! the quad corner faces the same side as the target, so the elliptic energy's barrier keeps
//! boundary quads from folding back over their neighbours (a pleat of positive hexes, which
//! the hexes' own corner tets do not see: it forms where the boundary is curved or creased).
//!
//! Apexes are extra points appended after the mesh's points; apex k follows its corner vertex
//! base[k] at the constant offset[k] (height: the vertex's local edge length), so the lifted
//! tet's determinant is height · n · ((p − v) × (q − v)) for the corner's two quad edges.

#include "core/types.h"
#include "optimize/features.h"
#include "solve/untangle.h"

#include <vector>

namespace polycube::optimize {

//! Lifted boundary quad corners.
struct BoundaryLift {
  std::vector<int> base;             //!< #A mesh vertex each apex follows
  std::vector<core::Vec3> offset;    //!< #A its offset from that vertex
  //! Lifted tets (corner, next, previous quad vertex, apex); apex k is vertex num_points + k.
  //! Reference: the right-angled corner of the quad's current edge lengths and the height.
  solve::TetElements elements;
  int skipped = 0;  //!< corners left out because they faced the wrong side (only_positive)
};

//! Lift the corners of the boundary quads of `mesh` along the target normal at each quad's
//! centre (a quad on one side of a sharp edge takes that side's normal).
//! \param edge_length #V local edge length (the lift height)
//! \param weight      weight factor of the lifted tets relative to a hex corner tet
//! \param only_positive leave out corners that face the wrong side now (when the barrier
//!        must not turn an optimization into an untangling)
BoundaryLift lift_boundary(const core::HexMesh& mesh, const TargetSurface& target,
                           const std::vector<double>& edge_length, double weight, bool only_positive);

//! The reduction of the mesh's points extended by the apexes: apex k's coordinates are those
//! of base[k] plus offset[k] (fixed when base[k] is fixed).
solve::LinearReduction with_apexes(const solve::LinearReduction& reduction, const BoundaryLift& lift);

//! Concatenate two element sets.
void append(solve::TetElements& to, const solve::TetElements& from);

}  // namespace polycube::optimize
