#pragma once
//! \file corner_fans.h
//! \brief Reopening of flipped chart fans at concave polycube corners (ARCHITECTURE §6.2 step 4).
//!
//! At a concave corner one chart has to open to 270° around the corner. When the deformation
//! cannot find that, it leaves the chart's fan swept the short way (90°) with every triangle
//! facing away from its label, while the tets stay positive or nearly so: the untangling is
//! stuck, since reaching the 270° sweep needs a large move of the whole fan. The repair places
//! the fan's inner spokes on the long sweep directly, in the chart's plane, at their distance
//! from the corner, after which a local untangling around the fan settles the tets below it.

#include "core/types.h"

#include <vector>

namespace polycube::mapping {

//! Result of reopen_flipped_fans().
struct ReopenedFans {
  int fans = 0;               //!< fans placed on their counter-clockwise sweep
  std::vector<int> vertices;  //!< the vertices moved (sorted)
};

//! For every polycube corner (a vertex whose boundary triangles carry three axes) and every
//! chart around it whose fan is one path of triangles with a triangle facing away from its
//! label in P: spread the fan's inner spokes evenly over the counter-clockwise sweep (seen from
//! the label's direction) from its first to its last spoke. The inner spokes must be free in
//! the chart's plane (on that chart only); the corner and the two outer spokes (on polycube
//! edges) stay. Only in-plane coordinates change.
//! \param tris    #B outward boundary triangles (indices into P)
//! \param labels  #B labels in 0..5
//! \param P       positions, updated in place
ReopenedFans reopen_flipped_fans(const std::vector<core::Tri>& tris, const std::vector<int>& labels,
                                 std::vector<core::Vec3>& P);

}  // namespace polycube::mapping
