#pragma once
//! \file structure_topology.h
//! \brief The topology the structure analyses (singularities, domains) share, computed once
//! from core/topology.h and reused by singularities.h, domains.h and report.h.

#include "core/topology.h"
#include "core/types.h"

#include <array>
#include <cstdint>
#include <vector>

namespace polycube::quality {

//! Edges, faces and their incidences of a hex mesh.
struct HexTopology {
  core::EdgeTopology<core::CellType::Hexa> edges;  //!< unique edges, cell_edges
  core::FaceTopology<core::CellType::Hexa> faces;  //!< unique faces, face_cells, cell_faces
  core::Adjacency edge_cells;                      //!< #E: incident hexes (the edge's valence)
  std::vector<std::array<int, 4>> face_edges;      //!< #F by 4: edge ids of each face
  core::Adjacency edge_faces;                      //!< #E: incident faces (sorted)
  std::vector<std::uint8_t> edge_on_boundary;      //!< #E: 1 when a boundary face contains the edge

  [[nodiscard]] int num_edges() const { return edges.num_edges(); }
  [[nodiscard]] int num_faces() const { return faces.num_faces(); }
  //! Number of hexes around edge e.
  [[nodiscard]] int edge_valence(int e) const { return edge_cells.degree(e); }
};

//! Topology of a hex mesh. O(C log C).
//! \throw core::InputError on out-of-range indices
//! \throw core::GeometryError when a face is shared by more than two hexes
HexTopology hex_topology(const core::HexMesh& mesh);

//! Edges and their incidences of a quad surface.
struct QuadTopology {
  core::EdgeTopology<core::CellType::Quad> edges;  //!< unique edges, cell_edges
  core::Adjacency edge_cells;                      //!< #E: incident quads
  core::Adjacency vertex_edges;                    //!< #V: incident edges (sorted)
  std::vector<int> vertex_quads;                   //!< #V: number of incident quads
  //! #E: 1 when the edge does not have exactly two quads (boundary or non-manifold edge)
  std::vector<std::uint8_t> edge_on_boundary;
  std::vector<std::uint8_t> vertex_on_boundary;  //!< #V: 1 when an incident edge is on the boundary

  [[nodiscard]] int num_edges() const { return edges.num_edges(); }
};

//! Topology of a quad surface. O(C log C). \throw core::InputError on out-of-range indices
QuadTopology quad_topology(const core::QuadMesh& mesh);

}  // namespace polycube::quality
