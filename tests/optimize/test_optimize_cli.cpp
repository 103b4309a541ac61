// `polycube optimize`: a normal run, bad input, and a result that cannot pass the check.
#include "cli/run_cli.h"
#include "io/mesh_io.h"
#include "optimize_fixtures.h"
#include "quality/scaled_jacobian.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace polycube {
namespace {

namespace fs = std::filesystem;

struct OptimizeCli : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::path(::testing::TempDir()) /
          ("pc_optimize_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
    core::HexMesh m = test::box_grid(4, 4, 4);
    test::perturb(m, 0.04, 3, [](const core::Vec3&) { return true; });
    io::write_mesh(dir / "hex.mesh", core::to_mesh_data(m));
    io::write_mesh(dir / "box.obj", core::to_mesh_data(test::box_surface()));
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string p(const std::string& name) const { return "'" + (dir / name).string() + "'"; }
};

TEST_F(OptimizeCli, NormalRunWritesMeshAndReport) {
  const auto r = test::run_cli("optimize " + p("hex.mesh") + " --target " + p("box.obj") + " -o " + p("out.vtk") +
                               " --report " + p("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mSJ"), std::string::npos);
  EXPECT_NE(r.out.find("Hausdorff"), std::string::npos);
  const core::HexMesh out = core::hexes_of(io::read_mesh(dir / "out.vtk"));
  EXPECT_EQ(out.num_cells(), 64);
  EXPECT_TRUE(quality::scaled_jacobian(out).all_positive());
  std::ifstream f(dir / "report.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_TRUE(j["check"]["ok"].get<bool>());
  EXPECT_GE(j["after"]["min"].get<double>(), j["before"]["min"].get<double>());
  EXPECT_LT(j["hausdorff"]["relative"].get<double>(), 0.009);
  EXPECT_TRUE(j.contains("untangle") && j.contains("quality"));
}

TEST_F(OptimizeCli, BadInputIsOneLineExitTwoAndNoOutput) {
  {
    const auto r = test::run_cli("optimize " + p("box.obj") + " --target " + p("box.obj") + " -o " + p("out.mesh"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  {
    const auto r = test::run_cli("optimize " + p("hex.mesh") + " --target " + p("missing.obj") + " -o " + p("out.mesh"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
  {
    std::ofstream(dir / "garbage.mesh") << "MeshVersionFormatted 1\nDimension 3\nVertices\n2\n0 0\n";
    const auto r = test::run_cli("optimize " + p("garbage.mesh") + " --target " + p("box.obj") + " -o " + p("out.mesh"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
  {
    const auto r = test::run_cli("optimize " + p("hex.mesh") + " --target " + p("box.obj") + " -o " + p("out.obj"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "out.mesh"));
  EXPECT_FALSE(fs::exists(dir / "out.obj"));
}

// A target that is not the mesh's shape (here: the right box, moved away) is refused before any
// work, naming the distance, by optimize and by pad; --max-start-distance lets it through.
TEST_F(OptimizeCli, TargetFarFromTheMeshIsRefusedBeforeAnyWork) {
  core::TriMesh far = test::box_surface();
  for (core::Vec3& v : far.points) v += core::Vec3(100.0, 0.0, 0.0);
  io::write_mesh(dir / "far.obj", core::to_mesh_data(far));
  for (const char* command : {"optimize", "pad"}) {
    SCOPED_TRACE(command);
    const auto r = test::run_cli(std::string(command) + " " + p("hex.mesh") + " --target " + p("far.obj") + " -o " +
                                 p("out.mesh"));
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("% of the target's diagonal away from"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--max-start-distance"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out.mesh"));
  }
  const auto allowed = test::run_cli("optimize " + p("hex.mesh") + " --target " + p("far.obj") + " -o " + p("out.mesh") +
                                     " --max-start-distance 1000 --quality-rounds 0");
  EXPECT_EQ(allowed.err.find("away from"), std::string::npos) << allowed.err;
}

TEST_F(OptimizeCli, UnrepairableResultExitsThreeWithoutOutput) {
  // A bar folded over itself stays folded when the optimizer is given no iterations. (Its
  // folded top is 41 % of the diagonal off the box: the start distance is allowed.)
  core::HexMesh m = test::box_grid(2, 2, 2);
  for (auto& q : m.points)
    if (q.z() == 1.0) q.z() = -0.5;  // the top layer pushed through the bottom: inverted hexes
  io::write_mesh(dir / "folded.mesh", core::to_mesh_data(m));
  const auto r = test::run_cli("optimize " + p("folded.mesh") + " --target " + p("box.obj") + " -o " +
                               p("out.mesh") + " --untangle-iterations 0 --quality-rounds 0 --max-start-distance 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("fold-over"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.mesh"));
  const auto k = test::run_cli("optimize " + p("folded.mesh") + " --target " + p("box.obj") + " -o " +
                               p("out.mesh") + " --untangle-iterations 0 --quality-rounds 0 --keep-failed --max-start-distance 1");
  EXPECT_EQ(k.exit_code, 3);
  EXPECT_TRUE(fs::exists(dir / "out.mesh"));
}

}  // namespace
}  // namespace polycube
