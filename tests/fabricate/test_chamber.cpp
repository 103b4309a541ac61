// Fitting a chamber: a part stands on one of its flat sides, its height within the chamber's
// and its footprint within the bed after some turn.
#include "fabricate/chamber.h"

#include <gtest/gtest.h>

#include <cmath>

namespace polycube {
namespace {

using core::Vec3;

//! The 8 corners of an axis-aligned box of size (a, b, c), turned by `angle` about z.
std::vector<Vec3> box_points(double a, double b, double c, double angle = 0.0) {
  std::vector<Vec3> p;
  for (int k = 0; k < 8; ++k) {
    const double x = (k & 1) * a, y = ((k >> 1) & 1) * b, z = ((k >> 2) & 1) * c;
    p.emplace_back(x * std::cos(angle) - y * std::sin(angle),
                   x * std::sin(angle) + y * std::cos(angle), z);
  }
  return p;
}

TEST(Chamber, ABarFitsLyingDownButNotStandingOnItsEnd) {
  const auto bar = box_points(10, 2, 1);
  const fabricate::Chamber c{11, 3, 2};
  EXPECT_TRUE(fabricate::fits_standing_on(bar, -Vec3::UnitZ(), c));
  EXPECT_FALSE(fabricate::fits_standing_on(bar, -Vec3::UnitX(), c));  // 10 high
  EXPECT_TRUE(fabricate::fits_standing_on(bar, -Vec3::UnitY(), c));   // 2 high, 10 x 1 on the bed
  EXPECT_FALSE(fabricate::fits_standing_on(bar, -Vec3::UnitY(), {9, 3, 2}));  // 10 > 9
}

TEST(Chamber, AFootprintLongerThanTheBedFitsAlongItsDiagonal) {
  const auto bar = box_points(10, 1, 1, 0.3);  // turned: the fit must find the turn
  const fabricate::Chamber square{8, 8, 2};    // diagonal 11.3: (10 + 1) / sqrt 2 = 7.8 <= 8
  EXPECT_TRUE(fabricate::fits_standing_on(bar, -Vec3::UnitZ(), square));
  const fabricate::Chamber small{7, 7, 2};  // 7.8 > 7
  EXPECT_FALSE(fabricate::fits_standing_on(bar, -Vec3::UnitZ(), small));
}

TEST(Chamber, TheFirstFittingBaseIsChosenAndAnUnlimitedChamberTakesTheFirst) {
  const auto bar = box_points(10, 2, 1);
  const std::vector<Vec3> bases{-Vec3::UnitX(), -Vec3::UnitZ(), Vec3::UnitZ()};
  EXPECT_EQ(fabricate::fitting_base(bar, bases, {11, 3, 2}), 1);
  EXPECT_EQ(fabricate::fitting_base(bar, bases, {1, 1, 1}), -1);
  EXPECT_EQ(fabricate::fitting_base(bar, bases, {}), 0);
}

}  // namespace
}  // namespace polycube
