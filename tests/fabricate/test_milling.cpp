// Milling checks on unions of unit cubes whose answers are counted by hand (unit squares, each
// subdivided into triangles): a cube is a height field and turns reached on every face; a T on
// its stem cannot be milled under its arms (turned away) nor on the stem's sides under them
// (occluded); a mushroom hides its stem and the plate under its cap; a closed cavity is never
// reached; a pocket is reached from above but not by tools orthogonal to its depth. The rules
// of milling.h hold in any frame, on convex shapes, and the answers repeat.
#include "core/topology.h"
#include "fabricate/milling.h"

#include "../support/fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace polycube {
namespace {

using core::Vec3;
using fabricate::ThreeAxis;

//! The boundary of the unit cells (i, j, k) of an nx x ny x nz grid that `keep` says, each cell
//! cut into res^3 cells so that every unit square of the surface carries 2 res^2 triangles.
template <class Keep>
core::TriMesh cubes_surface(int nx, int ny, int nz, Keep keep, int res = 2) {
  const core::HexMesh h = test::hex_grid(nx * res, ny * res, nz * res, 1.0 / res);
  core::HexMesh kept;
  kept.points = h.points;
  for (int k = 0, c = 0; k < nz * res; ++k)
    for (int j = 0; j < ny * res; ++j)
      for (int i = 0; i < nx * res; ++i, ++c)
        if (keep(i / res, j / res, k / res))
          kept.cells.push_back(h.cells[static_cast<std::size_t>(c)]);
  return core::boundary(test::tetrahedralize(kept)).surface;
}

Vec3 normal(const core::TriMesh& m, std::size_t t) {
  const auto& c = m.cells[t];
  return (m.points[c[1]] - m.points[c[0]]).cross(m.points[c[2]] - m.points[c[0]]).normalized();
}

Vec3 centre(const core::TriMesh& m, std::size_t t) {
  const auto& c = m.cells[t];
  return (m.points[c[0]] + m.points[c[1]] + m.points[c[2]]) / 3.0;
}

//! Triangles whose outward normal is `n` and whose centre is at height `h` along it.
std::vector<int> facing_at(const core::TriMesh& m, const Vec3& n, double h) {
  std::vector<int> out;
  for (std::size_t t = 0; t < m.cells.size(); ++t)
    if (normal(m, t).dot(n) > 1 - 1e-12 && std::abs(centre(m, t).dot(n) - h) < 1e-12)
      out.push_back(static_cast<int>(t));
  return out;
}

//! The triangles of the base: the bottom (z = 0) facing down.
std::vector<int> bottom(const core::TriMesh& m) { return facing_at(m, -Vec3::UnitZ(), 0.0); }

double area_of(const core::TriMesh& m, const std::vector<std::uint8_t>& flags, std::uint8_t v) {
  double a = 0;
  for (std::size_t t = 0; t < m.cells.size(); ++t)
    if (flags[t] == v) {
      const auto& c = m.cells[t];
      a += 0.5 * (m.points[c[1]] - m.points[c[0]]).cross(m.points[c[2]] - m.points[c[0]]).norm();
    }
  return a;
}

core::TriMesh cube() {
  return cubes_surface(
      1, 1, 1, [](int, int, int) { return true; }, 3);
}

//! A T of 4 unit cubes: the stem (1, 0, 0) under the bar (0..2, 0, 1); 18 unit squares.
core::TriMesh t_shape() {
  return cubes_surface(3, 1, 2, [](int i, int, int k) { return k == 1 || i == 1; });
}

//! A 4 x 4 plate (z in [0, 1]), a 2 x 2 stem on its middle (z in [1, 3]) and a 4 x 4 cap
//! (z in [3, 4]); 104 unit squares: plate bottom 16, sides 16, top ring 12; stem sides 16; cap
//! underside ring 12, sides 16, top 16.
core::TriMesh mushroom() {
  return cubes_surface(4, 4, 4, [](int i, int j, int k) {
    return k == 0 || k == 3 || (i >= 1 && i <= 2 && j >= 1 && j <= 2);
  });
}

//! A 3 x 3 x 3 cube without its middle cube: 54 outer unit squares and 6 inward.
core::TriMesh hollow_cube() {
  return cubes_surface(3, 3, 3, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 1); });
}

//! A 3 x 3 x 3 cube with a pocket one deep in the middle of its top: 53 outer unit squares, the
//! pocket's 4 walls and floor (5).
core::TriMesh pocketed_cube() {
  return cubes_surface(3, 3, 3, [](int i, int j, int k) { return !(i == 1 && j == 1 && k == 2); });
}

