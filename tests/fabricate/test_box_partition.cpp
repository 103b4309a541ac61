// The box partition of hand-made polycubes, where the boxes are known by hand: cuts at both
// planes of every concave edge (thesis §6.2), then merging where a union is a box.
#include "core/errors.h"
#include "fabricate/box_partition.h"
#include "fabricate/corners.h"

#include "../support/fixtures.h"

#include <gtest/gtest.h>

#include <set>

namespace polycube {
namespace {

using fabricate::Box;
using fabricate::OccupancyGrid;

//! Unit cells 0..n per axis, inside where `in` says.
template <class In>
OccupancyGrid unit_grid(int nx, int ny, int nz, In in) {
  OccupancyGrid g;
  const int n[3] = {nx, ny, nz};
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i <= n[a]; ++i) g.planes[a].push_back(i);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) g.inside.push_back(in(i, j, k) ? 1 : 0);
  return g;
}

std::set<std::array<int, 6>> box_set(const fabricate::BoxPartition& p) {
  std::set<std::array<int, 6>> s;
  for (const Box& b : p.boxes) s.insert({b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]});
  return s;
}

//! Every inside cell in exactly one box, no outside cell in any.
void expect_exact_cover(const OccupancyGrid& g, const fabricate::BoxPartition& p) {
  std::vector<int> hits(g.inside.size(), 0);
  for (const Box& b : p.boxes)
    for (int k = b.lo[2]; k < b.hi[2]; ++k)
      for (int j = b.lo[1]; j < b.hi[1]; ++j)
        for (int i = b.lo[0]; i < b.hi[0]; ++i) ++hits[g.index(i, j, k)];
  for (std::size_t c = 0; c < hits.size(); ++c)
    EXPECT_EQ(hits[c], g.inside[c] ? 1 : 0) << "cell " << c;
}

TEST(BoxPartition, AnLIsCutByBothPlanesOfItsConcaveEdgeThenMergedIntoTwo) {
  const OccupancyGrid g = unit_grid(2, 2, 1, [](int i, int j, int) { return !(i == 1 && j == 1); });
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  EXPECT_EQ(p.concave_edges, 1);
  EXPECT_EQ(p.cut_regions, 2);
  EXPECT_EQ(box_set(p), (std::set<std::array<int, 6>>{
                            {0, 0, 0, 1, 1, 1}, {1, 0, 0, 2, 1, 1}, {0, 1, 0, 1, 2, 1}}));
  EXPECT_EQ(p.contacts.size(), 2u);
  expect_exact_cover(g, p);
  fabricate::merge_boxes(g, p);
  ASSERT_EQ(p.boxes.size(), 2u);
  EXPECT_EQ(p.contacts.size(), 1u);
  expect_exact_cover(g, p);
}

TEST(BoxPartition, ATIsFourBoxesAndTwoAfterMerging) {
  const OccupancyGrid g = unit_grid(3, 2, 1, [](int i, int j, int) { return j == 0 || i == 1; });
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  EXPECT_EQ(p.concave_edges, 2);
  EXPECT_EQ(p.boxes.size(), 4u);
  expect_exact_cover(g, p);
  fabricate::merge_boxes(g, p);
  // The largest union first, ties to the lowest ids: the bar, then the stem.
  EXPECT_EQ(box_set(p), (std::set<std::array<int, 6>>{{0, 0, 0, 3, 1, 1}, {1, 1, 0, 2, 2, 1}}));
  ASSERT_EQ(p.contacts.size(), 1u);
  const fabricate::Contact& c = p.contacts[0];
  EXPECT_EQ(c.axis, 1);
  EXPECT_EQ(c.plane, 1);
  EXPECT_EQ(c.lo, (std::array<int, 3>{1, 1, 0}));
  EXPECT_EQ(c.hi, (std::array<int, 3>{2, 1, 1}));
}

