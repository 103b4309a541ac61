#pragma once
//! \file elements.h
//! \brief Canonical local orderings of every element kind, written once (ARCHITECTURE §4).
//!
//! Everything else in the project uses these tables; nothing re-derives them.
//!
//! Hexahedron (Verdict / VTK / MEDIT / Gmsh order):
//! \verbatim
//!          7-----------6            z
//!         /|          /|            |  y
//!        / |         / |            | /
//!       4-----------5  |            |/
//!       |  |        |  |            o------ x
//!       |  3--------|--2
//!       | /         | /     bottom ring 0-1-2-3 is counter-clockwise seen from the top,
//!       |/          |/      4-5-6-7 lies above 0-1-2-3.
//!       0-----------1
//! \endverbatim
//! Positively oriented when det(p1-p0, p3-p0, p4-p0) > 0.
//!
//! Tetrahedron: positive when (p1-p0) . ((p2-p0) x (p3-p0)) > 0, i.e. 0,1,2,3 = origin, x, y, z.
//!
//! Triangle 0-1-2 and quad 0-1-2-3 are counter-clockwise seen from the side their normal points to.
//!
//! Faces are listed with outward orientation for a positively oriented cell (counter-clockwise
//! seen from outside).

#include <array>

namespace polycube::core {

// --- tetrahedron ------------------------------------------------------------------------------

//! Tet edges as local vertex pairs.
inline constexpr std::array<std::array<int, 2>, 6> kTetEdges{
    {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}};

//! Tet faces, outward; face i is opposite local vertex i.
inline constexpr std::array<std::array<int, 3>, 4> kTetFaces{{{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}}};

// --- hexahedron -------------------------------------------------------------------------------

//! Hex edges as local vertex pairs: bottom ring, top ring, then the 4 vertical edges.
inline constexpr std::array<std::array<int, 2>, 12> kHexEdges{{{0, 1},
                                                              {1, 2},
                                                              {2, 3},
                                                              {3, 0},
                                                              {4, 5},
                                                              {5, 6},
                                                              {6, 7},
                                                              {7, 4},
                                                              {0, 4},
                                                              {1, 5},
                                                              {2, 6},
                                                              {3, 7}}};

//! Hex faces, outward: bottom (z-), top (z+), front (y-), right (x+), back (y+), left (x-).
inline constexpr std::array<std::array<int, 4>, 6> kHexFaces{{{0, 3, 2, 1},
                                                              {4, 5, 6, 7},
                                                              {0, 1, 5, 4},
                                                              {1, 2, 6, 5},
                                                              {2, 3, 7, 6},
                                                              {3, 0, 4, 7}}};

//! Face opposite each hex face (index into kHexFaces).
inline constexpr std::array<int, 6> kHexOppositeFace{1, 0, 4, 5, 2, 3};

//! For each hex corner, its three neighbours in right-handed order (Verdict): the corner's
//! Jacobian is det(p[n0]-p[i], p[n1]-p[i], p[n2]-p[i]); the tet (i, n0, n1, n2) is the corner
//! tetrahedron, positively oriented exactly when that Jacobian is positive.
inline constexpr std::array<std::array<int, 3>, 8> kHexCornerNeighbors{
    {{1, 3, 4}, {2, 0, 5}, {3, 1, 6}, {0, 2, 7}, {7, 5, 0}, {4, 6, 1}, {5, 7, 2}, {6, 4, 3}}};

// --- surface elements -------------------------------------------------------------------------

inline constexpr std::array<std::array<int, 2>, 3> kTriEdges{{{0, 1}, {1, 2}, {2, 0}}};
inline constexpr std::array<std::array<int, 2>, 4> kQuadEdges{{{0, 1}, {1, 2}, {2, 3}, {3, 0}}};

}  // namespace polycube::core
