// Sharp features of a target and the roles of hex vertices.
#include "core/topology.h"
#include "optimize/features.h"
#include "optimize/vertex_roles.h"
#include "optimize_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace polycube {
namespace {

TEST(Features, BoxHasTwelveSharpEdgesAndEightCorners) {
  const core::TriMesh box = test::box_surface(2, 1, 1);
  const auto f = optimize::detect_features(box, 40.0);
  EXPECT_EQ(f.edges.size(), 12u);  // the 6 face diagonals are flat
  EXPECT_EQ(f.corners.size(), 8u);
  EXPECT_EQ(f.num_lines, 12);
  for (const auto& e : f.edges) {
    // a box edge joins two box corners differing in exactly one coordinate
    const core::Vec3 d = box.points[e[1]] - box.points[e[0]];
    EXPECT_EQ((d.array() != 0).count(), 1);
  }
}

TEST(Features, ThresholdAboveTheDihedralFindsNothing) {
  const auto f = optimize::detect_features(test::box_surface(), 95.0);
  EXPECT_TRUE(f.edges.empty());
  EXPECT_TRUE(f.corners.empty());
}

TEST(Features, ClosestPointsOnSurfaceAndFeatureLines) {
  const core::TriMesh box = test::box_surface();
  const optimize::TargetSurface t(box, optimize::detect_features(box, 40.0));
  EXPECT_LT((t.closest_point({0.5, 0.5, 1.3}) - core::Vec3(0.5, 0.5, 1.0)).norm(), 1e-12);
  EXPECT_LT((t.closest_feature_point({0.5, 0.1, 0.2}) - core::Vec3(0.5, 0.0, 0.0)).norm(), 1e-12);
  const int k = t.nearest_corner({0.9, 1.1, 0.05});
  ASSERT_GE(k, 0);
  EXPECT_LT((t.corner_position(k) - core::Vec3(1, 1, 0)).norm(), 1e-12);
}

// A slab 0.1 thick: a point 0.3 below it is closest to the bottom face, but a boundary vertex
// there that faces up belongs to the top face, 0.4 away; only within `reach` of the closest
// distance is the facing side taken.
TEST(Features, ClosestPointFacingTakesTheSideFacingTheQuerysWayWithinReach) {
  const core::TriMesh slab = test::box_surface(10, 10, 0.1);
  const optimize::TargetSurface t(slab, optimize::detect_features(slab, 40.0));
  const core::Vec3 p(5, 5, -0.3);
  const auto up = t.closest_point_facing(p, {0, 0, 1}, 0.2);
  EXPECT_LT((up.first - core::Vec3(5, 5, 0.1)).norm(), 1e-12);
  EXPECT_LT((up.second - core::Vec3(0, 0, 1)).norm(), 1e-12);
  const auto down = t.closest_point_facing(p, {0, 0, -1}, 0.2);
  EXPECT_LT((down.first - core::Vec3(5, 5, 0)).norm(), 1e-12);
  EXPECT_LT((down.second - core::Vec3(0, 0, -1)).norm(), 1e-12);
  // The top face is 0.1 farther than the bottom one: beyond a reach of 0.05.
  const auto short_reach = t.closest_point_facing(p, {0, 0, 1}, 0.05);
  EXPECT_LT((short_reach.first - core::Vec3(5, 5, 0)).norm(), 1e-12);
  // No direction: the closest point.
  EXPECT_LT((t.closest_point_facing(p, core::Vec3::Zero(), 1.0).first - core::Vec3(5, 5, 0)).norm(), 1e-12);
}

TEST(VertexRoles, GridOfABox) {
  const int n = 4;
  const core::HexMesh m = test::box_grid(n, n, n);
  const core::TriMesh box = test::box_surface();
  const optimize::TargetSurface t(box, optimize::detect_features(box, 40.0));
  const auto r = optimize::classify_vertices(m, t, 40.0, 1.0);
  EXPECT_EQ(r.corners, 8);
  EXPECT_EQ(r.feature, 12 * (n - 1));
  EXPECT_EQ(r.surface, 6 * (n - 1) * (n - 1));
  for (int v = 0; v < m.num_points(); ++v) {
    const core::Vec3& p = m.points[v];
    const int on_walls = (p.array() == 0 || p.array() == 1).count();
    const optimize::VertexRole expected = on_walls == 0   ? optimize::VertexRole::Interior
                                          : on_walls == 1 ? optimize::VertexRole::Surface
                                          : on_walls == 2 ? optimize::VertexRole::Feature
                                                          : optimize::VertexRole::Corner;
    EXPECT_EQ(r.role[v], expected) << "vertex " << v;
    if (r.role[v] == optimize::VertexRole::Corner) {
      EXPECT_LT((t.corner_position(r.corner[v]) - p).norm(), 1e-12);
    }
  }
}

TEST(VertexRoles, TwoSharpEdgesTakeAJunctionOfThreeLines) {
  // the target: the unit cube (triangulated boundary of a 4^3 grid) whose features get one more
  // line, on the top face from (0.5, 0, 1) inwards, so (0.5, 0, 1) is a T junction of three
  // lines. The hex grid follows two of them there (the cube's top front edge): that vertex
  // takes the corner, as three sharp edges take the cube's corners.
  const int n = 4;
  const core::HexMesh m = test::box_grid(n, n, n);
  const core::TriMesh cube = test::boundary_surface(m);
  auto at = [&](const core::Vec3& x) {
    for (int v = 0; v < cube.num_points(); ++v)
      if ((cube.points[v] - x).norm() < 1e-12) return v;
    return -1;
  };
  optimize::SurfaceFeatures f = optimize::detect_features(cube, 40.0);
  ASSERT_EQ(f.corners.size(), 8u);
  const int t0 = at({0.5, 0, 1}), t1 = at({0.5, 0.25, 1}), t2 = at({0.5, 0.5, 1});
  ASSERT_TRUE(t0 >= 0 && t1 >= 0 && t2 >= 0);
  std::vector<std::pair<std::array<int, 2>, int>> edges;
  for (std::size_t e = 0; e < f.edges.size(); ++e) edges.push_back({f.edges[e], f.edge_line[e]});
  edges.push_back({{std::min(t0, t1), std::max(t0, t1)}, f.num_lines});
  edges.push_back({{std::min(t1, t2), std::max(t1, t2)}, f.num_lines});
  ++f.num_lines;
  std::sort(edges.begin(), edges.end());
  f.edges.clear();
  f.edge_line.clear();
  std::map<int, int> valence;
  for (const auto& [e, line] : edges) {
    f.edges.push_back(e);
    f.edge_line.push_back(line);
    ++valence[e[0]];
    ++valence[e[1]];
  }
  f.corners.clear();
  for (const auto& [v, k] : valence)
    if (k != 2) f.corners.push_back(v);  // the 8 cube corners, the T and the line's end
  ASSERT_EQ(f.corners.size(), 10u);
  const optimize::TargetSurface t(cube, std::move(f));
  const auto r = optimize::classify_vertices(m, t, 40.0, 0.5);
  EXPECT_EQ(r.corners, 9);  // the cube's 8 and the T; the line's inner end has no sharp hex edge
  for (int v = 0; v < m.num_points(); ++v) {
    if ((m.points[v] - core::Vec3(0.5, 0, 1)).norm() > 1e-12) continue;
    EXPECT_EQ(r.role[v], optimize::VertexRole::Corner);
    ASSERT_GE(r.corner[v], 0);
    EXPECT_LT((t.corner_position(r.corner[v]) - m.points[v]).norm(), 1e-12);
  }
}

TEST(VertexRoles, NoTargetFeaturesMeansSurfaceOnly) {
  const core::HexMesh m = test::box_grid(3, 3, 3);
  const optimize::TargetSurface t(test::box_surface(), {});
  const auto r = optimize::classify_vertices(m, t, 40.0, 1.0);
  EXPECT_EQ(r.corners + r.feature, 0);
  EXPECT_EQ(r.surface, 64 - 8);
}

}  // namespace
}  // namespace polycube
