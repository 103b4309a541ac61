// Tests of the max-flow / min-cut adapter (solve/max_flow.h): textbook networks with known cuts,
// unary terms (positive and negative), a brute-force check of the minimum energy, and errors.
#include "solve/max_flow.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace polycube::solve {
namespace {

TEST(MaxFlow, SmallNetworkHasTheKnownMinimumCut) {
  // s->0 (3), s->1 (2), 0->1 (1), 0->t (2), 1->t (3): max flow 5, everything saturated at t side.
  FlowNetwork net(2);
  net.source_capacity = {3.0, 2.0};
  net.sink_capacity = {2.0, 3.0};
  net.add_edge(0, 1, 1.0, 0.0);
  const auto r = max_flow(net);
  EXPECT_NEAR(r.flow, 5.0, 1e-12);
  // A chain with a bottleneck in the middle: s->0 (10), 0->1 (1), 1->t (10): cut 0 | 1.
  FlowNetwork chain(2);
  chain.source_capacity = {10.0, 0.0};
  chain.sink_capacity = {0.0, 10.0};
  chain.add_edge(0, 1, 1.0, 1.0);
  const auto c = max_flow(chain);
  EXPECT_NEAR(c.flow, 1.0, 1e-12);
  EXPECT_EQ(c.on_sink[0], 0);
  EXPECT_EQ(c.on_sink[1], 1);
}

TEST(MaxFlow, RejectsNegativeCapacity) {
  FlowNetwork net(2);
  net.add_edge(0, 1, -1.0, 0.0);
  EXPECT_THROW(max_flow(net), core::InternalError);
}

//! The network of Cormen et al., Introduction to Algorithms (3rd ed.), Figure 26.1, with inner
//! nodes v1..v4 = 0..3: s->v1 16, s->v2 13, v1->v3 12, v2->v1 4, v2->v4 14, v3->v2 9,
//! v3->t 20, v4->v3 7, v4->t 4.
FlowNetwork clrs() {
  FlowNetwork net(4);
  net.source_capacity = {16.0, 13.0, 0.0, 0.0};
  net.sink_capacity = {0.0, 0.0, 20.0, 4.0};
  net.add_edge(0, 2, 12.0, 0.0);
  net.add_edge(1, 0, 4.0, 0.0);
  net.add_edge(1, 3, 14.0, 0.0);
  net.add_edge(2, 1, 9.0, 0.0);
  net.add_edge(3, 2, 7.0, 0.0);
  return net;
}

TEST(MaxFlow, TextbookNetworkHasItsUniqueMinimumCut) {
  // Cut {s, v1, v2, v4} | {v3, t}: v1->v3 12 + v4->v3 7 + v4->t 4 = 23. The other source sides
  // cost more: {s} 29, {s,v1} 25, {s,v1,v2} 26, {s,v1,v2,v3,v4} 24, ...
  const auto r = max_flow(clrs());
  EXPECT_NEAR(r.flow, 23.0, 1e-12);
  EXPECT_EQ(r.on_sink, (std::vector<char>{0, 0, 1, 0}));
}

TEST(MaxFlow, PositiveUnaryCostMovesTheCut) {
  // v4 pays 10 more on the source side: v4->t becomes 14. Source sides: {s,v1,v2,v4} 12+7+14 = 33,
  // {s,v1,v2} 12+14 = 26, {s,v1} 13+12 = 25, {s} 29, {s,v1,v2,v3,v4} 20+14 = 34: cut 25, only v1
  // stays with the source.
  FlowNetwork net = clrs();
  net.add_unary(3, 10.0, 0.0);
  EXPECT_EQ(net.sink_capacity[3], 14.0);
  EXPECT_EQ(net.source_capacity[3], 0.0);
  const auto r = max_flow(net);
  EXPECT_NEAR(r.flow, 25.0, 1e-12);
  EXPECT_EQ(r.on_sink, (std::vector<char>{0, 1, 1, 1}));
  // Costs shifted by the same amount on both sides change nothing.
  FlowNetwork shifted = clrs();
  shifted.add_unary(3, 13.5, 3.5);
  const auto s = max_flow(shifted);
  EXPECT_NEAR(s.flow, 25.0, 1e-12);
  EXPECT_EQ(s.on_sink, r.on_sink);
}

TEST(MaxFlow, NegativeUnaryCostIsShiftedByAConstant) {
  // v3 gains 5 on the source side (cost -5) and pays 3 on the sink side. Energies (cut + unary):
  // v3 on the sink side at best 23 + 3 = 26; all inner nodes with the source 20 + 4 - 5 = 19,
  // {s,v1,v2,v3} 20 + 14 - 5 = 29. The least energy is 19, all with the source. The network
  // gets the costs minus min(-5, 3): s->v3 8, so the flow is 19 - (-5) = 24.
  FlowNetwork net = clrs();
  net.add_unary(2, -5.0, 3.0);
  EXPECT_EQ(net.source_capacity[2], 8.0);
  EXPECT_EQ(net.sink_capacity[2], 20.0);
  const auto r = max_flow(net);
  EXPECT_NEAR(r.flow, 24.0, 1e-12);
  EXPECT_EQ(r.on_sink, (std::vector<char>{0, 0, 0, 0}));
}

//! Energy of a side assignment: unary costs plus the capacities of the cut edges.
struct Energy {
  FlowNetwork net;
  std::vector<std::array<double, 2>> unary;  // per node: cost on the source side, on the sink side

