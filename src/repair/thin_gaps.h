#pragma once
//! \file thin_gaps.h
//! \brief Where a closed surface faces itself across a gap narrower than a given width: a slit
//! (a mouth drawn as two lips almost touching), a narrow cleft, two parts nearly touching. The
//! tets of a construction fill the solid on either side of such a gap, and no chart layout
//! opens it: the alpha wrap (repair.h) closes the gaps narrower than its ball.

#include "core/types.h"
#include "repair/repair.h"

#include <string>
#include <vector>

namespace polycube::repair {

//! What find_thin_gaps() found.
struct ThinGaps {
  double width = 0.0;             //!< the width asked for (model units)
  int vertices = 0;               //!< surface vertices that face the surface across a gap narrower than the width
  double narrowest = 0.0;         //!< the narrowest such gap (model units; 0 when none)
  std::vector<core::Vec3> sites;  //!< the first few of those vertices (RepairReport::kMaxSites), in vertex order
  //! "153 vertices face the surface across gaps narrower than 0.02 (the narrowest 0.003) (first
  //! at ...)", or "" when there is none.
  [[nodiscard]] std::string line() const;
};

//! The vertices of a closed, outward-oriented surface whose outward normal (area-weighted over
//! its triangles) meets the surface again within `width`, at a triangle facing back against it
//! (normals more than 120° apart: two sheets facing each other, not the two sides of a concave
//! corner, whose normals are about 90° apart).
//! \throw core::InputError when width is not positive
ThinGaps find_thin_gaps(const core::TriMesh& surface, double width);

//! The gaps the alpha wrap of `wrap` (its ball, wrap_alpha times the bounding-box diagonal)
//! closes: those narrower than the ball's diameter. Nothing when the surface or the ball is
//! empty.
ThinGaps gaps_the_wrap_closes(const core::TriMesh& surface, const RepairOptions& wrap);

}  // namespace polycube::repair
