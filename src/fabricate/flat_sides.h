#pragma once
//! \file flat_sides.h
//! \brief The flat sides of any closed surface (for checking a part made elsewhere): its planar
//! regions large enough to stand on.

#include "core/types.h"
#include "fabricate/parts.h"

#include <vector>

namespace polycube::fabricate {

//! Triangles on one plane (unit normal within 1e-6, offset within 1e-6 of the diagonal; coplanar
//! regions apart from each other count as one side) whose area is at least `min_area_fraction`
//! of the surface's, largest first, with the outward normal; `triangle_side` gets each
//! triangle's side or -1. Sides found this way have no cut (cut = -1).
std::vector<FlatSide> planar_sides(const core::TriMesh& mesh, std::vector<int>& triangle_side,
                                   double min_area_fraction = 0.01);

}  // namespace polycube::fabricate
