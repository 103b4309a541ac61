#pragma once
//! \file charts.h
//! \brief Charts of a labeled triangle surface: the components of equally labeled triangles
//! connected through manifold edges (ARCHITECTURE §6.2–6.3).

#include "core/types.h"

#include <vector>

namespace polycube::core {

//! Charts of a labeled surface.
struct TriangleCharts {
  std::vector<int> triangle_chart;  //!< #F chart of each triangle
  int count = 0;                    //!< number of charts
};

//! Charts of triangles `tris` with one label each: two triangles are in one chart when a chain
//! of equally labeled triangles, consecutive ones sharing an edge of exactly two triangles,
//! joins them. Charts are numbered in the order of their first triangle, so the numbering
//! depends only on the triangle order.
//! \param tris    #F triangles (any vertex indices)
//! \param labels  #F labels
TriangleCharts triangle_charts(const std::vector<Tri>& tris, const std::vector<int>& labels);

}  // namespace polycube::core