//! The inside of the cavity of hollow_cube: triangles whose centre is within [1, 2]^3.
bool in_cavity(const Vec3& p) {
  return (p.array() > 1 - 1e-9).all() && (p.array() < 2 + 1e-9).all();
}

TEST(Milling, ACubeOnAnyFaceIsAHeightField) {
  const core::TriMesh c = cube();
  for (int a = 0; a < 3; ++a)
    for (const double s : {-1.0, 1.0}) {
      const Vec3 down = s * Vec3::Unit(a);
      const std::vector<int> base = facing_at(c, down, s > 0 ? 1.0 : 0.0);
      ASSERT_EQ(base.size(), 18u);  // 3 x 3 squares, 2 triangles each
      const ThreeAxis r = fabricate::three_axis(c, down, base);
      // The four sides are vertical: side-on to the tool, reachable (thesis §6.5.2).
      EXPECT_EQ(r.unreachable, 0.0) << a << " " << s;
      EXPECT_NEAR(area_of(c, r.triangle, ThreeAxis::kBase), 1.0, 1e-12);
      EXPECT_NEAR(area_of(c, r.triangle, ThreeAxis::kReachable), 5.0, 1e-12);
    }
}

TEST(Milling, ACubeTurnsReachedOnEveryFaceEndsIncluded) {
  const core::TriMesh c = cube();
  for (int a = 0; a < 3; ++a) {
    // Through the centre, and through a point off it (only the direction matters).
    for (const Vec3& p : {Vec3(0.5, 0.5, 0.5), Vec3(3.0, -2.0, 0.25)}) {
      const fabricate::FourAxis r = fabricate::four_axis(c, {p, Vec3::Unit(a)}, 40);
      EXPECT_EQ(r.unreached, 0.0) << a;
      // The end faces (normal along the axis) are side-on to every tool: reached by the flank.
      for (const int t : facing_at(c, Vec3::Unit(a), 1.0)) EXPECT_EQ(r.reached[t], 1);
      for (const int t : facing_at(c, -Vec3::Unit(a), 0.0)) EXPECT_EQ(r.reached[t], 1);
    }
  }
  // With 4 directions the faces along the axis are faced head-on, the ends side-on.
  EXPECT_EQ(fabricate::four_axis(c, {Vec3::Zero(), Vec3::UnitX()}, 4).unreached, 0.0);
}

TEST(Milling, ATOnItsStemIsNoHeightFieldUnderItsArms) {
  const core::TriMesh t = t_shape();
  const std::vector<int> base = bottom(t);
  ASSERT_EQ(base.size(), 8u);  // the stem's end: one square of 2 x 2 x 2 triangles
  const ThreeAxis r = fabricate::three_axis(t, -Vec3::UnitZ(), base);
  // The arms' undersides (2 of 18 squares) face down; the stem's sides under them (2) face
  // sideways but the arms hang over them; its front and back are flush with the bar's.
  EXPECT_NEAR(r.height_field_unreachable, 2.0 / 18.0, 1e-12);
  EXPECT_NEAR(r.occluded, 2.0 / 18.0, 1e-12);
  EXPECT_NEAR(r.unreachable, 4.0 / 18.0, 1e-12);
  for (const int i : facing_at(t, -Vec3::UnitZ(), 1.0))
    EXPECT_EQ(r.triangle[i], ThreeAxis::kTurnedAway);
  for (const int i : facing_at(t, -Vec3::UnitX(), 1.0)) {
    if (centre(t, i).z() < 1) {
      EXPECT_EQ(r.triangle[i], ThreeAxis::kOccluded);
    }
  }
  for (const int i : facing_at(t, Vec3::UnitX(), 2.0)) {
    if (centre(t, i).z() < 1) {
      EXPECT_EQ(r.triangle[i], ThreeAxis::kOccluded);
    }
  }
  EXPECT_NEAR(area_of(t, r.triangle, ThreeAxis::kReachable), 13.0, 1e-12);

  // Upside down on the bar's top: a height field.
  const ThreeAxis flipped =
      fabricate::three_axis(t, Vec3::UnitZ(), facing_at(t, Vec3::UnitZ(), 2.0));
  EXPECT_EQ(flipped.unreachable, 0.0);
  // Turning about the bar's length (x), about the T's depth (y): everything is reached.
  EXPECT_EQ(fabricate::four_axis(t, {Vec3(0, 0.5, 1), Vec3::UnitX()}).unreached, 0.0);
  EXPECT_EQ(fabricate::four_axis(t, {Vec3(1.5, 0, 1), Vec3::UnitY()}).unreached, 0.0);
}

