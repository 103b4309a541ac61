// The polish of the worst hexes (src/optimize/polish.h): interior vertices moved to raise the
// minimum scaled Jacobian around them, never lowering the mesh's minimum or average, the
// boundary left where it is.
#include "core/topology.h"
#include "optimize/polish.h"
#include "quality/scaled_jacobian.h"

#include "support/fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

namespace polycube {
namespace {

//! The vertex of `m` nearest to `p`.
int nearest_vertex(const core::HexMesh& m, const core::Vec3& p) {
  int best = -1;
  double d = std::numeric_limits<double>::infinity();
  for (int v = 0; v < static_cast<int>(m.points.size()); ++v)
    if ((m.points[v] - p).norm() < d) {
      d = (m.points[v] - p).norm();
      best = v;
    }
  return best;
}

//! A 4 x 4 x 4 grid of the unit cube with two interior vertices pushed off their places (by a
//! third and a fifth of the cell side): the hexes around them are the worst.
core::HexMesh distorted_grid() {
  core::HexMesh m = test::box_grid(4, 4, 4);
  m.points[nearest_vertex(m, {0.5, 0.5, 0.5})] += core::Vec3(0.08, 0.05, -0.06);
  m.points[nearest_vertex(m, {0.25, 0.75, 0.5})] += core::Vec3(-0.05, 0.0, 0.03);
  return m;
}

TEST(Polish, TheWorstHexesAroundInteriorVerticesRiseAndTheBoundaryStays) {
  core::HexMesh m = distorted_grid();
  const quality::ScaledJacobianSummary before = quality::scaled_jacobian(m);
  ASSERT_TRUE(before.all_positive());
  ASSERT_LT(before.min, 0.8);
  const core::HexMesh start = m;
  const optimize::PolishResult r = optimize::polish_worst_hexes(m);
  const quality::ScaledJacobianSummary after = quality::scaled_jacobian(m);
  EXPECT_DOUBLE_EQ(r.min_before, before.min);
  EXPECT_DOUBLE_EQ(r.min_after, after.min);
  // A grid's interior vertex has its ideal place (SJ 1 around it) within the search's reach.
  EXPECT_GT(after.min, 0.97);
  EXPECT_GE(after.average, before.average);
  EXPECT_GE(r.moved, 2);
  EXPECT_GE(r.sweeps, 1);
  for (int v : core::boundary(m).vertex_map) EXPECT_EQ(m.points[v], start.points[v]) << v;
  EXPECT_EQ(m.cells, start.cells);

  // The same moves, bit for bit, on a second copy.
  core::HexMesh again = start;
  optimize::polish_worst_hexes(again);
  EXPECT_EQ(again.points, m.points);
}

// A boundary vertex moves only through the projector, which puts each trial back on the target:
// on the bottom face z = 0 a vertex pushed along the face returns towards its place, and stays
// on the face; a projector that refuses the vertex (a corner) leaves it where it is.
TEST(Polish, BoundaryVerticesMoveOnlyAlongTheTargetThroughTheProjector) {
  core::HexMesh start = test::box_grid(4, 4, 4);
  const int v = nearest_vertex(start, {0.5, 0.5, 0.0});
  start.points[v] += core::Vec3(0.09, -0.07, 0.0);
  const double before = quality::scaled_jacobian(start).min;
  ASSERT_LT(before, 0.8);

  core::HexMesh m = start;
  const optimize::BoundaryProjector onto_bottom = [&](int, core::Vec3& p) {
    p.z() = 0.0;  // every boundary vertex the worst hexes have here lies on z = 0
    return true;
  };
  const optimize::PolishResult r = optimize::polish_worst_hexes(m, {}, {}, onto_bottom);
  EXPECT_GT(r.min_after, 0.97);
  EXPECT_DOUBLE_EQ(m.points[v].z(), 0.0);
  EXPECT_NE(m.points[v], start.points[v]);

  core::HexMesh held = start;
  const optimize::BoundaryProjector refuse = [](int, core::Vec3&) { return false; };
  const optimize::PolishResult none = optimize::polish_worst_hexes(held, {}, {}, refuse);
  EXPECT_EQ(held.points[v], start.points[v]);
  // Only the interior vertex above it can give way: better than before, far from the 0.97 above.
  EXPECT_GE(none.min_after, before);
  EXPECT_LT(none.min_after, 0.9);
}

TEST(Polish, FixedVerticesAndInvalidMeshesAreLeftAsTheyAre) {
  const core::HexMesh start = distorted_grid();
  core::HexMesh m = start;
  std::vector<char> fixed(m.points.size(), 1);
  const optimize::PolishResult held = optimize::polish_worst_hexes(m, fixed);
  EXPECT_EQ(held.moved, 0);
  EXPECT_EQ(m.points, start.points);

  // An inverted hex: polishing is for valid meshes.
  core::HexMesh bad = test::box_grid(3, 3, 3);
  bad.points[nearest_vertex(bad, {1.0 / 3, 1.0 / 3, 1.0 / 3})] += core::Vec3(0.5, 0.5, 0.5);
  ASSERT_GT(quality::scaled_jacobian(bad).inverted, 0);
  const core::HexMesh bad_start = bad;
  const optimize::PolishResult none = optimize::polish_worst_hexes(bad);
  EXPECT_EQ(none.sweeps, 0);
  EXPECT_EQ(bad.points, bad_start.points);
}

}  // namespace
}  // namespace polycube
