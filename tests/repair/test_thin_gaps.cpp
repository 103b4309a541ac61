// Gaps narrower than a width between sheets of a closed surface (repair/thin_gaps.h): counted
// exactly on two boxes facing each other across a slot, none across a wider one, none on the
// open side of a single box; on an L-shaped bracket none at the width run uses (its concave
// corners meet at right angles, and its bolt holes are wider), but its holes' walls face each
// other across a width larger than the holes.
#include "core/errors.h"
#include "repair/thin_gaps.h"
#include "samples/samples.h"
#include "support/shapes.h"

#include <gtest/gtest.h>

namespace polycube {
namespace {

// Two unit boxes, split into 4 × 4 squares per face, 0.05 apart along x: the 3 × 3 inner
// vertices of each facing side see the other side at 0.05 along their normal; the vertices on
// the sides' rims have normals tilted off the slot.
core::TriMesh two_boxes(double gap) {
  return test::join(test::make_box(1.0, 1.0, 1.0, 4),
                    test::make_box(1.0, 1.0, 1.0, 4, core::Vec3(1.0 + gap, 0.0, 0.0)));
}

TEST(ThinGaps, TwoBoxesAcrossASlotNarrowerThanTheWidthFaceEachOtherAtTheirInnerVertices) {
  const repair::ThinGaps g = repair::find_thin_gaps(two_boxes(0.05), 0.1);
  EXPECT_EQ(g.vertices, 2 * 9);
  EXPECT_NEAR(g.narrowest, 0.05, 1e-12);
  ASSERT_EQ(g.sites.size(), repair::RepairReport::kMaxSites);
  for (const core::Vec3& p : g.sites)
    EXPECT_TRUE(std::abs(p.x() - 1.0) < 1e-12 || std::abs(p.x() - 1.05) < 1e-12) << p.transpose();
}

TEST(ThinGaps, ASlotWiderThanTheWidthIsNotOne) {
  EXPECT_EQ(repair::find_thin_gaps(two_boxes(0.05), 0.04).vertices, 0);
  EXPECT_EQ(repair::find_thin_gaps(test::make_box(1.0, 1.0, 1.0, 4), 10.0).vertices, 0);
}

TEST(ThinGaps, ABracketHasNoneAtTheWrapsWidthButItsHolesAreNarrowerThanHalfItsDiagonal) {
  const core::TriMesh bracket = samples::make_sample("l-bracket");
  const double diagonal = core::bounding_box(bracket.points).diagonal();
  EXPECT_EQ(repair::find_thin_gaps(bracket, 0.02 * diagonal).vertices, 0);
  const repair::ThinGaps holes = repair::find_thin_gaps(bracket, 0.5 * diagonal);
  EXPECT_GT(holes.vertices, 0);
  EXPECT_GT(holes.narrowest, 0.02 * diagonal);
}

TEST(ThinGaps, AWidthThatIsNotPositiveIsRefused) {
  EXPECT_THROW(repair::find_thin_gaps(two_boxes(0.05), 0.0), core::InputError);
}

}  // namespace
}  // namespace polycube
