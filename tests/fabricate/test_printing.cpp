// Support needed to print a part: a cube needs none on any side; a T standing on its stem needs
// support under the two arms of its bar (2 of its 18 unit squares), upside down none, on the end
// of its bar under the stem's side (1 of 18); the best base is the side needing least among
// those that fit the chamber; a solid in one piece takes its best axis. Features without area
// need support too: a keel rising less steeply than the printer's angle, a tip pointing down.
#include "core/topology.h"
#include "fabricate/printing.h"

#include "../support/fixtures.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <map>

namespace polycube {
namespace {

using core::Vec3;

//! The boundary of unit cells of a grid, keeping the cells `keep` says.
template <class Keep>
core::TriMesh cells_surface(int nx, int ny, int nz, Keep keep) {
  core::HexMesh h = test::hex_grid(nx, ny, nz);
  core::HexMesh kept;
  kept.points = h.points;
  for (int k = 0, c = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i, ++c)
        if (keep(i, j, k)) kept.cells.push_back(h.cells[static_cast<std::size_t>(c)]);
  return core::boundary(test::tetrahedralize(kept)).surface;
}

//! A T of 4 unit cubes: the stem (1, 0, 0) under the bar (0..2, 0, 1).
core::TriMesh t_shape() {
  return cells_surface(3, 1, 2, [](int i, int, int k) { return k == 1 || i == 1; });
}

TEST(Printing, ACubeNeedsNoSupportOnAnySide) {
  const core::TriMesh cube = cells_surface(2, 2, 2, [](int, int, int) { return true; });
  for (int a = 0; a < 3; ++a)
    for (const double s : {-1.0, 1.0}) {
      const fabricate::Standing st = fabricate::stand(cube, s * Vec3::Unit(a), {});
      EXPECT_EQ(st.overhang_area, 0.0) << a << " " << s;
      EXPECT_FALSE(st.needs_support()) << a << " " << s;
    }
}

TEST(Printing, AKeelRisingLessSteeplyThanThePrinterCanNeedsSupportThoughNoFaceOverhangs) {
  const fabricate::Standing low = fabricate::stand(test::keel_prism(30), -Vec3::UnitZ(), {});
  EXPECT_EQ(low.overhang_area, 0.0);  // every face is 60 degrees or more from straight down
  EXPECT_EQ(low.keels, 1);
  EXPECT_NEAR(low.keel_length, 4.0, 1e-12);
  EXPECT_EQ(low.tips, 0);
  EXPECT_TRUE(low.needs_support());
  const std::vector<std::uint8_t> marks =
      fabricate::support_marks(test::keel_prism(30), -Vec3::UnitZ(), 45);
  EXPECT_EQ(marks, (std::vector<std::uint8_t>{0, 0, 0, 2, 2, 0, 0, 0}));  // the keel's faces
  // Steeper than the angle, the keel holds itself up; the low end's cap now overhangs (area 2).
  const fabricate::Standing steep = fabricate::stand(test::keel_prism(60), -Vec3::UnitZ(), {});
  EXPECT_EQ(steep.keels, 0);
  EXPECT_NEAR(steep.overhang_area, 2.0, 1e-12);
  // Exactly at the angle the keel holds, as a face exactly at the angle does. So does the end
  // cap, now exactly at the angle too, but only along the one direction straight out of it,
  // which the V's faces cut off at its two lower edges: those are keels, the keel itself not.
  const fabricate::Standing at = fabricate::stand(test::keel_prism(45), -Vec3::UnitZ(), {});
  EXPECT_EQ(at.overhang_area, 0.0);
  EXPECT_EQ(at.keels, 2);
  EXPECT_EQ(fabricate::support_marks(test::keel_prism(45), -Vec3::UnitZ(), 45),
            (std::vector<std::uint8_t>{2, 0, 2, 0, 0, 2, 0, 0}));
  // A printer that takes 65 degrees from the vertical holds the 30-degree keel.
  fabricate::PrintOptions wide;
  wide.overhang_degrees = 65.0;
  EXPECT_EQ(fabricate::stand(test::keel_prism(30), -Vec3::UnitZ(), wide).keels, 0);
  // Upside down the keel is the top ridge.
  EXPECT_EQ(fabricate::stand(test::keel_prism(30), Vec3::UnitZ(), {}).keels, 0);
}

TEST(Printing, AmongSidesNeedingNoSupportAreaTheOneWithoutAKeelIsChosen) {
  fabricate::Part part;
  part.mesh = test::keel_prism(30);
  const Vec3 top = Eigen::AngleAxisd(-M_PI / 6, Vec3::UnitY()) * Vec3::UnitZ();
  // On the keel's end the keel needs support; on its top face, nothing does. The larger side
  // would win a tie of area alone.
  part.sides = {{0, -Vec3::UnitZ(), 3.0}, {1, top, 1.0}};
  const fabricate::PartPrint p = fabricate::check_part_printing(part, {});
  EXPECT_EQ(p.sides[0].support_fraction, 0.0);
  EXPECT_EQ(p.sides[1].support_fraction, 0.0);
  EXPECT_EQ(p.sides[0].keels, 1);
  EXPECT_FALSE(p.sides[1].needs_support());
  EXPECT_EQ(p.best, 1);
}

TEST(Printing, ATipPointingDownUnderAnArmNeedsSupport) {
  // The T with the underside of its arm x in [0, 1] pushed down into a pyramid, apex 0.9 below.
  core::TriMesh t = t_shape();
  const auto under_arm = [&](const std::array<int, 3>& c) {
    return std::all_of(c.begin(), c.end(),
                       [&](int v) { return t.points[v].z() == 1.0 && t.points[v].x() <= 1.0; });
  };
  std::map<std::pair<int, int>, int> sides;  // directed edges of the removed square
  std::vector<std::array<int, 3>> kept;
  for (const auto& c : t.cells) {
    if (!under_arm(c)) {
      kept.push_back(c);
      continue;
    }
    for (int e = 0; e < 3; ++e) ++sides[{c[e], c[(e + 1) % 3]}];
  }
  ASSERT_EQ(kept.size() + 2, t.cells.size());
  const int apex = static_cast<int>(t.points.size());
  t.points.emplace_back(0.5, 0.5, 0.1);
  for (const auto& [edge, n] : sides)
    if (!sides.count({edge.second, edge.first})) kept.push_back({edge.first, edge.second, apex});
  t.cells = kept;
  ASSERT_EQ(core::analyze_surface(t).boundary_edges, 0);
  const fabricate::Standing up = fabricate::stand(t, -Vec3::UnitZ(), {});
  EXPECT_EQ(up.tips, 1);
  EXPECT_EQ(up.keels, 0);                     // the pyramid's faces and edges are steep enough
  EXPECT_NEAR(up.overhang_area, 1.0, 1e-12);  // the other arm's underside
  EXPECT_EQ(fabricate::stand(t, Vec3::UnitZ(), {}).tips, 0);  // upside down: a pit's bottom
}

TEST(Printing, ATOnItsStemNeedsSupportUnderItsArms) {
  const core::TriMesh t = t_shape();
  const fabricate::Standing up = fabricate::stand(t, -Vec3::UnitZ(), {});
  EXPECT_NEAR(up.overhang_area, 2.0, 1e-12);
  EXPECT_NEAR(up.support_fraction, 2.0 / 18.0, 1e-12);
  // Upside down, on the bar's top: the stem's end and the arms' undersides face up.
  EXPECT_EQ(fabricate::stand(t, Vec3::UnitZ(), {}).overhang_area, 0.0);
  // On the end of the bar: the stem's side faces down one unit above the bed.
  EXPECT_NEAR(fabricate::stand(t, Vec3::UnitX(), {}).overhang_area, 1.0, 1e-12);
  // Lying flat, on the T's face: nothing faces down but the bed.
  EXPECT_EQ(fabricate::stand(t, -Vec3::UnitY(), {}).overhang_area, 0.0);
  // The overhang angle: faces exactly horizontal overhang at any angle below 90 degrees.
  fabricate::PrintOptions vertical;
  vertical.overhang_degrees = 89.0;
  EXPECT_NEAR(fabricate::stand(t, -Vec3::UnitZ(), vertical).overhang_area, 2.0, 1e-12);
}

TEST(Printing, ThePartStandsOnItsSideNeedingLeastSupportThatFitsTheChamber) {
  fabricate::Part part;
  part.mesh = t_shape();
  part.sides = {{0, -Vec3::UnitZ(), 1.0}, {1, Vec3::UnitZ(), 3.0}, {2, Vec3::UnitX(), 1.0}};
  const fabricate::PartPrint p = fabricate::check_part_printing(part, {});
  ASSERT_EQ(p.sides.size(), 3u);
  EXPECT_EQ(p.best, 1);  // upside down: no support
  EXPECT_NEAR(p.area, 18.0, 1e-12);
  fabricate::PrintOptions narrow;
  narrow.chamber = {2.5, 2.5, 3.5};  // the bar (3 long) fits only standing on its end
  const fabricate::PartPrint q = fabricate::check_part_printing(part, narrow);
  EXPECT_FALSE(q.sides[0].fits);
  EXPECT_FALSE(q.sides[1].fits);
  EXPECT_TRUE(q.sides[2].fits);
  EXPECT_EQ(q.best, 2);
  EXPECT_NEAR(q.sides[2].support_fraction, 1.0 / 18.0, 1e-12);
}

TEST(Printing, ASolidInOnePieceTakesItsBestAxis) {
  const fabricate::Standing s = fabricate::best_axis_standing(t_shape(), {});
  EXPECT_EQ(s.overhang_area, 0.0);
  EXPECT_EQ(s.down.x(), 0.0);  // on its face or upside down, not on an end (1 square)
}

TEST(Printing, APartStoodOnItsBaseSitsOnTheBedWithTheSameOverhangs) {
  const core::TriMesh t = t_shape();
  const Vec3 tilted = Vec3(1, -2, 0.5).normalized();
  for (const Vec3& down :
       {Vec3(-Vec3::UnitZ()), Vec3(Vec3::UnitZ()), Vec3(Vec3::UnitX()), tilted}) {
    const core::TriMesh on = fabricate::stand_on_bed(t, down);
    ASSERT_EQ(on.cells, t.cells);
    const core::BoundingBox box = core::bounding_box(on.points);
    EXPECT_NEAR(box.min.z(), 0.0, 1e-12);
    EXPECT_NEAR(box.min.x() + box.max.x(), 0.0, 1e-12);
    EXPECT_NEAR(box.min.y() + box.max.y(), 0.0, 1e-12);
    // A rigid motion: every edge keeps its length.
    for (const auto& c : t.cells)
      for (int e = 0; e < 3; ++e)
        EXPECT_NEAR((on.points[c[e]] - on.points[c[(e + 1) % 3]]).norm(),
                    (t.points[c[e]] - t.points[c[(e + 1) % 3]]).norm(), 1e-12);
    EXPECT_EQ(fabricate::overhanging(on, -Vec3::UnitZ(), 45), fabricate::overhanging(t, down, 45))
        << down.transpose();
  }
  // Stood on its stem's end (down = -z): the bar's two arms need support, as in the T above.
  const core::TriMesh upright = fabricate::stand_on_bed(t, -Vec3::UnitZ());
  EXPECT_NEAR(fabricate::stand(upright, -Vec3::UnitZ(), {}).overhang_area, 2.0, 1e-12);
}

}  // namespace
}  // namespace polycube
