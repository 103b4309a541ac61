// run's choice between the padded and the unpadded mesh (pipeline/stage_steps.h).
#include "pipeline/stage_steps.h"

#include <gtest/gtest.h>

namespace polycube {
namespace {

padding::PadResult padded(double msj_before, double msj_after, double distance) {
  padding::PadResult p;
  p.before.scaled_jacobian.min = msj_before;
  p.after.scaled_jacobian.min = msj_after;
  p.distance.relative = distance;
  return p;
}

TEST(PaddingKept, WhenItRaisesTheMinimumAndStaysNearTheSurface) {
  pipeline::RunOptions o;
  o.optimize_options.hausdorff_bound = 0.009;
  o.padding_usable_min_sj = 0.5;
  EXPECT_EQ(pipeline::padding_does_not_pay(padded(0.28, 0.31, 0.0088), 0.0087, o), "");
  // Lower, but usable: kept.
  EXPECT_EQ(pipeline::padding_does_not_pay(padded(0.8, 0.6, 0.004), 0.004, o), "");
  // Lower and not usable: not kept.
  EXPECT_NE(pipeline::padding_does_not_pay(padded(0.28, 0.25, 0.004), 0.004, o).find("mSJ"), std::string::npos);
}

// The surface is a constraint: a padded mesh that leaves the bound the unpadded one met is not
// kept, whatever it gains in mSJ; where the unpadded mesh was beyond the bound already, the
// padded one may not be farther.
TEST(PaddingKept, NotWhenItsBoundaryLeavesTheDistanceBound) {
  pipeline::RunOptions o;
  o.optimize_options.hausdorff_bound = 0.009;
  const std::string why = pipeline::padding_does_not_pay(padded(0.28, 0.30, 0.0095), 0.0088, o);
  EXPECT_NE(why.find("0.950 %"), std::string::npos) << why;
  EXPECT_NE(why.find("0.880 %"), std::string::npos) << why;
  EXPECT_EQ(pipeline::padding_does_not_pay(padded(0.28, 0.30, 0.0110), 0.0120, o), "");
  EXPECT_NE(pipeline::padding_does_not_pay(padded(0.28, 0.30, 0.0125), 0.0120, o), "");
}

}  // namespace
}  // namespace polycube
