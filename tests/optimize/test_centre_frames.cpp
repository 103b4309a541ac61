// The centre tet of a hex: found where the centre decides Verdict's scaled Jacobian, its frame
// exactly a quarter of the principal axes, and an untangling with it makes such a hex valid.
#include "core/elements.h"
#include "optimize/centre_frames.h"
#include "quality/scaled_jacobian.h"
#include "solve/untangle.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

namespace polycube {
namespace {

using core::Vec3;

//! A flat hex from an optimized mesh of a thin part: every corner positive, the centre negative.
core::HexMesh centre_inverted_hex() {
  core::HexMesh m;
  m.points = {{0.278, 0.358, 0.481}, {0.373, 0.409, 0.476}, {0.371, 0.406, 0.461},
              {0.282, 0.377, 0.482}, {0.286, 0.347, 0.485}, {0.362, 0.415, 0.469},
              {0.362, 0.412, 0.459}, {0.284, 0.353, 0.487}};
  m.cells = {{0, 1, 2, 3, 4, 5, 6, 7}};
  return m;
}

double corner_det(const core::HexMesh& m, int i) {
  const auto& nb = core::kHexCornerNeighbors[i];
  const Vec3& p = m.points[i];
  return (m.points[nb[0]] - p).dot((m.points[nb[1]] - p).cross(m.points[nb[2]] - p));
}

std::array<Vec3, 8> corners(const core::HexMesh& m) {
  std::array<Vec3, 8> p;
  for (int i = 0; i < 8; ++i) p[i] = m.points[m.cells[0][i]];
  return p;
}

TEST(CentreFrames, CentreInvertedHexHasVerdictsCentreValue) {
  const core::HexMesh m = centre_inverted_hex();
  for (int i = 0; i < 8; ++i) EXPECT_GT(corner_det(m, i), 0.0) << "corner " << i;
  const double centre = optimize::centre_value(m, m.cells[0]);
  EXPECT_LT(centre, 0.0);
  EXPECT_NEAR(quality::hex_scaled_jacobian(corners(m)).value, centre, 1e-12);
  core::HexMesh cube = m;
  cube.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                 {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  EXPECT_NEAR(optimize::centre_value(cube, cube.cells[0]), 1.0, 1e-15);  // a cube: all 9 are 1
  cube.points[6] = {1.3, 1.2, 1.1};  // corners drop below the centre: Verdict's value is a corner's
  EXPECT_GT(optimize::centre_value(cube, cube.cells[0]),
            quality::hex_scaled_jacobian(corners(cube)).value);
}

TEST(CentreFrames, CentreTetIsAQuarterOfThePrincipalAxes) {
  const core::HexMesh m = centre_inverted_hex();
  const solve::LinearReduction r = solve::identity_reduction(8);
  solve::TetElements el;
  const std::vector<std::array<double, 3>> lengths{{0.1, 0.2, 0.3}};
  const solve::LinearReduction ext = optimize::with_centre_tets(r, m, lengths, {2.0}, 0.5, el);
  ASSERT_EQ(ext.num_points(), 16);
  ASSERT_EQ(el.size(), 1);
  const std::vector<Vec3> x = solve::unflatten(ext.apply(solve::flatten(m.points)));
  const auto& p = m.points;
  const Vec3 x1 = p[1] + p[2] + p[5] + p[6] - p[0] - p[3] - p[4] - p[7];
  const Vec3 x2 = p[2] + p[3] + p[6] + p[7] - p[0] - p[1] - p[4] - p[5];
  const Vec3 x3 = p[4] + p[5] + p[6] + p[7] - p[0] - p[1] - p[2] - p[3];
  const auto& t = el.tets[0];
  EXPECT_LT((x[t[0]] - 0.25 * (p[0] + p[3] + p[4] + p[7])).norm(), 1e-15);
  EXPECT_LT((x[t[1]] - x[t[0]] - 0.25 * x1).norm(), 1e-15);
  EXPECT_LT((x[t[2]] - x[t[0]] - 0.25 * x2).norm(), 1e-15);
  EXPECT_LT((x[t[3]] - x[t[0]] - 0.25 * x3).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(el.weights[0], 0.5 * 2.0 * 0.1 * 0.2 * 0.3 / 6.0);
  // J = [X1 X2 X3] / 4 divided column by column by the reference lengths.
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 4; ++i) J += x[t[i]] * el.gradients[0].row(i);
  EXPECT_LT((J.col(0) - 0.25 * x1 / 0.1).norm(), 1e-12);
  EXPECT_LT((J.col(2) - 0.25 * x3 / 0.3).norm(), 1e-12);
}

TEST(CentreFrames, UntanglingWithTheCentreTetMakesTheHexValid) {
  core::HexMesh m = centre_inverted_hex();
  ASSERT_LE(quality::hex_scaled_jacobian(corners(m)).value, 0.0);
  // Bottom face fixed, top free; corner tets against a cube corner of the hex's size.
  std::vector<int> var(24, -1);
  int n = 0;
  for (int i = 12; i < 24; ++i) var[i] = n++;
  const solve::LinearReduction r = solve::index_reduction(var, n, solve::flatten(m.points));
  const double h = 0.05;
  std::vector<Vec3> ref{{0, 0, 0}, {h, 0, 0}, {h, h, 0}, {0, h, 0},
                        {0, 0, h}, {h, 0, h}, {h, h, h}, {0, h, h}};
  std::vector<std::array<int, 4>> tets;
  for (int i = 0; i < 8; ++i)
    tets.push_back({i, core::kHexCornerNeighbors[i][0], core::kHexCornerNeighbors[i][1],
                    core::kHexCornerNeighbors[i][2]});
  solve::TetElements el = solve::reference_elements(ref, tets);
  const solve::LinearReduction ext = optimize::with_centre_tets(r, m, {{h, h, h}}, {1.0}, 1.0, el);
  Eigen::VectorXd y(n);
  for (int i = 12; i < 24; ++i) y[var[i]] = m.points[i / 3][i % 3];
  const solve::UntangleResult res = solve::untangle(el, ext, y, {});
  EXPECT_GT(res.inverted_before, 0);
  EXPECT_TRUE(res.untangled);
  std::vector<Vec3> x = solve::unflatten(ext.apply(y));
  x.resize(8);
  m.points = x;
  EXPECT_GT(quality::hex_scaled_jacobian(corners(m)).value, 0.0);
}

}  // namespace
}  // namespace polycube
