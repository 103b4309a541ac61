// Sharp features of a target and the roles of hex vertices.
#include "optimize/features.h"
#include "optimize/vertex_roles.h"
#include "optimize_fixtures.h"

#include <gtest/gtest.h>

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

TEST(VertexRoles, NoTargetFeaturesMeansSurfaceOnly) {
  const core::HexMesh m = test::box_grid(3, 3, 3);
  const optimize::TargetSurface t(test::box_surface(), {});
  const auto r = optimize::classify_vertices(m, t, 40.0, 1.0);
  EXPECT_EQ(r.corners + r.feature, 0);
  EXPECT_EQ(r.surface, 64 - 8);
}

}  // namespace
}  // namespace polycube
