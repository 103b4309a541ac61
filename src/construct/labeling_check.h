#pragma once
//! \file labeling_check.h
//! \brief Validity of a polycube labeling (ARCHITECTURE §6.2 step 3): the charts, their
//! boundaries and corners, and the list of defects.
//!
//! A chart is a maximal edge-connected set of triangles with one label. A labeling is valid when
//! 1. every chart has at least 4 neighbouring charts;
//! 2. no two charts with opposite labels (+X/−X, +Y/−Y, +Z/−Z) share a boundary edge;
//! 3. every corner joins exactly three charts of three distinct axes. A vertex's valence is the
//!    number of its incident chart-boundary edges; a corner is a vertex of valence >= 3, and a
//!    valid corner has valence 3, three distinct charts around it, and their three axes distinct.

#include "core/types.h"

#include <string>
#include <vector>

namespace polycube::construct {

//! Charts, their adjacency, corners and boundaries of a labeling.
struct ChartLayout {
  std::vector<int> triangle_chart;               //!< #T chart of each triangle
  std::vector<int> chart_label;                  //!< #charts label of each chart
  std::vector<int> chart_triangles;              //!< #charts number of triangles
  std::vector<double> chart_area;                //!< #charts area
  std::vector<std::vector<int>> chart_neighbors; //!< #charts sorted neighbouring charts
  std::vector<int> corners;                      //!< sorted vertices of valence >= 3
  //! Number of chart boundaries: maximal chains of chart-boundary edges between corners
  //! (a closed chain without corner counts once). Equals the polycube's edges when valid.
  int num_boundaries = 0;
  [[nodiscard]] int num_charts() const { return static_cast<int>(chart_label.size()); }
};

enum class DefectKind {
  TooFewNeighbors,    //!< rule 1
  OppositeNeighbors,  //!< rule 2
  InvalidCorner,      //!< rule 3
};

//! Name of a defect kind ("too-few-neighbors", "opposite-neighbors", "invalid-corner").
const char* defect_kind_name(DefectKind kind);

//! One violated rule.
struct Defect {
  DefectKind kind = DefectKind::TooFewNeighbors;
  std::vector<int> charts;  //!< the chart(s) concerned (sorted)
  int vertex = -1;          //!< the corner's vertex for InvalidCorner, else -1
  std::string reason;       //!< one sentence naming the charts/vertex and what is wrong
};

//! Result of check_labeling().
struct LabelingCheck {
  ChartLayout layout;
  std::vector<Defect> defects;  //!< ordered by kind, then charts / vertex
  [[nodiscard]] bool valid() const { return defects.empty(); }
};

//! Compute the charts and check the three validity rules.
//! \param surface  closed, edge-manifold triangle surface (#V, #T)
//! \param labels   #T labels in {0..5}
//! \throw core::InputError when labels has the wrong size or a label is out of range, or the
//!        surface is not a closed edge-manifold surface
LabelingCheck check_labeling(const core::TriMesh& surface, const std::vector<int>& labels);

}  // namespace polycube::construct
