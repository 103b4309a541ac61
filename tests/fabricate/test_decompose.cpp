// The whole decomposition on the affinely mapped T (its planes are exact): flat sides known by
// hand, the partition measured independently, and a chamber that forces splits until every
// part stands in it.
#include "core/errors.h"
#include "core/topology.h"
#include "fabricate/box_partition.h"
#include "fabricate/decompose.h"
#include "fabricate/partition_check.h"

#include "fabricate_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/LU>

namespace polycube {
namespace {

core::TriMesh model_boundary(const core::PolycubeMap& map) {
  return core::boundary(map.model_mesh()).surface;
}

void expect_partition(const fabricate::Decomposition& d, const core::TriMesh& solid,
                      double volume) {
  for (const fabricate::Part& p : d.parts.parts) {
    EXPECT_FALSE(p.mesh.cells.empty()) << "box " << p.box;
    EXPECT_TRUE(p.closed) << "box " << p.box;
    EXPECT_TRUE(p.outward) << "box " << p.box;
    EXPECT_FALSE(p.self_intersecting) << "box " << p.box;
  }
  EXPECT_NEAR(d.parts.volume_sum, volume, 1e-9 * volume);
  const fabricate::PartitionCheck c = fabricate::check_partition(d.parts, solid);
  EXPECT_GT(c.samples_inside, 1000);
  EXPECT_EQ(c.overlap, 0.0);
  EXPECT_EQ(c.gap, 0.0);
  EXPECT_LT(c.surface_deviation, 1e-9);
}

TEST(Decompose, TheTsTwoPartsEachHaveTheSeamAsTheirFlatSide) {
  const test::AffineT t = test::affine_t();
  const core::TriMesh solid = model_boundary(t.map);
  const fabricate::Decomposition d = fabricate::decompose(t.map, solid);
  EXPECT_EQ(d.boxes, 4);
  ASSERT_EQ(d.parts.parts.size(), 2u);
  EXPECT_EQ(d.rounds, 1);
  expect_partition(d, solid, 4 * t.A.determinant());
  // The cut is the plane y = 1: the bar's whole top face (x in [0, 3], z in [0, 1]) lies on it,
  // the stub's bottom face (x in [1, 2]) too. n: a unit square of it mapped, oriented +y.
  const core::Vec3 n = (t.A * core::Vec3::UnitZ()).cross(t.A * core::Vec3::UnitX());
  for (const fabricate::Part& p : d.parts.parts) {
    ASSERT_EQ(p.sides.size(), 1u);
    const bool stub = p.volume < 2 * t.A.determinant();
    EXPECT_NEAR(p.sides[0].area, (stub ? 1 : 3) * n.norm(), 1e-9);
    // The bar lies below the seam (its outward normal points up, +n), the stub above.
    EXPECT_NEAR(p.sides[0].normal.dot(n.normalized()), stub ? -1.0 : 1.0, 1e-9);
    int on_side = 0;
    for (int s : p.triangle_side) on_side += s == 0 ? 1 : 0;
    EXPECT_GE(on_side, 2);
  }
  for (int b : d.base) EXPECT_EQ(b, 0);
}

//! Every part stands on its base in the chamber.
void expect_fitting(const fabricate::Decomposition& d, const fabricate::Chamber& chamber) {
  EXPECT_EQ(d.unfit_parts, 0);
  for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
    const fabricate::Part& p = d.parts.parts[i];
    ASSERT_GE(d.base[i], 0);
    EXPECT_TRUE(fabricate::fits_standing_on(
        p.mesh.points, p.sides[static_cast<std::size_t>(d.base[i])].normal, chamber));
  }
}

TEST(Decompose, MergingStopsWhereTheMergedPartWouldNotFitTheChamber) {
  const test::AffineT t = test::affine_t();
  const core::TriMesh solid = model_boundary(t.map);
  fabricate::DecomposeOptions o;
  o.chamber = {4, 4, 4};  // a unit cell's image (2.5 x 3.3 x 1.5) fits; the bar, 6.7 long, not
  const fabricate::Decomposition d = fabricate::decompose(t.map, solid, o);
  EXPECT_EQ(d.parts.parts.size(), 4u);  // the thesis's partition: no union fits
  EXPECT_EQ(d.rounds, 1);
  expect_partition(d, solid, 4 * t.A.determinant());
  expect_fitting(d, o.chamber);
}

TEST(Decompose, AChamberTooSmallForABoxSplitsItUntilEveryPartStandsInIt) {
  const test::AffineT t = test::affine_t();
  const core::TriMesh solid = model_boundary(t.map);
  fabricate::DecomposeOptions o;
  o.chamber = {2.6, 2.6, 2.6};  // not even a unit cell's image fits
  const fabricate::Decomposition d = fabricate::decompose(t.map, solid, o);
  EXPECT_GT(d.parts.parts.size(), 4u);
  EXPECT_GT(d.chamber_planes, 0);
  expect_partition(d, solid, 4 * t.A.determinant());
  expect_fitting(d, o.chamber);
}

TEST(Decompose, AChamberSmallerThanAnyPieceIsRefusedBeforeCutting) {
  const test::AffineT t = test::affine_t();
  fabricate::DecomposeOptions o;
  o.chamber = {0.1, 0.1, 0.1};
  EXPECT_THROW(fabricate::decompose(t.map, model_boundary(t.map), o), core::GeometryError);
}

TEST(Decompose, InsertingAPlaneSplitsTheCellsItCrosses) {
  const test::AffineT t = test::affine_t();
  fabricate::OccupancyGrid g = fabricate::occupancy_grid(t.map);
  const fabricate::OccupancyGrid before = g;
  EXPECT_EQ(fabricate::insert_plane(g, 0, 1.0), 1);  // already a plane: unchanged
  EXPECT_EQ(g.inside, before.inside);
  EXPECT_EQ(fabricate::insert_plane(g, 0, 1.5), 2);
  ASSERT_EQ(g.cells(0), 4);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) {
      const int from = i < 2 ? i : i - 1;  // cells 1 and 2 are the halves of the old cell 1
      EXPECT_EQ(g.in({i, j, 0}), before.in({from, j, 0})) << i << " " << j;
    }
  EXPECT_EQ(fabricate::insert_plane(g, 2, -1.0), 0);  // beyond the grid: a layer outside
  ASSERT_EQ(g.cells(2), 2);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 4; ++i) EXPECT_FALSE(g.in({i, j, 0}));
}

}  // namespace
}  // namespace polycube
