// Whole construction (construct_polycube) on the quick shapes of ../shared/data: the result is
// accepted by the independent certifier and its simplification is certified
// (construct/model_checks.h). The larger models are in test_construct_heavy.cpp.
#include "construct/model_checks.h"
#include "samples/samples.h"

#include <gtest/gtest.h>

namespace polycube {
namespace {

using test::construct_file;
using test::expect_certified;
using test::expect_simplified;
using test::kData;

TEST(ConstructModels, Torus) { construct_file(kData / "surface/torus.obj"); }
TEST(ConstructModels, CubeMinusSphere) { construct_file(kData / "surface/cube_minus_sphere.obj"); }
TEST(ConstructModels, TetB0) { construct_file(kData / "tet/B0.mesh"); }
TEST(ConstructModels, TetSphere) { construct_file(kData / "tet/sphere.mesh"); }
TEST(ConstructModels, Fandisk) { construct_file(kData / "surface/fandisk.obj"); }
TEST(ConstructModels, B0Surface) { construct_file(kData / "surface/B0.obj"); }
TEST(ConstructModels, TetS3) { construct_file(kData / "tet/S3.mesh"); }
TEST(ConstructModels, ThreeHoles) { construct_file(kData / "surface/3holes.obj"); }

TEST(ConstructModels, DeterministicBitForBit) {
  const auto path = kData / "surface/torus.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "missing " << path;
  const core::TriMesh s = io::read_surface(path);
  const auto a = construct::construct_polycube(s);
  const auto b = construct::construct_polycube(s);
  EXPECT_EQ(a.map.tets, b.map.tets);
  EXPECT_EQ(a.labels, b.labels);
  ASSERT_EQ(a.map.polycube.size(), b.map.polycube.size());
  for (std::size_t v = 0; v < a.map.polycube.size(); ++v) {
    EXPECT_EQ(a.map.polycube[v], b.map.polycube[v]) << v;
    EXPECT_EQ(a.map.model[v], b.map.model[v]) << v;
  }
}

class ConstructSample : public ::testing::TestWithParam<std::string> {};
TEST_P(ConstructSample, IsCertified) {
  const construct::ConstructResult r = construct::construct_polycube(samples::make_sample(GetParam()));
  expect_certified(r, GetParam());
  expect_simplified(r, GetParam());
}
INSTANTIATE_TEST_SUITE_P(Samples, ConstructSample, ::testing::Values("box-cylinder", "l-bracket", "flange", "ring"),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace polycube