TEST(BoxPartition, ACubeWithANotchOnOneEdgeIsElevenBoxesAndFourAfterMerging) {
  const OccupancyGrid g =
      unit_grid(3, 3, 3, [](int i, int j, int k) { return !(i == 1 && j == 2 && k == 2); });
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  EXPECT_EQ(p.concave_edges, 5);   // the notch's floor-to-back edge and its four wall edges
  EXPECT_EQ(p.cut_regions, 4);     // planes x = 1, x = 2, y = 2, z = 2, each across the cube
  EXPECT_EQ(p.boxes.size(), 11u);  // 3 x 2 x 2 blocks minus the notch
  expect_exact_cover(g, p);
  fabricate::merge_boxes(g, p);
  EXPECT_EQ(p.boxes.size(), 4u);  // the least: the notch leaves two top corners apart
  expect_exact_cover(g, p);
}

TEST(BoxPartition, MergingStopsWhereTheUnionWouldNotFit) {
  const OccupancyGrid g = unit_grid(4, 1, 1, [](int, int, int) { return true; });
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  ASSERT_EQ(p.boxes.size(), 1u);  // no concave edge: no cut, one box
  const OccupancyGrid t = unit_grid(3, 2, 1, [](int i, int j, int) { return j == 0 || i == 1; });
  fabricate::BoxPartition q = fabricate::partition_boxes(t);
  fabricate::merge_boxes(t, q, [](const Box& b) { return b.hi[0] - b.lo[0] <= 2; });
  EXPECT_EQ(q.boxes.size(), 3u);
  for (const Box& b : q.boxes) EXPECT_LE(b.hi[0] - b.lo[0], 2);
  expect_exact_cover(t, q);
}

TEST(BoxPartition, CellsTouchingAlongAnEdgeOnlyAreRefused) {
  const OccupancyGrid g = unit_grid(2, 2, 1, [](int i, int j, int) { return i == j; });
  try {
    (void)fabricate::partition_boxes(g);
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("touch along an edge only"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(
      (void)fabricate::partition_boxes(unit_grid(1, 1, 1, [](int, int, int) { return false; })),
      core::InputError);
}

TEST(BoxPartition, TheGridOfAPolycubeMapHasItsChartPlanesAndCells) {
  // An L of 3 unit hexes in polycube space (x in [0,2], y in [0,2], z in [0,1]), tetrahedralized.
  core::HexMesh h = test::hex_grid(2, 2, 1);
  h.cells.erase(h.cells.begin() + 3);  // cell (1, 1, 0)
  const core::TetMesh t = test::tetrahedralize(h);
  core::PolycubeMap map{t.cells, t.points, t.points};
  const OccupancyGrid g = fabricate::occupancy_grid(map);
  for (int a = 0; a < 2; ++a) EXPECT_EQ(g.planes[a], (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(g.planes[2], (std::vector<double>{0, 1}));
  EXPECT_EQ(g.inside, (std::vector<std::uint8_t>{1, 1, 1, 0}));
  EXPECT_EQ(fabricate::partition_boxes(g).boxes.size(), 3u);
}

TEST(BoxCorners, CornersFollowTheMapIntoModelSpace) {
  // The L of 3 unit hexes; model space is an affine image of polycube space, so every corner
  // must land exactly on the image of its polycube position.
  core::HexMesh h = test::hex_grid(2, 2, 1);
  h.cells.erase(h.cells.begin() + 3);
  const core::TetMesh t = test::tetrahedralize(h);
  auto affine = [](const core::Vec3& p) {
    return core::Vec3(2 * p.x() + 0.5 * p.y() + 1, 3 * p.y() - 2, 0.5 * p.z() + p.x());
  };
  std::vector<core::Vec3> model;
  for (const auto& p : t.points) model.push_back(affine(p));
  const core::PolycubeMap map{t.cells, model, t.points};
  const OccupancyGrid g = fabricate::occupancy_grid(map);
  fabricate::BoxPartition p = fabricate::partition_boxes(g);
  fabricate::merge_boxes(g, p);
  const fabricate::BoxCorners c = fabricate::map_corners(map, g, p);
  ASSERT_EQ(c.model.size(), 8 * p.boxes.size());
  EXPECT_EQ(c.not_located, 0);
  for (std::size_t b = 0; b < p.boxes.size(); ++b)
    for (int k = 0; k < 8; ++k) {
      const core::Vec3 q = fabricate::box_corner(g, p.boxes[b], k & 1, (k >> 1) & 1, (k >> 2) & 1);
      EXPECT_LT((c.model[8 * b + k] - affine(q)).norm(), 1e-12) << "box " << b << " corner " << k;
    }
}

}  // namespace
}  // namespace polycube
