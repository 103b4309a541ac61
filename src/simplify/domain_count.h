#pragma once
//! \file domain_count.h
//! \brief Base-complex domain counts of a polycube structure (#D for the hex mesh, #dom for the
//! surface quad layout; thesis Tables 3.1–3.2), from the coarsest grid that carries them.
//!
//! Gridding a polycube whose corners are on the integer lattice gives a hex mesh whose base
//! complex only depends on the planes of the structure: refining each cell of the rectilinear
//! grid of the polycube's distinct plane coordinates into lattice cells adds no singular edge
//! and no block. So we mesh that grid (one hex per grid cell inside the polycube) and count
//! with quality::hex_domains / quality::quad_domains. With the input's own coordinates this is
//! the "naive snapping at a scale where no two distinct corner coordinates merge"; with the
//! aligned integer coordinates it is the gridding of the simplified map at scale 1.

#include "core/types.h"
#include "simplify/corner_system.h"

#include <array>
#include <vector>

namespace polycube::simplify {

//! The counts.
struct DomainCount {
  int hexes = 0;         //!< cells of the plane grid inside the polycube
  int hex_domains = 0;   //!< #D
  int quads = 0;         //!< boundary quads of that grid
  int quad_domains = 0;  //!< #dom
};

//! Hex mesh of the polycube on the grid of its distinct class coordinates (hexes in the
//! canonical order, positively oriented).
//! \param values  per axis, #classes: the coordinate of each class (the input's, or aligned ones)
core::HexMesh plane_grid(const CornerSystem& system, const structure::PolycubeStructure& structure,
                         const std::array<std::vector<double>, 3>& values);

//! #D and #dom of the polycube with the given class coordinates.
DomainCount count_domains(const CornerSystem& system, const structure::PolycubeStructure& structure,
                          const std::array<std::vector<double>, 3>& values);

}  // namespace polycube::simplify
