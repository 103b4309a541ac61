// End-to-end tests of `polycube run`: every stage's output re-readable and consistent with the
// report, exit codes, refusal of bad input before any heavy work, determinism.
#include "core/types.h"
#include "io/mesh_io.h"
#include "quality/domains.h"
#include "quality/scaled_jacobian.h"

#include "cli/run_cli.h"
#include "construct/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polycube {
namespace {

namespace fs = std::filesystem;

using test::CliResult;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

fs::path temp_dir(const std::string& name) {
  // One folder per process: ctest runs each test case as its own process, possibly in parallel.
  const fs::path d = fs::temp_directory_path() / ("polycube_run_test_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

CliResult run(const std::string& args) { return test::run_cli("run " + args); }

void write_surface(const fs::path& p, const core::TriMesh& m) {
  core::MeshData d;
  d.points = m.points;
  d.triangles = m.cells;
  io::write_mesh(p, d);
}

class RunBox : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = temp_dir("box");
    write_surface(dir_ / "box.obj", test::make_box(1.0, 2.0, 1.5, 4));
    result_ = run("\"" + (dir_ / "box.obj").string() + "\" -o \"" + (dir_ / "out").string() + "\" --hexes 3000");
  }
  static fs::path dir_;
  static CliResult result_;
};
fs::path RunBox::dir_;
CliResult RunBox::result_;

TEST_F(RunBox, EveryStageSucceedsAndTheSummaryNamesThem) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  for (const char* stage : {"construct", "simplify", "hexmesh", "optimize", "quality", "total"})
    EXPECT_NE(result_.out.find(std::string("| ") + stage + " |"), std::string::npos) << result_.out;
}

TEST_F(RunBox, OutputsAreReReadableAndMatchTheReport) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = nlohmann::json::parse(slurp(out / "report.json"));
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["charts"], 6);
  EXPECT_EQ(j["corners"], 8);
  for (const char* f : {"construct/model.mesh", "construct/polycube.mesh", "simplify/model.mesh",
                        "simplify/polycube.mesh", "hex.mesh", "hex_optimized.mesh", "hex_quality.vtk", "quad.vtk"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  EXPECT_EQ(static_cast<int>(hex.cells.size()), j["hexes"].get<int>());
  // The target was 3000 hexes; the simplified box is scaled by an integer, so within a factor 2.
  EXPECT_GT(hex.cells.size(), 1500u);
  EXPECT_LT(hex.cells.size(), 6000u);
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(hex);
  EXPECT_EQ(sj.inverted, 0);
  EXPECT_EQ(sj.invalid, 0);
  EXPECT_GT(sj.min, 0.0);
  EXPECT_NEAR(sj.min, j["final"]["msj"].get<double>(), 1e-12);
  // A box is one block, before and after simplification, and in the final mesh.
  EXPECT_EQ(j["hex_domains_after"], 1);
  EXPECT_EQ(quality::hex_domains(hex).domains, 1);
  EXPECT_EQ(j["final"]["domains"], 1);
  EXPECT_LE(j["final"]["hausdorff_relative"].get<double>(), 0.009);
  const core::MeshData vtk = io::read_mesh(out / "hex_quality.vtk");
  EXPECT_EQ(vtk.hexes.size(), hex.cells.size());
}

TEST_F(RunBox, SameInputSameOutput) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path again = dir_ / "again";
  fs::create_directories(again);
  const CliResult r = run("\"" + (dir_ / "box.obj").string() + "\" -o \"" + (again / "out").string() + "\" --hexes 3000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "out" / "hex_optimized.mesh"), slurp(again / "out" / "hex_optimized.mesh"));
  EXPECT_EQ(slurp(dir_ / "out" / "simplify" / "polycube.mesh"), slurp(again / "out" / "simplify" / "polycube.mesh"));
}

TEST(RunCli, OpenSurfaceStopsWithExitTwoBeforeAnyHeavyWork) {
  const fs::path dir = temp_dir("open");
  auto m = test::make_box(1.0, 1.0, 1.0, 2);
  m.cells.pop_back();
  write_surface(dir / "open.obj", m);
  const CliResult r = run("\"" + (dir / "open.obj").string() + "\" -o \"" + (dir / "out").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("stage input failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "construct"));
  EXPECT_FALSE(fs::exists(dir / "out" / "hex.mesh"));
  const auto j = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["failure"]["stage"], "input");
}

TEST(RunCli, NonManifoldSurfaceStopsWithExitTwo) {
  const fs::path dir = temp_dir("nonmanifold");
  auto m = test::make_box(1.0, 1.0, 1.0, 1);
  const int a = m.cells[0][0], b = m.cells[0][1], c = m.num_points();
  m.points.push_back((m.points[a] + m.points[b]) / 2 + core::Vec3(2, 2, 2));
  m.cells.push_back({a, b, c});
  m.cells.push_back({b, a, c});
  write_surface(dir / "fin.obj", m);
  const CliResult r = run("\"" + (dir / "fin.obj").string() + "\" -o \"" + (dir / "out").string() + "\"");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("manifold"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "construct"));
}

TEST(RunCli, AFailingStageIsNamedAndEarlierResultsAreKept) {
  // A lattice bound far too small for the requested hexes makes the gridding refuse: the
  // construction and simplification results must stay, the stage must be named.
  const fs::path dir = temp_dir("fail");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run("\"" + (dir / "box.obj").string() + "\" -o \"" + (dir / "out").string() +
                           "\" --no-simplify --hexes 2000000000");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("stage hexmesh failed"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "construct" / "polycube.mesh"));
  EXPECT_FALSE(fs::exists(dir / "out" / "hex.mesh"));
}

}  // namespace
}  // namespace polycube
