#pragma once
//! \file foldover_check.h
//! \brief Global fold-over check of a hex mesh (ARCHITECTURE §6.5): no inverted element, and a
//! boundary that does not cross itself. Per-element signs alone miss a layer of positive hexes
//! folded back over the mesh; the boundary self-intersection test catches it.

#include "core/types.h"

#include <array>
#include <string>
#include <vector>

namespace polycube::optimize {

//! Options of check_foldover().
struct FoldoverOptions {
  //! Stop counting boundary triangle pairs after this many intersecting ones (the check only
  //! needs one; the count is for reports).
  int max_reported_intersections = 100;
};

//! What check_foldover() found.
struct FoldoverReport {
  int hexes = 0;
  //! Hexes with a corner tet (corner and its three neighbours, core::kHexCornerNeighbors) that is
  //! flat or negatively oriented, by CGAL's exact orientation predicate.
  int inverted_hexes = 0;
  //! Hexes whose Verdict scaled Jacobian (corners and centre) is <= 0 or invalid.
  int nonpositive_scaled_jacobian = 0;
  int boundary_triangles = 0;  //!< boundary quads split in two (0-1-2, 0-2-3)
  //! Pairs of boundary triangles that intersect other than in their shared vertices or edge
  //! (capped at FoldoverOptions::max_reported_intersections).
  int boundary_self_intersections = 0;
  //! Where the boundary crosses itself: midpoint of the two triangles' centroids, one per
  //! intersecting pair counted (in the order of the boundary's triangles).
  std::vector<core::Vec3> crossings;
  [[nodiscard]] bool ok() const {
    return inverted_hexes == 0 && nonpositive_scaled_jacobian == 0 && boundary_self_intersections == 0;
  }
  //! One line: "ok" or what failed.
  [[nodiscard]] std::string reason() const;
};

//! Global fold-over check of a hex mesh.
//! \throw core::InputError on out-of-range indices
//! \throw core::GeometryError when a face is shared by more than two hexes
FoldoverReport check_foldover(const core::HexMesh& mesh, const FoldoverOptions& options = {});

//! Number of intersecting pairs of triangles of a triangle soup, pairs that share vertices
//! being tested only for intersections away from what they share (at most `cap` counted).
//! Triangles with a repeated vertex index count as intersecting nothing.
//! \param where when given, receives the intersecting pairs (triangle indices, sorted)
int count_self_intersections(const core::TriMesh& soup, int cap = 100,
                             std::vector<std::array<int, 2>>* where = nullptr);

}  // namespace polycube::optimize
