// The guillotine cut plan: every cut leaves the boxes of a group entirely on one side or the
// other, the tree ends in single boxes (boxes - 1 cuts), and a pinwheel gets a box split.
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"

#include "fabricate_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <algorithm>
#include <set>

namespace polycube {
namespace {

using fabricate::Box;
using fabricate::OccupancyGrid;

OccupancyGrid full_grid(int nx, int ny, int nz) {
  OccupancyGrid g;
  const int n[3] = {nx, ny, nz};
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= n[a]; ++i) g.planes[a].push_back(i);
  g.inside.assign(static_cast<std::size_t>(nx) * ny * nz, 1);
  return g;
}

//! Each cut splits its group (the parent's side, or every box) into its two sides, each box
//! wholly on its side; single boxes at the leaves.
void expect_valid_plan(const fabricate::CutPlan& plan) {
  const auto& boxes = plan.partition.boxes;
  ASSERT_EQ(plan.cuts.size() + 1, boxes.size());
  std::vector<int> leaves_seen(boxes.size(), 0);
  for (std::size_t c = 0; c < plan.cuts.size(); ++c) {
    const fabricate::Cut& cut = plan.cuts[c];
    std::vector<int> group;
    if (cut.parent < 0) {
      for (std::size_t b = 0; b < boxes.size(); ++b) group.push_back(static_cast<int>(b));
    } else {
      ASSERT_LT(cut.parent, static_cast<int>(c));  // parents first
      const auto& p = plan.cuts[cut.parent];
      group = cut.parent_above ? p.above : p.below;
    }
    std::vector<int> sides = cut.below;
    sides.insert(sides.end(), cut.above.begin(), cut.above.end());
    std::sort(sides.begin(), sides.end());
    std::sort(group.begin(), group.end());
    EXPECT_EQ(sides, group) << "cut " << c;
    EXPECT_FALSE(cut.below.empty());
    EXPECT_FALSE(cut.above.empty());
    if (cut.axis >= 0) {
      for (int b : cut.below) EXPECT_LE(boxes[b].hi[cut.axis], cut.plane);
      for (int b : cut.above) EXPECT_GE(boxes[b].lo[cut.axis], cut.plane);
    } else {  // a separation: no contact between the sides
      EXPECT_TRUE(cut.contacts.empty());
      for (const auto& k : plan.partition.contacts) {
        const bool b0 = std::count(cut.below.begin(), cut.below.end(), k.boxes[0]) > 0;
        const bool a1 = std::count(cut.above.begin(), cut.above.end(), k.boxes[1]) > 0;
        const bool a0 = std::count(cut.above.begin(), cut.above.end(), k.boxes[0]) > 0;
        const bool b1 = std::count(cut.below.begin(), cut.below.end(), k.boxes[1]) > 0;
        EXPECT_FALSE((b0 && a1) || (a0 && b1));
      }
    }
    for (const auto& k : cut.contacts) {
      EXPECT_EQ(k.axis, cut.axis);
      EXPECT_EQ(k.plane, cut.plane);
    }
    if (cut.below.size() == 1) ++leaves_seen[cut.below[0]];
    if (cut.above.size() == 1) ++leaves_seen[cut.above[0]];
  }
  for (std::size_t b = 0; b < boxes.size(); ++b) EXPECT_EQ(leaves_seen[b], 1) << "box " << b;
}

fabricate::BoxPartition partition_of(const OccupancyGrid& g, std::vector<Box> boxes) {
  fabricate::BoxPartition p;
  p.boxes = std::move(boxes);
  fabricate::index_boxes(g, p);
  return p;
}

TEST(CutPlan, ATIsCutOnceAlongItsSeam) {
  OccupancyGrid g = full_grid(3, 2, 1);
  g.inside = {1, 1, 1, 0, 1, 0};
  const auto p = partition_of(g, {{{0, 0, 0}, {3, 1, 1}}, {{1, 1, 0}, {2, 2, 1}}});
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  expect_valid_plan(plan);
  ASSERT_EQ(plan.cuts.size(), 1u);
  EXPECT_EQ(plan.cuts[0].axis, 1);
  EXPECT_EQ(plan.cuts[0].plane, 1);
  ASSERT_EQ(plan.cuts[0].contacts.size(), 1u);
  EXPECT_EQ(plan.split_boxes, 0);
}

TEST(CutPlan, TheNotchedCubeIsCutThreeTimes) {
  OccupancyGrid g = full_grid(3, 3, 3);
  g.inside[g.index(1, 2, 2)] = 0;
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  fabricate::merge_boxes(g, p);
  ASSERT_EQ(p.boxes.size(), 4u);
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  expect_valid_plan(plan);
  EXPECT_EQ(plan.split_boxes, 0);
}

TEST(CutPlan, APinwheelGetsOneBoxSplit) {
  // Four 2 x 1 boxes turning around a unit centre in a 3 x 3 square: no plane crosses none.
  const OccupancyGrid g = full_grid(3, 3, 1);
  const auto p = partition_of(g, {{{0, 0, 0}, {2, 1, 1}},
                                  {{2, 0, 0}, {3, 2, 1}},
                                  {{1, 2, 0}, {3, 3, 1}},
                                  {{0, 1, 0}, {1, 3, 1}},
                                  {{1, 1, 0}, {2, 2, 1}}});
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  EXPECT_EQ(plan.split_boxes, 1);
  EXPECT_EQ(plan.partition.boxes.size(), 6u);
  expect_valid_plan(plan);
}

TEST(CutPlan, TheArmsOfAUAreCutApartByAFreePlaneWithoutContacts) {
  OccupancyGrid g = full_grid(3, 2, 1);
  g.inside = {1, 1, 1, 1, 0, 1};
  const auto p =
      partition_of(g, {{{0, 0, 0}, {3, 1, 1}}, {{0, 1, 0}, {1, 2, 1}}, {{2, 1, 0}, {3, 2, 1}}});
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  expect_valid_plan(plan);
  ASSERT_EQ(plan.cuts.size(), 2u);
  EXPECT_EQ(plan.cuts[0].axis, 1);  // the base off the arms
  EXPECT_EQ(plan.cuts[0].contacts.size(), 2u);
  EXPECT_EQ(plan.cuts[1].axis, 0);  // then the arms apart, at the first free plane x = 1
  EXPECT_EQ(plan.cuts[1].plane, 1);
  EXPECT_TRUE(plan.cuts[1].contacts.empty());
  EXPECT_EQ(plan.cuts[1].below, std::vector<int>{1});
  EXPECT_EQ(plan.cuts[1].above, std::vector<int>{2});
}

TEST(CutPlanes, AnAffineMapGivesExactPlanesOrientedFromBelowToAbove) {
  // The T mapped affinely: every cut's mapped points lie exactly on a plane whose normal is
  // A^-T e_axis.
  const test::AffineT t = test::affine_t();
  const core::PolycubeMap& map = t.map;
  const Eigen::Matrix3d& A = t.A;
  const core::Vec3& shift = t.shift;
  const OccupancyGrid g = fabricate::occupancy_grid(map);
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  fabricate::merge_boxes(g, p);
  const fabricate::CutPlan plan = fabricate::plan_cuts(g, p);
  ASSERT_EQ(plan.cuts.size(), 1u);
  const std::vector<fabricate::CutPlane> planes = fabricate::fit_cut_planes(map, g, plan);
  ASSERT_EQ(planes.size(), 1u);
  const fabricate::CutPlane& q = planes[0];
  EXPECT_EQ(q.points, 4);  // the 4 corners of the unit contact
  EXPECT_LT(q.max_deviation, 1e-12);
  const core::Vec3 expected =
      (A.inverse().transpose() * core::Vec3::Unit(plan.cuts[0].axis)).normalized();
  EXPECT_NEAR(q.normal.dot(expected), 1.0, 1e-12);
  // The plane passes through the mapped contact: n . (A x + shift) = offset at polycube y = 1.
  EXPECT_NEAR(q.normal.dot(A * core::Vec3(1, 1, 0) + shift), q.offset, 1e-12);
}

}  // namespace
}  // namespace polycube
