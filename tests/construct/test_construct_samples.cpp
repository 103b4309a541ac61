// The built-in samples (CSG parts, genus 0..2) get valid labelings, checked independently.
#include "construct/pipeline.h"
#include "construct/polycube_estimate.h"
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

// Unfolding against the polycube estimate keeps the labeling valid (independent validator) and
// never folds more; the estimate's folded count is recomputed here, not taken from the result.
TEST_P(SampleLabeling, UnfoldKeepsValidityAndNeverFoldsMore) {
  const core::TriMesh s = samples::make_sample(GetParam());
  const auto p = test::run_pipeline(construct::tetrahedralize(s).mesh);
  ASSERT_TRUE(p.repair.valid());
  const auto before = construct::estimate_polycube(p.surface, p.labels);
  const auto un = construct::unfold_labeling(p.surface, p.labels);
  EXPECT_TRUE(test::validate_labeling(p.surface, un.labels).valid()) << GetParam();
  const auto after = construct::estimate_polycube(p.surface, un.labels);
  EXPECT_LE(after.flipped_area, before.flipped_area) << GetParam();
  EXPECT_EQ(un.folded_before, static_cast<int>(before.flipped.size()));
  EXPECT_EQ(un.folded_after, static_cast<int>(after.flipped.size()));
  if (un.moves == 0) {
    EXPECT_EQ(un.labels, p.labels);
  }
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
