// Scaled Jacobian: the Verdict values of issue 3 on single elements, tets and quads, summaries.
#include "quality/scaled_jacobian.h"

#include "core/errors.h"

#include "quality_fixtures.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace polycube::quality {
namespace {

using core::Vec3;
using test::unit_hex;

constexpr double kTol = 1e-9;

TEST(HexScaledJacobian, UnitCubeIsOne) {
  const auto e = hex_scaled_jacobian(unit_hex());
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, 1.0, kTol);
}

TEST(HexScaledJacobian, ScaledAndTranslatedCubeIsOne) {
  auto p = unit_hex();
  for (auto& v : p) v = 1e-4 * v + Vec3(1e3, -2e3, 5.0);
  const auto e = hex_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, 1.0, 1e-6);  // translation by 1e3 of a 1e-4 cube costs ~1e-12/1e-4 digits
}

TEST(HexScaledJacobian, InsideOutCubeIsMinusOne) {
  const auto c = unit_hex();
  const std::array<Vec3, 8> p{c[4], c[5], c[6], c[7], c[0], c[1], c[2], c[3]};  // rings swapped
  const auto e = hex_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, -1.0, kTol);
}

TEST(HexScaledJacobian, ShearMatchesVerdict) {
  // x += s z: the values Verdict (ParaView) reports, given in issue 3.
  const std::array<std::pair<double, double>, 3> cases{
      {{0.5, 0.8944271910}, {1.0, 0.7071067812}, {2.0, 0.4472135955}}};
  for (const auto& [s, expected] : cases) {
    auto p = unit_hex();
    for (auto& v : p) v.x() += s * v.z();
    const auto e = hex_scaled_jacobian(p);
    EXPECT_TRUE(e.valid);
    EXPECT_NEAR(e.value, expected, kTol) << "s = " << s;
    EXPECT_NEAR(e.value, 1.0 / std::sqrt(1.0 + s * s), 1e-12);  // cos of the shear angle
  }
}

TEST(HexScaledJacobian, TwistedTopFaceMatchesVerdict) {
  auto p = unit_hex();
  const double a = std::numbers::pi / 2;
  for (int i = 4; i < 8; ++i) {
    const double x = p[i].x() - 0.5, y = p[i].y() - 0.5;
    p[i].x() = 0.5 + std::cos(a) * x - std::sin(a) * y;
    p[i].y() = 0.5 + std::sin(a) * x + std::cos(a) * y;
  }
  const auto e = hex_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, 0.7071067812, kTol);
}

TEST(HexScaledJacobian, CollapsedEdgeIsInvalid) {
  auto p = unit_hex();
  p[1] = p[0];
  auto e = hex_scaled_jacobian(p);
  EXPECT_FALSE(e.valid);
  EXPECT_EQ(e.value, kInvalidScaledJacobian);

  // Collapsed up to rounding, on a large far-away element: still invalid (relative threshold).
  p = unit_hex();
  for (auto& v : p) v = 1e3 * v + Vec3(1e6, 0, 0);
  p[6] = p[7] + Vec3(1e-10, 0, 0);
  e = hex_scaled_jacobian(p);
  EXPECT_FALSE(e.valid);

  // A whole face collapsed to a point, and a non-finite coordinate.
  p = unit_hex();
  p[5] = p[6] = p[7] = p[4];
  EXPECT_FALSE(hex_scaled_jacobian(p).valid);
  p = unit_hex();
  p[3].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(hex_scaled_jacobian(p).valid);
}

TEST(HexScaledJacobian, FlatHexIsZeroNotInvalid) {
  // All points in the plane z = 0 but no zero-length vector: a valid, zero-quality element.
  auto p = unit_hex();
  for (int i = 4; i < 8; ++i) p[i] = p[i - 4] + Vec3(0.3, 0.1, 0.0);
  const auto e = hex_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_LE(e.value, 1e-12);
}

TEST(TetScaledJacobian, RegularAndCornerTets) {
  // Regular tet: 1.
  std::array<Vec3, 4> p{Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)};
  if ((p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) < 0) std::swap(p[2], p[3]);
  auto e = tet_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, 1.0, kTol);

  // Corner tet (0, e1, e2, e3): det 1, worst corner product 1 * sqrt2 * sqrt2 = 2: sqrt2 / 2.
  p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  e = tet_scaled_jacobian(p);
  EXPECT_NEAR(e.value, std::sqrt(2.0) / 2.0, kTol);
  std::swap(p[2], p[3]);  // inverted
  e = tet_scaled_jacobian(p);
  EXPECT_TRUE(e.valid);
  EXPECT_NEAR(e.value, -std::sqrt(2.0) / 2.0, kTol);

  p[3] = p[0];  // collapsed edge
  EXPECT_FALSE(tet_scaled_jacobian(p).valid);
}

