#pragma once
//! \file surface_graph.h
//! \brief Internal to construct/: the fixed topology and geometry of a closed boundary surface
//! that labeling, checking and repair all walk (built once, reused by every evaluation).

#include "core/topology.h"
#include "core/types.h"

#include <array>
#include <vector>

namespace polycube::construct::detail {

//! Topology of a closed, edge-manifold triangle surface.
struct SurfaceGraph {
  int num_triangles = 0;
  int num_vertices = 0;
  std::vector<std::array<int, 2>> edges;           //!< #E vertex pairs (a < b)
  std::vector<std::array<int, 2>> edge_triangles;  //!< #E the two triangles of each edge
  std::vector<std::array<int, 3>> triangle_edges;  //!< #T edge ids in the order of kTriEdges
  core::Adjacency vertex_triangles;                //!< #V incident triangles
  core::Adjacency vertex_edges;                    //!< #V incident edges
  std::vector<core::Vec3> normals;                 //!< #T unit normals (zero if degenerate)
  std::vector<core::Vec3> centroids;               //!< #T
  std::vector<double> areas;                       //!< #T
  std::vector<double> edge_lengths;                //!< #E
  double total_area = 0.0;
  std::vector<std::array<int, 3>> triangles;       //!< #T vertex triples (copy of the surface)

  //! The three vertices of triangle t.
  [[nodiscard]] const std::array<int, 3>& triangles_vertices(int t) const { return triangles[t]; }

  //! The triangle across edge e from triangle t.
  [[nodiscard]] int other(int e, int t) const {
    return edge_triangles[e][0] == t ? edge_triangles[e][1] : edge_triangles[e][0];
  }
};

//! Build the graph. \throw core::InputError when an edge does not have exactly two triangles.
SurfaceGraph build_surface_graph(const core::TriMesh& surface);

}  // namespace polycube::construct::detail