TEST(Milling, AMushroomHidesItsStemAndPlateUnderItsCap) {
  const core::TriMesh m = mushroom();
  const ThreeAxis r = fabricate::three_axis(m, -Vec3::UnitZ(), bottom(m));
  // Turned away: the cap's underside ring (12 of 104). Occluded: the stem's sides (16) and the
  // plate's top ring (12), all under the cap; the plate's sides are flush with the cap's.
  EXPECT_NEAR(r.height_field_unreachable, 12.0 / 104.0, 1e-12);
  EXPECT_NEAR(r.occluded, 28.0 / 104.0, 1e-12);
  EXPECT_NEAR(r.unreachable, 40.0 / 104.0, 1e-12);
  EXPECT_NEAR(area_of(m, r.triangle, ThreeAxis::kBase), 16.0, 1e-12);
  for (const int i : facing_at(m, Vec3::UnitZ(), 1.0))
    EXPECT_EQ(r.triangle[i], ThreeAxis::kOccluded);

  // Turning about the stem (z), tools horizontal: the stem's sides face them under the cap,
  // the plate's top and cap's underside are side-on and reached beside the stem (from the
  // side away from it); about x the same holds for the y and z faces. Nothing is unreached.
  for (const Vec3& dir : std::vector<Vec3>{Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitY()}) {
    const fabricate::FourAxis f = fabricate::four_axis(m, {Vec3(2, 2, 2), dir});
    EXPECT_EQ(f.unreached, 0.0) << dir.transpose();
  }
  // With only the 4 head-on directions about x, the stem's x sides (side-on) are still reached:
  // the tool along y passes between plate and cap.
  EXPECT_EQ(fabricate::four_axis(m, {Vec3(2, 2, 2), Vec3::UnitX()}, 4).unreached, 0.0);
}

TEST(Milling, AClosedCavityIsNeverReached) {
  const core::TriMesh h = hollow_cube();
  // 3-axis: the cavity's ceiling faces down (1 of 60), its floor and walls are under the top (5).
  const ThreeAxis r = fabricate::three_axis(h, -Vec3::UnitZ(), bottom(h));
  EXPECT_NEAR(r.height_field_unreachable, 1.0 / 60.0, 1e-12);
  EXPECT_NEAR(r.occluded, 5.0 / 60.0, 1e-12);
  for (std::size_t t = 0; t < h.cells.size(); ++t) {
    if (in_cavity(centre(h, t))) {
      EXPECT_NE(r.triangle[t], ThreeAxis::kReachable);
    }
  }
  // 4-axis about the coordinate axes and the automatic one: the 6 inner squares, no more.
  const fabricate::Axis automatic = fabricate::choose_axis(h);
  for (const fabricate::Axis& axis :
       {fabricate::Axis{Vec3(1.5, 1.5, 1.5), Vec3::UnitX()},
        fabricate::Axis{Vec3(1.5, 1.5, 1.5), Vec3::UnitY()},
        fabricate::Axis{Vec3(1.5, 1.5, 1.5), Vec3::UnitZ()}, automatic}) {
    const fabricate::FourAxis f = fabricate::four_axis(h, axis);
    EXPECT_NEAR(f.unreached, 6.0 / 60.0, 1e-12) << axis.direction.transpose();
    for (std::size_t t = 0; t < h.cells.size(); ++t)
      EXPECT_EQ(f.reached[t], in_cavity(centre(h, t)) ? 0 : 1);
  }
}

TEST(Milling, APocketIsMilledFromAboveButNotAcrossItsDepth) {
  const core::TriMesh p = pocketed_cube();
  // From above the pocket's floor faces the tool and its walls are side-on: a height field.
  EXPECT_EQ(fabricate::three_axis(p, -Vec3::UnitZ(), bottom(p)).unreachable, 0.0);
  // Turning about its depth (z) every tool is orthogonal to it: its walls and floor (5 of 58)
  // are behind the cube's walls.
  EXPECT_NEAR(fabricate::four_axis(p, {Vec3(1.5, 1.5, 1.5), Vec3::UnitZ()}).unreached, 5.0 / 58.0,
              1e-12);
  // Turning about x the tool comes from above too.
  EXPECT_EQ(fabricate::four_axis(p, {Vec3(1.5, 1.5, 1.5), Vec3::UnitX()}).unreached, 0.0);
  // The automatic axis is across the depth: the normal covariance's smallest eigenvalue is z's
  // (18 against 20), whose check leaves the pocket; x or y reach everything.
  const fabricate::Axis a = fabricate::choose_axis(p);
  EXPECT_NEAR(a.direction.z(), 0.0, 1e-12);
  EXPECT_NEAR(a.direction.norm(), 1.0, 1e-12);
  EXPECT_NEAR((a.point - Vec3(1.5, 1.5, 1.5)).head<2>().norm(), 0.0, 1e-12);
  EXPECT_EQ(fabricate::four_axis(p, a).unreached, 0.0);
}

