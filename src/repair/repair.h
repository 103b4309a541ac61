#pragma once
//! \file repair.h
//! \brief Repairs of an input surface that never move it.
//!
//! Meshes as exporters write them are often a triangle soup (OBJ, OFF and PLY writers that give
//! each triangle its own three vertices), or carry triangles that repeat a vertex or repeat
//! another triangle. None of these change the shape, only how it is stored; fixing them is
//! what every other tool of the field does on load. So they are applied by default, in this
//! order, and each is counted:
//!   1. vertices at exactly the same coordinates become one (no tolerance: a tolerance would
//!      move the surface, and may join what the model keeps apart);
//!   2. triangles that use a vertex twice (after 1) are dropped: they have no area;
//!   3. a triangle with the same three vertices in the same turning order as an earlier one is
//!      dropped (the first is kept);
//!   4. vertices no triangle uses are dropped.
//! A mesh that needs none of them comes back unchanged, bit for bit (same vertex order).

#include "core/types.h"

#include <string>
#include <vector>

namespace polycube::repair {

//! What repair_surface changed.
struct RepairReport {
  int merged_vertices = 0;       //!< vertices joined to an earlier one at the same coordinates
  int degenerate_triangles = 0;  //!< triangles dropped for using a vertex twice
  int duplicate_triangles = 0;   //!< triangles dropped for repeating an earlier one
  int unused_vertices = 0;       //!< vertices dropped for belonging to no triangle

  [[nodiscard]] bool changed() const {
    return merged_vertices + degenerate_triangles + duplicate_triangles + unused_vertices > 0;
  }
  //! One line per kind of change, e.g. "merged 24 vertices at equal coordinates".
  [[nodiscard]] std::vector<std::string> lines() const;
};

//! Apply the repairs above to `mesh` (its labels, if any, follow its triangles).
RepairReport repair_surface(core::TriMesh& mesh);

}  // namespace polycube::repair
