// Map distortion of tet maps with known Jacobians.
#include "quality/distortion.h"

#include "core/errors.h"
#include "quality_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <cmath>

namespace polycube::quality {
namespace {

using core::Vec3;

std::vector<Vec3> mapped(const core::TetMesh& m, const Eigen::Matrix3d& a) {
  std::vector<Vec3> out;
  for (const auto& p : m.points) out.push_back(a * p + Vec3(3, -1, 2));
  return out;
}

TEST(MapDistortion, IdentityIsOne) {
  const auto m = test::tet_grid(3);
  const auto d = map_distortion(m, m.points);
  EXPECT_EQ(d.tets, 6 * 27);
  EXPECT_EQ(d.invalid, 0);
  for (const auto* s : {&d.isometric, &d.conformal, &d.volume}) {
    EXPECT_NEAR(s->average, 1.0, 1e-12);
    EXPECT_NEAR(s->max, 1.0, 1e-12);
  }
  for (double v : d.per_tet_isometric) EXPECT_NEAR(v, 1.0, 1e-12);
  for (double v : d.per_tet_volume_ratio) EXPECT_NEAR(v, 1.0, 1e-12);
}

TEST(MapDistortion, UniformScaleByTwo) {
  const auto m = test::tet_grid(2);
  const auto d = map_distortion(m, mapped(m, 2.0 * Eigen::Matrix3d::Identity()));
  EXPECT_NEAR(d.isometric.max, 2.0, 1e-12);
  EXPECT_NEAR(d.isometric.average, 2.0, 1e-12);
  EXPECT_NEAR(d.conformal.max, 1.0, 1e-12);
  EXPECT_NEAR(d.volume.average, 8.0, 1e-11);

  // Normalizing the volume removes the global scale.
  const auto n =
      map_distortion(m, mapped(m, 2.0 * Eigen::Matrix3d::Identity()), DistortionOptions{true});
  EXPECT_NEAR(n.target_scale, 0.5, 1e-12);
  EXPECT_NEAR(n.isometric.max, 1.0, 1e-12);
  EXPECT_NEAR(n.volume.max, 1.0, 1e-12);
}

TEST(MapDistortion, RotatedAnisotropicScale) {
  // J = R diag(1, 2, 4): singular values 4, 2, 1: isometric 4, conformal 4, volume 8.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Matrix3d a = r * Vec3(1, 2, 4).asDiagonal();
  const auto m = test::tet_grid(2);
  const auto d = map_distortion(m, mapped(m, a));
  EXPECT_EQ(d.invalid, 0);
  EXPECT_NEAR(d.isometric.max, 4.0, 1e-10);
  EXPECT_NEAR(d.conformal.average, 4.0, 1e-10);
  EXPECT_NEAR(d.volume.max, 8.0, 1e-10);

  // Shrinking: diag(0.5, 1, 1): isometric 1/0.5 = 2, volume max(0.5, 2) = 2.
  const auto s = map_distortion(m, mapped(m, Vec3(0.5, 1, 1).asDiagonal()));
  EXPECT_NEAR(s.isometric.max, 2.0, 1e-12);
  EXPECT_NEAR(s.conformal.max, 2.0, 1e-12);
  EXPECT_NEAR(s.volume.max, 2.0, 1e-12);
  EXPECT_NEAR(s.per_tet_volume_ratio[0], 0.5, 1e-12);
}

TEST(MapDistortion, InvertedTetsAreCounted) {
  // A mirror flips every tet.
  const auto m = test::tet_grid(1);
  const auto mirror = map_distortion(m, mapped(m, Vec3(-1, 1, 1).asDiagonal()));
  EXPECT_EQ(mirror.inverted_target, 6);
  EXPECT_EQ(mirror.inverted_source, 0);
  EXPECT_EQ(mirror.invalid, 6);
  EXPECT_TRUE(std::isinf(mirror.per_tet_isometric[0]));
  EXPECT_EQ(mirror.isometric.max, 0.0);  // no valid tet
  EXPECT_EQ(mirror.fields()[0].values[0], -1.0);

  // Moving the centre vertex of a 2^3 grid far outside flips some of the tets around it.
  auto g = test::tet_grid(2);
  auto target = g.points;
  int centre = -1;
  for (std::size_t v = 0; v < target.size(); ++v)
    if ((target[v] - Vec3(0.5, 0.5, 0.5)).norm() < 1e-12) centre = static_cast<int>(v);
  ASSERT_GE(centre, 0);
  target[centre] = Vec3(0.5, 0.5, 3.0);
  int expected = 0;
  for (const auto& t : g.cells)
    if (test::signed_tet_volume(target, t) <= 0) ++expected;
  ASSERT_GT(expected, 0);
  const auto d = map_distortion(g, target);
  EXPECT_EQ(d.inverted_target, expected);
  EXPECT_EQ(d.invalid, expected);

  // A flat tet in the target is counted too (exact predicate, exactly zero volume).
  auto flat = g.points;
  const auto& t0 = g.cells[0];
  flat[t0[3]] =
      flat[t0[0]] + 0.5 * (flat[t0[1]] - flat[t0[0]]) + 0.25 * (flat[t0[2]] - flat[t0[0]]);
  EXPECT_GE(map_distortion(g, flat).inverted_target, 1);
}

TEST(MapDistortion, BadInputThrows) {
  const auto m = test::tet_grid(1);
  auto short_target = m.points;
  short_target.pop_back();
  EXPECT_THROW(map_distortion(m, short_target), core::InputError);
  auto nan_target = m.points;
  nan_target[0].x() = std::nan("");
  EXPECT_THROW(map_distortion(m, nan_target), core::InputError);
  auto mirror = mapped(m, Vec3(-1, 1, 1).asDiagonal());
  EXPECT_THROW(map_distortion(m, mirror, DistortionOptions{true}), core::GeometryError);
}

}  // namespace
}  // namespace polycube::quality
