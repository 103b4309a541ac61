#include "solve/max_flow.h"

#include "core/errors.h"

// Boost.Graph trips GCC's -Wmaybe-uninitialized / -Warray-bounds after inlining (false positives).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/range/iterator_range.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

#include <cmath>

namespace polycube::solve {

namespace {

using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
using EdgeDesc = boost::graph_traits<Graph>::edge_descriptor;

void check_capacity(double c) {
  PC_REQUIRE(std::isfinite(c) && c >= 0.0, "max_flow: capacity must be finite and >= 0");
}

}  // namespace

void FlowNetwork::add_unary(int node, double cost_source, double cost_sink) {
  PC_REQUIRE(node >= 0 && node < num_nodes, "add_unary: node out of range");
  // cost_source is paid when the node stays with the source: that cuts node -> sink.
  const double m = std::min(cost_source, cost_sink);
  sink_capacity[static_cast<std::size_t>(node)] += cost_source - m;
  source_capacity[static_cast<std::size_t>(node)] += cost_sink - m;
}

void FlowNetwork::add_edge(int a, int b, double capacity_ab, double capacity_ba) {
  edges.push_back({a, b, capacity_ab, capacity_ba});
}

MaxFlowResult max_flow(const FlowNetwork& net) {
  const int n = net.num_nodes;
  PC_REQUIRE(static_cast<int>(net.source_capacity.size()) == n &&
                 static_cast<int>(net.sink_capacity.size()) == n,
             "max_flow: terminal capacity arrays must have num_nodes entries");
  const int s = n;
  const int t = n + 1;

  // Directed arcs (each with its reverse), laid out in a compressed sparse row graph: one
  // allocation instead of one vector per vertex.
  struct Arc {
    int from, to;
    double cap;
    int rev;  // index of the reverse arc in `arcs`
  };
  std::vector<Arc> arcs;
  arcs.reserve(4 * static_cast<std::size_t>(n) + 2 * net.edges.size());
  auto add_pair = [&](int a, int b, double cab, double cba) {
    check_capacity(cab);
    check_capacity(cba);
    const int i = static_cast<int>(arcs.size());
    arcs.push_back({a, b, cab, i + 1});
    arcs.push_back({b, a, cba, i});
  };
  for (int v = 0; v < n; ++v) {
    const double cs = net.source_capacity[static_cast<std::size_t>(v)];
    const double ct = net.sink_capacity[static_cast<std::size_t>(v)];
    if (cs > 0.0) add_pair(s, v, cs, 0.0);
    if (ct > 0.0) add_pair(v, t, ct, 0.0);
    if (!(std::isfinite(cs) && cs >= 0.0 && std::isfinite(ct) && ct >= 0.0))
      PC_REQUIRE(false, "max_flow: terminal capacity must be finite and >= 0");
  }
  for (const auto& e : net.edges) {
    PC_REQUIRE(e.a >= 0 && e.a < n && e.b >= 0 && e.b < n && e.a != e.b,
               "max_flow: edge node out of range");
    check_capacity(e.capacity_ab);
    check_capacity(e.capacity_ba);
    if (e.capacity_ab <= 0.0 && e.capacity_ba <= 0.0) continue;
    add_pair(e.a, e.b, e.capacity_ab, e.capacity_ba);
  }

  // Sort arcs by source (counting sort, stable); position[i] = CSR index of arc i.
  const auto nv = static_cast<std::size_t>(n) + 2;
  std::vector<std::size_t> start(nv + 1, 0);
  for (const auto& a : arcs) ++start[static_cast<std::size_t>(a.from) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::size_t> position(arcs.size());
  std::vector<std::pair<std::size_t, std::size_t>> sorted(arcs.size());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < arcs.size(); ++i) {
      const std::size_t k = fill[static_cast<std::size_t>(arcs[i].from)]++;
      position[i] = k;
      sorted[k] = {static_cast<std::size_t>(arcs[i].from), static_cast<std::size_t>(arcs[i].to)};
    }
  }
  Graph g(boost::edges_are_sorted, sorted.begin(), sorted.end(), nv);
  std::vector<EdgeDesc> desc;
  desc.reserve(arcs.size());
  for (const auto e : boost::make_iterator_range(boost::edges(g))) desc.push_back(e);
  PC_REQUIRE(desc.size() == arcs.size(), "max_flow: graph construction lost arcs");

  std::vector<double> capacity(arcs.size());
  std::vector<double> residual(arcs.size());
  std::vector<EdgeDesc> reverse(arcs.size());
  for (std::size_t i = 0; i < arcs.size(); ++i) {
    capacity[position[i]] = arcs[i].cap;
    reverse[position[i]] = desc[position[static_cast<std::size_t>(arcs[i].rev)]];
  }
  std::vector<EdgeDesc> pred(nv);
  std::vector<boost::default_color_type> color(nv);
  std::vector<long> dist(nv);
  const auto eidx = boost::get(boost::edge_index, g);
  const auto vidx = boost::get(boost::vertex_index, g);

  MaxFlowResult result;
  result.flow = boost::boykov_kolmogorov_max_flow(
      g, boost::make_iterator_property_map(capacity.begin(), eidx),
      boost::make_iterator_property_map(residual.begin(), eidx),
      boost::make_iterator_property_map(reverse.begin(), eidx),
      boost::make_iterator_property_map(pred.begin(), vidx),
      boost::make_iterator_property_map(color.begin(), vidx),
      boost::make_iterator_property_map(dist.begin(), vidx), vidx, static_cast<Vertex>(s),
      static_cast<Vertex>(t));
  // Vertices of the source tree are black after the algorithm; the rest (sink tree and free
  // vertices) form the sink side of a minimum cut.
  result.on_sink.assign(static_cast<std::size_t>(n), 0);
  for (int v = 0; v < n; ++v)
    result.on_sink[static_cast<std::size_t>(v)] =
        color[static_cast<std::size_t>(v)] != boost::black_color ? 1 : 0;
  return result;
}

}  // namespace polycube::solve
