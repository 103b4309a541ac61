#pragma once
//! \file thin_gaps.h
//! \brief Where a closed surface faces itself across a gap narrower than a given width: a slit
//! (a mouth drawn as two lips almost touching), a narrow cleft, two parts nearly touching. The
//! tets of a construction fill the solid on either side of such a gap, and no chart layout
//! opens it: the alpha wrap (repair.h) closes the gaps narrower than its ball.

#include "core/types.h"

#include <vector>

namespace polycube::repair {

//! What find_thin_gaps() found.
struct ThinGaps {
  int vertices = 0;               //!< surface vertices that face the surface across a gap narrower than the width
  double narrowest = 0.0;         //!< the narrowest such gap (model units; 0 when none)
  std::vector<core::Vec3> sites;  //!< the first few of those vertices (at most kMaxSites), in vertex order
  static constexpr std::size_t kMaxSites = 3;
};

//! The vertices of a closed, outward-oriented surface whose outward normal (area-weighted over
//! its triangles) meets the surface again within `width`, at a triangle facing back against it
//! (normals more than 120° apart: two sheets facing each other, not the two sides of a concave
//! corner, whose normals are about 90° apart).
//! \throw core::InputError when width is not positive
ThinGaps find_thin_gaps(const core::TriMesh& surface, double width);

}  // namespace polycube::repair
