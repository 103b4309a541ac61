#pragma once
//! \file padding_topology.h
//! \brief The incidences padding needs on top of quality::hex_topology (internal to padding/):
//! facets, edges and hexes around each vertex, the two boundary facets of each boundary edge,
//! the cells around an edge in turning order, and the "ghost" cells glued outside boundary
//! facets (sheet.h).

#include "core/types.h"
#include "quality/structure_topology.h"

#include <array>
#include <vector>

namespace polycube::padding::detail {

//! The incidences the insertion and the binary problem need, on top of quality::hex_topology.
struct Topology {
  quality::HexTopology t;
  core::Adjacency vertex_faces;                   //!< #V: facets containing each vertex (sorted)
  core::Adjacency vertex_edges;                   //!< #V: edges containing each vertex (sorted)
  core::Adjacency vertex_hexes;                   //!< #V: hexes containing each vertex (sorted)
  std::vector<std::array<int, 2>> edge_boundary;  //!< #E: the two boundary facets of a boundary edge
  int num_hexes = 0;

  //! Cell key of the ghost glued outside boundary facet f (hexes are keys 0..#H-1).
  [[nodiscard]] int ghost(int f) const { return num_hexes + f; }
};

Topology build_topology(const core::HexMesh& mesh);

//! Cells around edge e in counter-clockwise order about its direction (edges[e][0] -> [1]): in a
//! hex, the facet where that direction appears in the outward vertex order is the one the turn
//! leaves by. At a boundary edge the sequence starts with the ghost of one boundary facet and
//! ends with the other's (the cycle closes through them).
std::vector<int> cells_around(const core::HexMesh& mesh, const Topology& tp, int e);

//! The facets around edge e in the same order: facet k lies between cells_around()[k] and
//! [k+1] (at a boundary edge: the boundary facet, the inner facets, the other boundary facet).
std::vector<int> facets_around(const core::HexMesh& mesh, const Topology& tp, int e);

}  // namespace polycube::padding::detail
