#pragma once
//! \file labeled_mesh.h
//! \brief A tet mesh whose boundary triangles carry polycube labels, with the chart variables
//! that tie every chart to one plane (ARCHITECTURE §6.2 steps 4–5), and the edits that keep the
//! three consistent (edge and triangle splits).
//!
//! Charts are the edge-connected boundary triangles of one label (core/charts.h). The
//! coordinate of a chart along its label's axis is one unknown shared by all its vertices;
//! charts of one axis that touch at a vertex share it too (a chart group). A polycube
//! position whose chart coordinates are copied from their group's value has every chart
//! exactly planar, bit for bit.

#include "core/types.h"

#include <array>
#include <vector>

namespace polycube::mapping {

//! Chart groups of a labeled boundary.
struct ChartVariables {
  std::vector<int> triangle_chart;  //!< #B chart of each boundary triangle
  int num_charts = 0;
  std::vector<int> vertex_group;    //!< 3#V group of coordinate (v, axis), −1 when v is on no chart of that axis
  int num_groups = 0;
};

//! A tet mesh with labeled boundary triangles.
struct LabeledTetMesh {
  core::TetMesh mesh;                //!< positively oriented tets
  std::vector<core::Tri> boundary;   //!< #B outward boundary triangles (volume indices), core::boundary() order
  std::vector<int> labels;           //!< #B labels in 0..5
  std::vector<int> boundary_cell;    //!< #B tet owning each boundary triangle
  ChartVariables charts;             //!< see update_charts()
};

//! Attach labels to the boundary of `mesh`: `tris` (any order and orientation) must be exactly
//! the boundary faces of mesh. The result's boundary is in core::boundary() order; charts are
//! computed.
//! \throw core::InputError when tris is not the set of boundary faces or a label is out of range
LabeledTetMesh label_tet_mesh(core::TetMesh mesh, const std::vector<core::Tri>& tris, const std::vector<int>& labels);

//! Re-derive boundary order and owners after an edit of lm.mesh (labels follow their triangles).
//! Charts are left as they were: call update_charts() when they are needed.
void refresh_boundary(LabeledTetMesh& lm);

//! Recompute the charts and chart groups of lm.
void update_charts(LabeledTetMesh& lm);

//! The chart groups of a labeled boundary of a mesh with nv vertices.
ChartVariables chart_variables(int nv, const std::vector<core::Tri>& tris, const std::vector<int>& labels);

//! Boundary triangles whose three vertices share the chart group of an in-plane axis (the
//! constraints would make them flat).
std::vector<int> forced_flat_triangles(const LabeledTetMesh& lm);

//! Chart-interior boundary edges whose ends share the chart group of an in-plane axis: the
//! constraints put the edge on a polycube edge while the chart lies on both sides of it, which
//! forces a fold.
std::vector<std::array<int, 2>> chord_edges(const LabeledTetMesh& lm);

//! Boundary edges to split so that, at every polycube corner, each chart's fan has at least
//! `min_fan` triangles (none when min_fan <= 1).
std::vector<std::array<int, 2>> thin_fan_edges(const LabeledTetMesh& lm, int min_fan);

//! Split `edges` (sorted pairs) at their midpoints, every tet and boundary triangle around each
//! in two; edges whose tets were already split in this call are left for the next. `other`
//! (optional, #V) gets the midpoints too. Call refresh_boundary() afterwards.
//! \return the number of edges split
int split_edges(LabeledTetMesh& lm, const std::vector<std::array<int, 2>>& edges,
                std::vector<core::Vec3>* other = nullptr);

//! An interior vertex whose neighbours all lie on one chart plane (the same group on one axis),
//! with one face of its link that is not on the boundary (locked_interior_vertices() gives one
//! such pair per face). The chart's plane takes every corner of the vertex's star, so no
//! position of the vertex makes its tets positive: the centroid that the refinement after
//! TetGen puts into a tet with several boundary facets is one when those facets lie in one
//! chart. Splitting the link's interior faces gives it a neighbour that also sees the far side.
struct LockedVertex {
  int vertex = -1;
  std::array<int, 3> face{};
};
std::vector<LockedVertex> locked_interior_vertices(const LabeledTetMesh& lm);

//! Split the interior face `face` at its centroid: each of its two tets becomes three, unless
//! one is marked in `touched` (#T, grows with the new tets). `other` (optional, #V) gets the
//! centroid too.
bool split_interior_face(LabeledTetMesh& lm, std::array<int, 3> face, std::vector<char>& touched,
                         std::vector<core::Vec3>* other = nullptr);

//! Split boundary triangle f and its tet at the triangle's centroid, unless the tet is marked
//! in `touched` (#T, grows with the new tets). Call refresh_boundary() afterwards.
bool split_boundary_triangle(LabeledTetMesh& lm, int f, std::vector<char>& touched,
                             std::vector<core::Vec3>* other = nullptr);

//! The variables of a polycube position under the chart constraints.
struct MapVariables {
  std::vector<int> var;  //!< 3#V variable of coordinate (v, axis): chart group g is variable g, then the free coordinates in order
  int count = 0;         //!< number of variables
};

//! The variables of lm's positions (lm.charts must be up to date).
MapVariables map_variables(const LabeledTetMesh& lm);

//! Boundary triangles of lm facing away from their label in positions P.
int facing_away(const LabeledTetMesh& lm, const std::vector<core::Vec3>& P);

//! Failures of polycube positions P: tets with det <= 0 plus triangles facing away.
int failures(const LabeledTetMesh& lm, const std::vector<core::Vec3>& P);

}  // namespace polycube::mapping
