// Tests of construct::label_surface, the labeling stage on its own (what `polycube label` runs).
// Validity is judged by the independent validator in validator.h, not by labeling_check.
#include "construct/label_surface.h"
#include "core/errors.h"

#include "support/shapes.h"
#include "construct/validator.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>

namespace polycube {
namespace {

core::Vec3 unit_normal(const core::TriMesh& s, int t) {
  const auto& c = s.cells[t];
  return (s.points[c[1]] - s.points[c[0]]).cross(s.points[c[2]] - s.points[c[0]]).normalized();
}

//! The invariants of every result: the labels belong to the boundary surface, the boundary
//! triangles in volume indices are that surface's, and the reported check is the labels'.
void expect_consistent(const construct::LabelSurfaceResult& r) {
  const core::TriMesh& s = r.boundary.surface;
  ASSERT_EQ(r.labels.size(), s.cells.size());
  ASSERT_EQ(r.initial_labels.size(), s.cells.size());
  ASSERT_EQ(r.boundary_triangles.size(), s.cells.size());
  for (std::size_t t = 0; t < s.cells.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(r.mesh.points[r.boundary_triangles[t][k]], s.points[s.cells[t][k]]);
  const construct::LabelingCheck again = construct::check_labeling(s, r.labels);
  EXPECT_EQ(again.layout.triangle_chart, r.check.layout.triangle_chart);
  EXPECT_EQ(again.defects.size(), r.check.defects.size());
  EXPECT_DOUBLE_EQ(r.fidelity, construct::labeling_fidelity(s, r.labels));
  EXPECT_DOUBLE_EQ(r.fidelity_before_repair, construct::labeling_fidelity(s, r.initial_labels));
}

TEST(LabelSurface, BoxGetsOneChartPerFaceFacingItsAxis) {
  const construct::LabelSurfaceResult r = construct::label_surface(test::make_box(1.0, 2.0, 1.5, 3));
  expect_consistent(r);
  EXPECT_GT(r.tetgen_tets, 0);
  EXPECT_GT(r.mesh.num_cells(), 0);
  const core::TriMesh& s = r.boundary.surface;
  ASSERT_TRUE(r.valid());
  EXPECT_EQ(r.check.layout.num_charts(), 6);
  EXPECT_EQ(r.check.layout.corners.size(), 8u);
  EXPECT_EQ(r.check.layout.num_boundaries, 12);
  std::vector<int> chart_labels = r.check.layout.chart_label;
  std::sort(chart_labels.begin(), chart_labels.end());
  EXPECT_EQ(chart_labels, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  for (int t = 0; t < s.num_cells(); ++t)
    EXPECT_NEAR(unit_normal(s, t).dot(construct::label_direction(r.labels[t])), 1.0, 1e-12) << "triangle " << t;
  EXPECT_NEAR(r.fidelity, 0.0, 1e-12);
  EXPECT_EQ(r.initial_defects, 0);
  EXPECT_EQ(r.repair_moves, 0);
  EXPECT_TRUE(r.estimate.flipped.empty());
  EXPECT_TRUE(r.predeform.points.empty());
  const auto v = test::validate_labeling(s, r.labels);
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(v.charts, 6);
  EXPECT_EQ(v.corners, 8);
}

TEST(LabelSurface, SphereGetsAValidLabelingWhoseTrianglesFaceTheirAxis) {
  construct::LabelSurfaceOptions o;
  o.labeling.compactness = 3.0;  // strong: the cube's layout, one chart per label
  const construct::LabelSurfaceResult r = construct::label_surface(test::make_sphere(1.0, 16, 32), o);
  expect_consistent(r);
  const core::TriMesh& s = r.boundary.surface;
  ASSERT_TRUE(r.valid());
  EXPECT_TRUE(test::validate_labeling(s, r.labels).valid());
  EXPECT_EQ(r.check.layout.num_charts(), 6);
  EXPECT_EQ(r.check.layout.corners.size(), 8u);
  for (int t = 0; t < s.num_cells(); ++t)
    EXPECT_GT(unit_normal(s, t).dot(construct::label_direction(r.labels[t])), 0.0) << "triangle " << t;
}

TEST(LabelSurface, TetMeshInputGivesTheSameLabeling) {
  // The tetrahedralized box is already refined: taking it as input changes nothing.
  const construct::LabelSurfaceResult a = construct::label_surface(test::make_box(2.0, 1.0, 1.0, 2));
  const construct::LabelSurfaceResult b = construct::label_surface(a.mesh);
  expect_consistent(b);
  EXPECT_EQ(b.tetgen_tets, 0);
  EXPECT_EQ(b.refine.split_edges + b.refine.split_tets, 0);
  EXPECT_EQ(b.mesh.cells, a.mesh.cells);
  EXPECT_EQ(b.labels, a.labels);
  EXPECT_TRUE(b.valid());
}

TEST(LabelSurface, PredeformationKeepsPositionsAndLabelingIsValid) {
  construct::LabelSurfaceOptions o;
  o.predeform.iterations = 5;
  const construct::LabelSurfaceResult r = construct::label_surface(test::make_sphere(1.0, 12, 24), o);
  expect_consistent(r);
  EXPECT_EQ(r.predeform.points.size(), r.mesh.points.size());
  EXPECT_GT(r.predeform.iterations, 0);
  EXPECT_LT(r.predeform.misalignment_after, r.predeform.misalignment_before);
  EXPECT_TRUE(r.valid());
  EXPECT_TRUE(test::validate_labeling(r.boundary.surface, r.labels).valid());
}

TEST(LabelSurface, Deterministic) {
  const core::TriMesh s = test::make_torus(2.0, 0.7, 32, 16);
  const construct::LabelSurfaceResult a = construct::label_surface(s);
  const construct::LabelSurfaceResult b = construct::label_surface(s);
  EXPECT_EQ(a.mesh.points, b.mesh.points);
  EXPECT_EQ(a.mesh.cells, b.mesh.cells);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.initial_labels, b.initial_labels);
}

TEST(LabelSurface, OpenSurfaceIsBadInput) {
  core::TriMesh m = test::make_box(1.0, 1.0, 1.0, 2);
  m.cells.pop_back();
  EXPECT_THROW(construct::label_surface(m), core::InputError);
}

}  // namespace
}  // namespace polycube
