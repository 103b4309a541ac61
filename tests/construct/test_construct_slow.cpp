// Heavier shared models (labelled "slow": run with ctest -L slow).
#include "construct/pipeline.h"

#include <gtest/gtest.h>

namespace polycube {
namespace {

const std::filesystem::path kData = POLYCUBE_DATA_DIR;
using test::run_model;

TEST(ModelsSlow, Bunny) { run_model(kData / "surface/bunny.obj"); }
TEST(ModelsSlow, RockerArm) { run_model(kData / "surface/rocker-arm.obj"); }
TEST(ModelsSlow, Moai) { run_model(kData / "surface/moai.obj"); }
TEST(ModelsSlow, MaxPlanck) { run_model(kData / "surface/max-planck.obj"); }
TEST(ModelsSlow, B0Surface) { run_model(kData / "surface/B0.obj"); }
TEST(ModelsSlow, TetS3) { run_model(kData / "tet/S3.mesh"); }

}  // namespace
}  // namespace polycube
