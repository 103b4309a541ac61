//! Tests of the chart-boundary turning points (construct/turning_points.h).
#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/tetrahedralize.h"
#include "construct/turning_points.h"
#include "support/shapes.h"
#include "core/errors.h"
#include "support/fixtures.h"
#include "core/polycube_map.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace polycube {
namespace {

using core::Vec3;

struct LabeledBox {
  core::TriMesh surface;
  std::vector<int> labels;
};
LabeledBox labeled_box(int n) {
  LabeledBox b;
  b.surface = test::make_box(1, 1, 1, n);
  for (const auto& t : b.surface.cells) {
    const auto& p = b.surface.points;
    b.labels.push_back(core::dominant_axis_label((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]])));
  }
  return b;
}

TEST(TurningPoints, StraightBoxEdgesHaveNone) {
  const LabeledBox b = labeled_box(4);
  const auto t = construct::boundary_turning(b.surface, b.surface.points, b.labels);
  EXPECT_EQ(t.chains, 12);
  EXPECT_TRUE(t.steps.empty());
  EXPECT_EQ(t.backward_length, 0.0);
}

TEST(TurningPoints, PlantedBackwardStepIsMeasured) {
  // Move one vertex in the middle of a box edge past its neighbour along the edge's axis: the
  // chain now steps back by exactly the overshoot.
  const LabeledBox b = labeled_box(4);
  std::vector<Vec3> p = b.surface.points;
  // The edge x = 1, z = 1 runs along y; its vertices are at y = 0, 0.25, ..., 1.
  int mid = -1;
  for (int v = 0; v < b.surface.num_points(); ++v)
    if (std::abs(p[v].x() - 1) < 1e-12 && std::abs(p[v].z() - 1) < 1e-12 && std::abs(p[v].y() - 0.5) < 1e-12) mid = v;
  ASSERT_GE(mid, 0);
  p[mid].y() = 0.8;  // past the vertex at 0.75: steps 0.25 -> 0.8 -> 0.75 -> 1
  const auto t = construct::boundary_turning(b.surface, p, b.labels);
  EXPECT_EQ(t.chains, 12);
  ASSERT_EQ(t.steps.size(), 1u);
  EXPECT_NEAR(t.steps[0].length, 0.05, 1e-12);
  EXPECT_NEAR(t.backward_length, 0.05, 1e-12);
  EXPECT_EQ(t.steps[0].from, mid);
  const auto& tri = b.surface.cells;
  for (int f : {t.steps[0].left, t.steps[0].right}) {
    const auto& c = tri[f];
    EXPECT_TRUE(std::find(c.begin(), c.end(), mid) != c.end()) << "the step's triangles hold its vertices";
  }
  EXPECT_NE(b.labels[t.steps[0].left], b.labels[t.steps[0].right]);
}

TEST(TurningPoints, StraighteningKeepsTheLabelingValidAndNeverRaisesTheBackwardLength) {
  // A sphere labeled by its normals (repaired): chart boundaries wander.
  const core::TriMesh s = test::make_sphere(1.0, 24, 48);
  std::vector<int> labels;
  for (const auto& t : s.cells)
    labels.push_back(core::dominant_axis_label((s.points[t[1]] - s.points[t[0]]).cross(s.points[t[2]] - s.points[t[0]])));
  const auto rep = construct::repair_labeling(s, labels);
  ASSERT_TRUE(rep.valid());
  // Measure on a wavy copy so that the boundaries have backward steps to remove.
  std::vector<Vec3> p = s.points;
  for (Vec3& q : p) q += 0.1 * Vec3(std::sin(9 * q.y()), std::sin(9 * q.z()), std::sin(9 * q.x()));
  const auto before = construct::boundary_turning(s, p, rep.labels);
  ASSERT_FALSE(before.steps.empty()) << "fixture: no backward step to remove";
  const auto r = construct::straighten_boundaries(s, p, rep.labels, 20);
  EXPECT_TRUE(construct::check_labeling(s, r.labels).valid());
  EXPECT_NEAR(r.backward_before, before.backward_length, 1e-12);
  EXPECT_EQ(r.steps_before, static_cast<int>(before.steps.size()));
  const auto after = construct::boundary_turning(s, p, r.labels);
  EXPECT_NEAR(r.backward_after, after.backward_length, 1e-12);
  EXPECT_EQ(r.steps_after, static_cast<int>(after.steps.size()));
  EXPECT_LE(r.backward_after, r.backward_before);
  EXPECT_GT(r.moves, 0);
  EXPECT_LT(r.backward_after, r.backward_before);
  EXPECT_EQ(r.labels.size(), labels.size());
}

}  // namespace
}  // namespace polycube