TEST(Milling, ConvexPartsHaveNothingOccluded) {
  // A sphere: only its lower half is turned away from above; every triangle turns reached.
  const core::TriMesh s = test::sphere(4);
  const ThreeAxis r = fabricate::three_axis(s, -Vec3::UnitZ(), {});
  EXPECT_EQ(r.occluded, 0.0);
  for (std::size_t t = 0; t < s.cells.size(); ++t)
    EXPECT_EQ(r.triangle[t] == ThreeAxis::kTurnedAway, normal(s, t).z() < -1e-9) << t;
  for (const Vec3& dir : std::vector<Vec3>{Vec3::UnitZ(), Vec3(1, 2, 3).normalized()})
    EXPECT_EQ(fabricate::four_axis(s, {Vec3::Zero(), dir}).unreached, 0.0);
}

TEST(Milling, TheAnswersDoNotDependOnTheFrame) {
  // The mushroom turned and moved far away: side-on faces are no longer exactly side-on.
  const core::TriMesh m = mushroom();
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  const Vec3 shift(1000.0, -250.0, 40.0);
  core::TriMesh moved = m;
  for (Vec3& q : moved.points) q = rot * q + shift;
  const ThreeAxis a = fabricate::three_axis(m, -Vec3::UnitZ(), bottom(m));
  const ThreeAxis b = fabricate::three_axis(moved, rot * -Vec3::UnitZ(), bottom(m));
  EXPECT_EQ(a.triangle, b.triangle);
  EXPECT_NEAR(b.unreachable, 40.0 / 104.0, 1e-9);
  const fabricate::FourAxis fa = fabricate::four_axis(m, {Vec3(2, 2, 2), Vec3::UnitX()});
  const fabricate::FourAxis fb =
      fabricate::four_axis(moved, {rot * Vec3(2, 2, 2) + shift, rot * Vec3::UnitX()});
  EXPECT_EQ(fa.reached, fb.reached);
  const core::TriMesh h = hollow_cube();
  core::TriMesh hm = h;
  for (Vec3& q : hm.points) q = rot * q + shift;
  EXPECT_NEAR(fabricate::four_axis(hm, {shift, rot * Vec3::UnitY()}).unreached, 6.0 / 60.0, 1e-9);
}

TEST(Milling, TwoRunsGiveTheSameAnswers) {
  // A bumpy torus: parts of it are hidden from every direction of a check.
  core::TriMesh torus = test::split_quads(test::torus_quads(60, 40));
  for (Vec3& q : torus.points) q *= 1.0 + 0.1 * std::sin(5 * q.x()) * std::cos(3 * q.y());
  const fabricate::Axis axis = fabricate::choose_axis(torus);
  EXPECT_EQ(axis.point, fabricate::choose_axis(torus).point);
  EXPECT_EQ(axis.direction, fabricate::choose_axis(torus).direction);
  const fabricate::FourAxis a = fabricate::four_axis(torus, {Vec3::Zero(), Vec3::UnitZ()});
  const fabricate::FourAxis b = fabricate::four_axis(torus, {Vec3::Zero(), Vec3::UnitZ()});
  EXPECT_EQ(a.reached, b.reached);
  EXPECT_EQ(a.unreached, b.unreached);
  EXPECT_GT(a.unreached, 0.0);  // the inner side facing the hole, behind the far side
  const ThreeAxis c = fabricate::three_axis(torus, -Vec3::UnitX(), {});  // on edge
  const ThreeAxis d = fabricate::three_axis(torus, -Vec3::UnitX(), {});
  EXPECT_EQ(c.triangle, d.triangle);
  EXPECT_EQ(c.unreachable, d.unreachable);
  EXPECT_GT(c.occluded, 0.0);  // the far half of the ring behind the near one
}

}  // namespace
}  // namespace polycube