TEST(QuadScaledJacobian, SquareRhombusAndOrientation) {
  std::array<Vec3, 4> p{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  EXPECT_NEAR(quad_scaled_jacobian(p).value, 1.0, kTol);
  EXPECT_NEAR(quad_scaled_jacobian(p, Vec3(0, 0, 2)).value, 1.0, kTol);
  // Seen from below (reference normal -z) the square is clockwise: inverted.
  EXPECT_NEAR(quad_scaled_jacobian(p, Vec3(0, 0, -1)).value, -1.0, kTol);

  // 60 degree rhombus: sin 60.
  const double c = 0.5, s = std::sqrt(3.0) / 2;
  p = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1 + c, s, 0), Vec3(c, s, 0)};
  EXPECT_NEAR(quad_scaled_jacobian(p).value, s, kTol);

  // Non-convex (arrow) quad: one corner has a negative cross product.
  p = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 2, 0), Vec3(1.5, 0.5, 0)};
  EXPECT_LT(quad_scaled_jacobian(p, Vec3(0, 0, 1)).value, 0.0);

  p[3] = p[2];  // collapsed
  EXPECT_FALSE(quad_scaled_jacobian(p).valid);
}

TEST(ScaledJacobianSummary, CountsHistogramAndField) {
  core::HexMesh m = test::gridded_box(2, 1, 1, 2);  // 16 unit-ish hexes
  ASSERT_EQ(m.num_cells(), 16);
  // Invert hex 3 (swap its rings) and collapse one edge of hex 5 (duplicate a vertex index).
  auto& h3 = m.cells[3];
  h3 = {h3[4], h3[5], h3[6], h3[7], h3[0], h3[1], h3[2], h3[3]};
  m.cells[5][1] = m.cells[5][0];
  const auto s = scaled_jacobian(m);
  EXPECT_EQ(s.count, 16);
  EXPECT_EQ(s.inverted, 1);
  EXPECT_EQ(s.invalid, 1);
  EXPECT_FALSE(s.all_positive());
  EXPECT_NEAR(s.min, -1.0, kTol);
  EXPECT_NEAR(s.max, 1.0, kTol);
  EXPECT_NEAR(s.average, (14.0 - 1.0 - 1.0) / 16.0, kTol);
  EXPECT_EQ(s.histogram[0], 2);
  EXPECT_EQ(s.histogram[kHistogramBins - 1], 14);
  const core::Field f = s.field();
  EXPECT_EQ(f.name, "scaled_jacobian");
  ASSERT_EQ(f.values.size(), 16u);
  EXPECT_NEAR(f.values[3], -1.0, kTol);
  EXPECT_EQ(f.values[5], kInvalidScaledJacobian);

  const auto lean = scaled_jacobian(m, ScaledJacobianOptions{false});
  EXPECT_TRUE(lean.values.empty());
  EXPECT_EQ(lean.inverted, 1);
  EXPECT_DOUBLE_EQ(lean.average, s.average);
}

TEST(ScaledJacobianSummary, HistogramBinEdges) {
  // A value exactly on a bin edge goes to the bin it closes: (0.2 (k-1), 0.2 k].
  core::HexMesh m;
  for (const auto& v : unit_hex()) m.points.push_back(v);
  m.cells.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  const auto s = scaled_jacobian(m);
  EXPECT_EQ(s.histogram[5], 1);  // 1.0 is in (0.8, 1]
  EXPECT_DOUBLE_EQ(histogram_bin_lower(1), 0.0);
  EXPECT_DOUBLE_EQ(histogram_bin_upper(5), 1.0);
}

TEST(ScaledJacobianSummary, BadIndicesThrow) {
  core::HexMesh m = test::gridded_box(1, 1, 1, 1);
  m.cells[0][7] = 99;
  EXPECT_THROW(scaled_jacobian(m), core::InputError);
  core::QuadMesh q;
  q.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  q.cells.push_back({0, 1, 2, 3});
  EXPECT_THROW(scaled_jacobian(q, {}, {Vec3(0, 0, 1), Vec3(0, 0, 1)}), core::InputError);
  EXPECT_NEAR(scaled_jacobian(q, {}, {Vec3(0, 0, -1)}).min, -1.0, kTol);
}

TEST(ScaledJacobianSummary, EmptyMesh) {
  const auto s = scaled_jacobian(core::HexMesh{});
  EXPECT_EQ(s.count, 0);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.average, 0.0);
  EXPECT_TRUE(s.all_positive());
}

}  // namespace
}  // namespace polycube::quality
