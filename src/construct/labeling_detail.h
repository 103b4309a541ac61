#pragma once
//! \file labeling_detail.h
//! \brief Internal to construct/: the labeling energy shared by graph cut and repair.

#include "construct/labeling.h"
#include "construct/surface_graph.h"

#include <array>
#include <vector>

namespace polycube::construct::detail {

//! Energy terms precomputed once: data cost per (triangle, label), Potts weight per edge.
struct Energy {
  std::vector<std::array<double, kNumLabels>> data;  //!< #T
  std::vector<double> edge_weight;                   //!< #E cost of a label change across it

  //! Total energy of a labeling.
  [[nodiscard]] double total(const SurfaceGraph& g, const std::vector<int>& labels) const {
    double e = 0.0;
    for (int t = 0; t < g.num_triangles; ++t) e += data[t][labels[t]];
    for (std::size_t k = 0; k < g.edges.size(); ++k)
      if (labels[g.edge_triangles[k][0]] != labels[g.edge_triangles[k][1]]) e += edge_weight[k];
    return e;
  }
};

//! Build the energy of graph_cut_labeling() for these options.
Energy make_energy(const SurfaceGraph& g, const LabelingOptions& options);

}  // namespace polycube::construct::detail
