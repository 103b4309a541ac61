// Global fold-over check: inverted corners and boundary self-intersections.
#include "optimize/foldover_check.h"
#include "optimize_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace polycube {
namespace {

TEST(Foldover, GridPasses) {
  const core::HexMesh m = test::box_grid(3, 3, 3);
  const auto r = optimize::check_foldover(m);
  EXPECT_TRUE(r.ok()) << r.reason();
  EXPECT_EQ(r.hexes, 27);
  EXPECT_EQ(r.boundary_triangles, 6 * 9 * 2);
}

TEST(Foldover, InvertedHexIsCaught) {
  core::HexMesh m = test::box_grid(2, 2, 2);
  m.points[13] = core::Vec3(1.6, 0.5, 0.5);  // the centre vertex pushed through a face: corners invert
  const auto r = optimize::check_foldover(m);
  EXPECT_FALSE(r.ok());
  EXPECT_GT(r.inverted_hexes, 0);
}

TEST(Foldover, BarBentLessThanATurnPasses) {
  const core::HexMesh m = test::bent_bar(0.9);
  const auto r = optimize::check_foldover(m);
  EXPECT_EQ(r.inverted_hexes, 0);
  EXPECT_TRUE(r.ok()) << r.reason();
}

TEST(Foldover, BarFoldedOverItselfIsCaught) {
  const core::HexMesh m = test::bent_bar(1.1);
  const auto r = optimize::check_foldover(m);
  EXPECT_EQ(r.inverted_hexes, 0);  // every hex is positive...
  EXPECT_EQ(r.nonpositive_scaled_jacobian, 0);
  EXPECT_GT(r.boundary_self_intersections, 0);  // ...but the boundary crosses itself
  EXPECT_FALSE(r.ok());
}

TEST(Foldover, PaddedLayerFoldedBackIsCaught) {
  // A 4x4x4 grid with a padding layer on top; the layer is folded back over the mesh: its top
  // vertices are moved below the layer's bottom, flipping the padding hexes (and crossing the
  // boundary).
  core::HexMesh m = test::box_grid(4, 4, 5, 1, 1, 1.25);
  for (auto& p : m.points)
    if (p.z() > 1.2) p.z() = 0.9;  // top of the padding layer folded down below z = 1
  const auto r = optimize::check_foldover(m);
  EXPECT_FALSE(r.ok());
  EXPECT_GT(r.boundary_self_intersections, 0);
}

TEST(Foldover, SharedVertexAndEdgePairsAreNotIntersections) {
  // Two triangles sharing an edge, folded flat onto each other, do intersect; unfolded ones do not.
  core::TriMesh t;
  t.points = {{0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, {0.5, -1, 0}};
  t.cells = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(optimize::count_self_intersections(t), 0);
  t.points[3] = {0.5, 0.5, 0};  // the second triangle folded onto the first
  EXPECT_EQ(optimize::count_self_intersections(t), 1);
  // Sharing one vertex, meeting only there.
  core::TriMesh u;
  u.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0.5}, {0, -1, 0.5}};
  u.cells = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(optimize::count_self_intersections(u), 0);
  u.points[3] = {0.5, 0.2, -0.5};
  u.points[4] = {0.2, 0.5, 0.5};  // its opposite edge pierces the first triangle
  EXPECT_EQ(optimize::count_self_intersections(u), 1);
}

}  // namespace
}  // namespace polycube
