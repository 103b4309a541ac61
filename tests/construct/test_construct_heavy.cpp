// Whole construction on the large shapes of ../shared/data (label "heavy", not in `make test`:
// about 12 minutes on 2 cores; `make test-heavy` runs them). Each map is accepted by the independent
// certifier and its simplification is certified (construct/model_checks.h).
#include "construct/model_checks.h"

#include <gtest/gtest.h>

namespace polycube {
namespace {

using test::construct_file;
using test::kData;

TEST(ConstructHeavy, TetCup) { construct_file(kData / "tet/cup.mesh"); }
TEST(ConstructHeavy, Bunny) { construct_file(kData / "surface/bunny.obj"); }
TEST(ConstructHeavy, RockerArm) { construct_file(kData / "surface/rocker-arm.obj"); }
TEST(ConstructHeavy, Moai) { construct_file(kData / "surface/moai.obj"); }
TEST(ConstructHeavy, MaxPlanck) { construct_file(kData / "surface/max-planck.obj"); }

}  // namespace
}  // namespace polycube
