// The built-in samples (CSG parts, genus 0..2) get valid labelings, checked independently.
#include "construct/pipeline.h"
#include "samples/samples.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace polycube {
namespace {

class SampleLabeling : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleLabeling, IsValid) {
  const core::TriMesh s = samples::make_sample(GetParam());
  const auto mesh = construct::tetrahedralize(s).mesh;
  test::expect_valid(test::run_pipeline(mesh), GetParam());
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleLabeling,
                         ::testing::Values("box-cylinder", "l-bracket", "flange", "ring"),
                         [](const auto& param_info) {
                           std::string n = param_info.param;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace polycube