  double operator()(const std::vector<char>& on_sink) const {
    double e = 0;
    for (int v = 0; v < net.num_nodes; ++v) e += unary[v][on_sink[v] ? 1 : 0];
    for (const auto& ed : net.edges) {
      if (!on_sink[ed.a] && on_sink[ed.b]) e += ed.capacity_ab;
      if (on_sink[ed.a] && !on_sink[ed.b]) e += ed.capacity_ba;
    }
    return e;
  }
};

TEST(MaxFlow, RandomEnergiesReachTheBruteForceMinimum) {
  // flow = min energy - sum_v min(unary costs of v) (max_flow.h: the cut changes by a constant),
  // and the returned sides reach the minimum.
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> cost(-6, 6), cap(0, 5);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 8;
    Energy e{FlowNetwork(n), {}};
    double shift = 0;
    for (int v = 0; v < n; ++v) {
      const double cs = cost(rng), ct = cost(rng);
      e.net.add_unary(v, cs, ct);
      e.unary.push_back({cs, ct});
      shift += std::min(cs, ct);
    }
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        if (cap(rng) > 2) e.net.add_edge(a, b, cap(rng), cap(rng));
    double best = std::numeric_limits<double>::infinity();
    std::vector<char> sides(n);
    for (int mask = 0; mask < (1 << n); ++mask) {
      for (int v = 0; v < n; ++v) sides[v] = (mask >> v) & 1;
      best = std::min(best, e(sides));
    }
    const auto r = max_flow(e.net);
    EXPECT_NEAR(r.flow, best - shift, 1e-9) << "trial " << trial;
    EXPECT_NEAR(e(r.on_sink), best, 1e-9) << "trial " << trial;
  }
}

TEST(MaxFlow, RejectsOutOfRangeNodesAndBadCapacities) {
  FlowNetwork net(3);
  EXPECT_THROW(net.add_unary(3, 1.0, 0.0), core::InternalError);
  EXPECT_THROW(net.add_unary(-1, 1.0, 0.0), core::InternalError);
  for (const auto& [a, b] : std::vector<std::pair<int, int>>{{0, 3}, {3, 0}, {-1, 1}, {1, 1}}) {
    FlowNetwork bad(3);
    bad.add_edge(a, b, 1.0, 1.0);
    EXPECT_THROW(max_flow(bad), core::InternalError) << a << " " << b;
  }
  FlowNetwork nan(2);
  nan.add_edge(0, 1, 1.0, std::nan(""));
  EXPECT_THROW(max_flow(nan), core::InternalError);
  FlowNetwork inf(2);
  inf.sink_capacity[1] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(max_flow(inf), core::InternalError);
  FlowNetwork negative(2);
  negative.source_capacity[0] = -1.0;
  EXPECT_THROW(max_flow(negative), core::InternalError);
  FlowNetwork sizes(2);
  sizes.sink_capacity.pop_back();
  EXPECT_THROW(max_flow(sizes), core::InternalError);
  // The same networks with valid entries go through.
  FlowNetwork good(3);
  good.add_edge(0, 2, 1.0, 1.0);
  EXPECT_NO_THROW(max_flow(good));
}

}  // namespace
}  // namespace polycube::solve
