// The solid cut into parts along the plan: on an affinely mapped T the cut plane is exact, so
// each part is the affine image of its box; the parts are closed, outward, free of
// self-intersections and their volumes add up to the solid's.
#include "core/topology.h"
#include "fabricate/corners.h"
#include "fabricate/parts.h"

#include "fabricate_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

namespace polycube {
namespace {

TEST(Parts, AnAffineTIsCutIntoItsTwoBoxesExactly) {
  const test::AffineT t = test::affine_t();
  const core::PolycubeMap& map = t.map;
  const Eigen::Matrix3d& A = t.A;
  const fabricate::OccupancyGrid g = fabricate::occupancy_grid(map);
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  fabricate::merge_boxes(g, p);
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  const auto planes = fabricate::fit_cut_planes(map, g, plan);
  core::TetMesh mt;
  mt.points = map.model;
  mt.cells = map.tets;
  const core::TetBoundary b = core::boundary(mt);
  const fabricate::Parts parts =
      fabricate::cut_parts(b.surface, plan, planes, fabricate::box_lookup(map, g, plan.partition),
                           fabricate::map_centres(fabricate::ToModel(map), g, plan.partition));
  ASSERT_EQ(parts.parts.size(), 2u);
  const double det = A.determinant();
  EXPECT_NEAR(parts.solid_volume, 4 * det, 1e-9);
  EXPECT_NEAR(parts.volume_sum, parts.solid_volume, 1e-9);
  for (const fabricate::Part& part : parts.parts) {
    EXPECT_TRUE(part.closed);
    EXPECT_TRUE(part.outward);
    EXPECT_FALSE(part.self_intersecting);
    EXPECT_EQ(part.components, 1);
    const fabricate::Box& box = plan.partition.boxes[part.box];
    EXPECT_NEAR(part.volume, det * static_cast<double>(box.cells()), 1e-9) << "box " << part.box;
  }
  EXPECT_EQ(parts.unassigned_components, 0);
}

}  // namespace
}  // namespace polycube
