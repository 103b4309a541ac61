// The boundary orientation barrier: lifted boundary quad corners face the target's outside,
// flipped corners are found, apexes follow their vertex exactly.
#include "core/topology.h"
#include "optimize/boundary_lift.h"
#include "optimize/features.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "optimize_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>

namespace polycube {
namespace {

using core::Vec3;

//! Determinants of the lifted tets at the mesh's current points.
std::vector<double> lifted_dets(const core::HexMesh& m, const optimize::BoundaryLift& lift) {
  std::vector<double> d;
  const int nv = m.num_points();
  for (const auto& t : lift.elements.tets) {
    const Vec3& v = m.points[t[0]];
    const Vec3 apex = m.points[lift.base[t[3] - nv]] + lift.offset[t[3] - nv];
    d.push_back((m.points[t[1]] - v).dot((m.points[t[2]] - v).cross(apex - v)));
  }
  return d;
}

int find_point(const core::HexMesh& m, const Vec3& q) {
  return static_cast<int>(std::find_if(m.points.begin(), m.points.end(),
                                       [&](const Vec3& p) { return (p - q).norm() < 1e-12; }) -
                          m.points.begin());
}

TEST(BoundaryLift, CubeCornersFaceOutward) {
  const core::HexMesh m = test::box_grid(1, 1, 1);
  const optimize::TargetSurface target(test::box_surface(), {});
  const std::vector<double> h(8, 0.5);
  const auto lift = optimize::lift_boundary(m, target, h, 1.0, true);
  ASSERT_EQ(lift.elements.size(), 24);  // 6 quads, 4 corners each
  EXPECT_EQ(lift.skipped, 0);
  for (double d : lifted_dets(m, lift)) EXPECT_NEAR(d, 0.5, 1e-12);  // unit edges, height 0.5
  const Vec3 centre(0.5, 0.5, 0.5);
  for (std::size_t k = 0; k < lift.base.size(); ++k) {
    // the offset is an outward axis direction of length 0.5
    EXPECT_NEAR(lift.offset[k].norm(), 0.5, 1e-12);
    EXPECT_GT(lift.offset[k].dot(m.points[lift.base[k]] - centre), 0.0);
  }
}

TEST(BoundaryLift, InwardTargetIsReoriented) {
  core::TriMesh inward = test::box_surface();
  for (auto& t : inward.cells) std::swap(t[1], t[2]);
  const optimize::TargetSurface target(inward, {});
  const core::HexMesh m = test::box_grid(1, 1, 1);
  const auto lift = optimize::lift_boundary(m, target, std::vector<double>(8, 1.0), 1.0, true);
  EXPECT_EQ(lift.elements.size(), 24);
  EXPECT_EQ(lift.skipped, 0);
}

TEST(BoundaryLift, FoldedTopIsFoundAndSkipped) {
  core::HexMesh m = test::box_grid(4, 4, 2);
  // swap two neighbouring top vertices: the top quads around them face down in places
  std::swap(m.points[find_point(m, {0.25, 0.5, 1})], m.points[find_point(m, {0.5, 0.5, 1})]);
  const optimize::TargetSurface target(test::box_surface(), {});
  const std::vector<double> h(m.points.size(), 0.25);
  const auto all = optimize::lift_boundary(m, target, h, 1.0, false);
  const auto positive = optimize::lift_boundary(m, target, h, 1.0, true);
  const std::vector<double> d = lifted_dets(m, all);
  const auto flipped = std::count_if(d.begin(), d.end(), [](double x) { return !(x > 0); });
  EXPECT_GT(flipped, 0);
  EXPECT_EQ(positive.skipped, flipped);
  EXPECT_EQ(positive.elements.size() + positive.skipped, all.elements.size());
  for (double x : lifted_dets(m, positive)) EXPECT_GT(x, 0.0);
}

TEST(BoundaryLift, ApexesFollowTheirVertex) {
  const core::HexMesh m = test::box_grid(1, 1, 1);
  const optimize::TargetSurface target(test::box_surface(), {});
  const auto lift = optimize::lift_boundary(m, target, std::vector<double>(8, 1.0), 1.0, true);
  // vertex 0 fixed, the others free
  std::vector<int> var(24, -1);
  int n = 0;
  for (int i = 3; i < 24; ++i) var[i] = n++;
  const solve::LinearReduction r = solve::index_reduction(var, n, solve::flatten(m.points));
  const solve::LinearReduction ext = optimize::with_apexes(r, lift);
  ASSERT_EQ(ext.num_points(), 8 + static_cast<int>(lift.base.size()));
  Eigen::VectorXd y(n);
  for (int i = 0; i < n; ++i) y[i] = 0.1 * i - 0.7;
  const std::vector<Vec3> x = solve::unflatten(ext.apply(y));
  for (std::size_t k = 0; k < lift.base.size(); ++k)
    EXPECT_EQ(x[8 + k], x[lift.base[k]] + lift.offset[k]);  // bit for bit
  for (std::size_t k = 0; k < lift.base.size(); ++k) {
    if (lift.base[k] == 0) {
      EXPECT_EQ(x[8 + k], m.points[0] + lift.offset[k]);  // fixed base: fixed apex
    }
  }
}

TEST(BoundaryLift, OptimizedFoldedTopFacesOutEverywhere) {
  core::HexMesh m = test::box_grid(4, 4, 2);
  std::swap(m.points[find_point(m, {0.25, 0.5, 1})], m.points[find_point(m, {0.5, 0.5, 1})]);
  const core::TriMesh box = test::box_surface();
  const auto r = optimize::optimize_hex_mesh(m, box);
  EXPECT_TRUE(r.untangled);
  const optimize::TargetSurface target(box, {});
  const auto lift = optimize::lift_boundary(m, target, std::vector<double>(m.points.size(), 0.25), 1.0, true);
  EXPECT_EQ(lift.skipped, 0);
  EXPECT_TRUE(optimize::check_foldover(m).ok()) << optimize::check_foldover(m).reason();
}

}  // namespace
}  // namespace polycube
