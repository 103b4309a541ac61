#pragma once
//! \file face_attraction.h
//! \brief Attraction of the hex boundary's quad centres to the target (ARCHITECTURE §6.5).
//!
//! Vertex attraction alone interpolates the surface: every boundary vertex on it, every quad a
//! chord. Where quads are long for the curvature, or straddle a sharp edge the hex mesh has no
//! edge for, the chord is what the Hausdorff distance sees (curved and creased models). Each
//! boundary quad's centre, the mean of its four corners, is made an extra point of the
//! reduction and attracted to the target too, so the boundary fits the surface in the least
//! squares sense instead of interpolating it.

#include "core/types.h"
#include "solve/untangle.h"

#include <array>
#include <vector>

namespace polycube::optimize {

//! The boundary quads of a hex mesh as mesh vertex ids (outward).
std::vector<std::array<int, 4>> boundary_quads(const core::HexMesh& mesh);

//! The reduction extended by one point per quad, the mean of its four corners: point k is
//! reduction point num_points + k (constant parts averaged too, so fixed corners count).
solve::LinearReduction with_quad_centres(const solve::LinearReduction& reduction,
                                         const std::vector<std::array<int, 4>>& quads);

}  // namespace polycube::optimize
