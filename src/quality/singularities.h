#pragma once
//! \file singularities.h
//! \brief Singular edges and vertices of hex meshes (#Se, #Sv) and singular vertices of quad
//! meshes (#sv), counted as the thesis's tables count them (cinolib's definitions,
//! ARCHITECTURE §6.1; thesis Tables 3.2 and 4.1).
//!
//! Hex mesh (cinolib Hexmesh::edge_is_singular / vert_is_singular):
//! - an edge is on the boundary when a boundary face contains it; a boundary edge is singular
//!   when its number of incident hexes is not 2, an interior edge when it is not 4. So the
//!   convex (1 hex) and concave (3 hexes) edges of a gridded polycube are singular;
//! - a vertex is singular when the number of singular edges incident to it is neither 0 nor 2.
//!   A vertex inside a chain of singular edges (2) is regular; a sharp polycube corner (3 convex
//!   edges) is singular, as in the thesis.
//!
//! Quad mesh (cinolib Quadmesh::vert_is_singular): an interior vertex is singular when it is
//! not incident to exactly 4 quads; a boundary vertex (on an edge that does not have exactly two
//! quads) when it is not incident to exactly 2 quads (cinolib: vertex valence != 3). On the
//! boundary quad mesh of a gridded polycube the singular vertices are the polycube corners
//! (3 quads at a convex corner, 5 or 6 at the others).
//!
//! #Se and #Sv count mesh edges and vertices (not chains).

#include "core/types.h"
#include "quality/structure_topology.h"

#include <cstdint>
#include <map>
#include <vector>

namespace polycube::quality {

//! Singularities of a hex mesh.
struct HexSingularities {
  int singular_vertices = 0;                  //!< #Sv
  int singular_edges = 0;                     //!< #Se (boundary + interior)
  int boundary_singular_edges = 0;            //!< singular edges on the boundary (valence != 2)
  int interior_singular_edges = 0;            //!< singular interior edges (valence != 4)
  std::map<int, int> boundary_valence;        //!< valence -> number of singular boundary edges
  std::map<int, int> interior_valence;        //!< valence -> number of singular interior edges
  std::vector<std::uint8_t> edge_singular;    //!< #E (HexTopology edge order): 1 if singular
  std::vector<std::uint8_t> vertex_singular;  //!< #V: 1 if singular
};

//! Singularities of a hex mesh. \throw as hex_topology
HexSingularities hex_singularities(const core::HexMesh& mesh);
//! Same, reusing a topology computed by hex_topology(mesh).
HexSingularities hex_singularities(const core::HexMesh& mesh, const HexTopology& topology);

//! Singular vertices of a quad mesh.
struct QuadSingularities {
  int singular_vertices = 0;            //!< #sv
  int boundary_singular_vertices = 0;   //!< of which on the boundary
  std::map<int, int> interior_valence;  //!< quads around -> number of singular interior vertices
  std::map<int, int> boundary_valence;  //!< quads around -> number of singular boundary vertices
  std::vector<std::uint8_t> vertex_singular;  //!< #V: 1 if singular (unreferenced points: 0)
};

//! Singular vertices of a quad mesh. \throw core::InputError on out-of-range indices
QuadSingularities quad_singularities(const core::QuadMesh& mesh);
//! Same, reusing a topology computed by quad_topology(mesh).
QuadSingularities quad_singularities(const core::QuadMesh& mesh, const QuadTopology& topology);

}  // namespace polycube::quality
