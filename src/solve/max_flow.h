#pragma once
//! \file max_flow.h
//! \brief Minimum s-t cut / maximum flow on a sparse graph (adapter over Boost.Graph's
//! Boykov–Kolmogorov algorithm), so the rest of the project never includes a Boost graph header.

#include <vector>

namespace polycube::solve {

//! An s-t flow network: `num_nodes` inner nodes plus the implicit source and sink.
struct FlowNetwork {
  int num_nodes = 0;
  //! #N capacities of the edges source -> node (cut when the node ends on the sink side).
  std::vector<double> source_capacity;
  //! #N capacities of the edges node -> sink (cut when the node ends on the source side).
  std::vector<double> sink_capacity;

  //! One pair of opposite directed edges between two inner nodes.
  struct Edge {
    int a = 0, b = 0;
    double capacity_ab = 0.0;  //!< a -> b, cut when a is on the source side and b on the sink side
    double capacity_ba = 0.0;  //!< b -> a
  };
  std::vector<Edge> edges;

  //! A network of n nodes with zero terminal capacities.
  explicit FlowNetwork(int n = 0)
      : num_nodes(n), source_capacity(static_cast<std::size_t>(n), 0.0),
        sink_capacity(static_cast<std::size_t>(n), 0.0) {}

  //! Add a unary cost: `cost_source` paid when the node stays on the source side, `cost_sink`
  //! when it goes to the sink side (negative costs are shifted; the cut changes by a constant).
  void add_unary(int node, double cost_source, double cost_sink);
  //! Add a pair of directed edges.
  void add_edge(int a, int b, double capacity_ab, double capacity_ba);
};

//! The minimum cut.
struct MaxFlowResult {
  double flow = 0.0;           //!< value of the maximum flow (= capacity of the minimum cut)
  std::vector<char> on_sink;   //!< #N, 1 when the node is on the sink side of the minimum cut
};

//! Solve with Boykov–Kolmogorov. Capacities must be finite and >= 0.
//! \throw core::InternalError on a negative or non-finite capacity or an out-of-range node.
MaxFlowResult max_flow(const FlowNetwork& network);

}  // namespace polycube::solve
