// The choice between a padded mesh and the unpadded one (padding::why_not_kept; `run` applies it).
#include "padding/padding.h"

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
  const auto why = [](const padding::PadResult& p, double unpadded) {
    return padding::why_not_kept(p, unpadded, 0.009, 0.5);
  };
  EXPECT_EQ(why(padded(0.28, 0.31, 0.0088), 0.0087), "");
  // Lower, but usable: kept.
  EXPECT_EQ(why(padded(0.8, 0.6, 0.004), 0.004), "");
  // Lower and not usable: not kept.
  EXPECT_NE(why(padded(0.28, 0.25, 0.004), 0.004).find("mSJ"), std::string::npos);
}

// The surface is a constraint: a padded mesh that leaves the bound the unpadded one met is not
// kept, whatever it gains in mSJ; where the unpadded mesh was beyond the bound already, the
// padded one may not be farther.
TEST(PaddingKept, NotWhenItsBoundaryLeavesTheDistanceBound) {
  const auto why = [](const padding::PadResult& p, double unpadded) {
    return padding::why_not_kept(p, unpadded, 0.009, 0.5);
  };
  const std::string far = why(padded(0.28, 0.30, 0.0095), 0.0088);
  EXPECT_NE(far.find("0.950 %"), std::string::npos) << far;
  EXPECT_NE(far.find("0.880 %"), std::string::npos) << far;
  EXPECT_EQ(why(padded(0.28, 0.30, 0.0110), 0.0120), "");
  EXPECT_NE(why(padded(0.28, 0.30, 0.0125), 0.0120), "");
}

}  // namespace
}  // namespace polycube
