#pragma once
//! \file structure.h
//! \brief The structure of a polycube (ARCHITECTURE §6.3; thesis §1.1, §3.2): charts, polycube
//! edges, corners and faces as rectilinear polygons.
//!
//! Definitions (all in polycube space, on the boundary triangles of the map's tet mesh):
//! - a boundary triangle's **label** is the dominant axis of its normal with its sign
//!   (core::dominant_axis_label: 0..5 = +X, -X, +Y, -Y, +Z, -Z);
//! - a **chart** is a connected set (through shared edges) of boundary triangles with one label;
//!   it lies on the plane `axis = coordinate`;
//! - a **polycube edge** is a maximal chain of boundary edges along which the same two charts
//!   meet, cut at corners; its axis is the one neither chart's normal points along. It is
//!   **convex** when the solid angle there is 90 degrees, **concave** when it is 270;
//! - a **corner** is a boundary vertex where three or more charts meet;
//! - a **face** is a chart seen as a rectilinear polygon: its boundary loops, counter-clockwise
//!   seen from outside the solid, the outer loop first, then the holes.
//! Vertex ids are the map's vertex ids throughout.

#include "core/polycube_map.h"

#include <array>
#include <vector>

namespace polycube::structure {

//! One closed boundary loop of a chart.
struct Loop {
  std::vector<int>
      vertices;              //!< map vertices along the loop (the first is not repeated at the end)
  std::vector<int> corners;  //!< corner ids met along the loop, in order (the polygon's vertices)
  double area = 0.0;         //!< signed area enclosed, seen from outside: > 0 outer loop, < 0 hole
};

//! A planar region of the polycube surface with one label.
struct Chart {
  int label = 0;               //!< 0..5 = +X, -X, +Y, -Y, +Z, -Z
  int axis = 0;                //!< 0, 1, 2 = x, y, z (normal direction)
  int sign = 1;                //!< +1 or -1: the outward normal is sign * e_axis
  double coordinate = 0.0;     //!< mean coordinate of its vertices along axis (the plane)
  double deviation = 0.0;      //!< largest |vertex coordinate - coordinate| (planarity)
  double area = 0.0;           //!< total area of its triangles
  std::vector<int> triangles;  //!< indices into PolycubeStructure::triangles
};

//! A chain of boundary edges where two charts meet, from corner to corner.
struct Edge {
  int axis = -1;  //!< direction 0, 1, 2; -1 when the two charts share an axis (invalid)
  std::array<int, 2> charts{-1, -1};   //!< the two charts (sorted)
  std::array<int, 2> corners{-1, -1};  //!< corner ids at the two ends; -1, -1 for a closed loop
  std::vector<int> vertices;           //!< map vertices from corners[0] to corners[1]
  bool convex = true;                  //!< false: concave (reflex) edge
  double length = 0.0;                 //!< polycube-space length of the chain
};

//! A boundary vertex where three or more charts meet.
struct Corner {
  int vertex = -1;          //!< map vertex id
  core::Vec3 position;      //!< polycube position
  std::vector<int> charts;  //!< the charts meeting there (sorted)
  std::vector<int> edges;   //!< incident polycube edges (sorted)
};

//! A chart as a rectilinear polygon, possibly with holes (faces[i] is chart i).
struct Face {
  int chart = -1;
  std::vector<Loop> loops;  //!< loops[0] is the outer loop, then the holes
  [[nodiscard]] int num_holes() const {
    return loops.empty() ? 0 : static_cast<int>(loops.size()) - 1;
  }
};

//! The whole structure.
struct PolycubeStructure {
  std::vector<core::Tri> triangles;  //!< #F boundary triangles (map vertex ids), outward
  std::vector<int> triangle_tet;     //!< #F owning tet of each triangle
  std::vector<int> triangle_label;   //!< #F label of each triangle
  std::vector<int> triangle_chart;   //!< #F chart of each triangle
  std::vector<Chart> charts;
  std::vector<Edge> edges;
  std::vector<Corner> corners;
  std::vector<Face> faces;         //!< one per chart, same order
  std::vector<int> vertex_corner;  //!< #V corner id of each map vertex, or -1

  [[nodiscard]] int num_convex_edges() const;
  [[nodiscard]] int num_concave_edges() const;
  [[nodiscard]] int num_faces_with_holes() const;
  //! Largest chart deviation from planarity (polycube units).
  [[nodiscard]] double max_chart_deviation() const;
};

//! Extract the structure of a polycube map.
//! \pre the map is valid (validate_map); on an invalid map the result is unspecified but the
//!      call does not crash
//! \throw core::InputError on inconsistent sizes or indices
//! \throw core::GeometryError when a tet face is shared by more than two tets
PolycubeStructure extract_structure(const core::PolycubeMap& map);

}  // namespace polycube::structure
