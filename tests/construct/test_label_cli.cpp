// End-to-end tests of `polycube label`: outputs, exit codes, refusals with reasons.
#include "core/types.h"
#include "io/mesh_io.h"

#include "support/shapes.h"
#include "construct/validator.h"

#include "cli/surface_file.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polycube {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string err;
};

fs::path temp_dir(const std::string& name) { return test::scratch_dir("polycube_label_test_" + name); }

CliRun run_label(const fs::path& input, const fs::path& out) {
  const fs::path err = out.parent_path() / (out.filename().string() + ".stderr");
  const std::string cmd = std::string("\"") + POLYCUBE_CLI + "\" label \"" + input.string() + "\" -o \"" +
                          out.string() + "\" > /dev/null 2> \"" + err.string() + "\"";
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  return r;
}

using test::write_surface;

TEST(LabelCli, CubeWritesConsistentOutputs) {
  const fs::path dir = temp_dir("cube");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 3));
  const CliRun r = run_label(dir / "box.obj", dir / "out");
  ASSERT_EQ(r.code, 0) << r.err;
  const core::MeshData mesh = io::read_mesh(dir / "out/tets.mesh");
  EXPECT_FALSE(mesh.tets.empty());
  std::ifstream lf(dir / "out/labeling.txt");
  std::vector<int> labels;
  for (int l; lf >> l;) labels.push_back(l);
  ASSERT_EQ(labels.size(), mesh.triangles.size());
  core::TriMesh bnd;
  bnd.points = mesh.points;
  bnd.cells = mesh.triangles;
  EXPECT_TRUE(test::validate_labeling(bnd, labels).valid());
  std::ifstream jf(dir / "out/report.json");
  const auto j = nlohmann::json::parse(jf);
  EXPECT_EQ(j["valid"], true);
  // The graph cut before the repair: a box's cut needs no move, so it is the labeling itself.
  std::ifstream cf(dir / "out/labeling_cut.txt");
  std::vector<int> cut;
  for (int l; cf >> l;) cut.push_back(l);
  EXPECT_EQ(j["repair_moves"], 0);
  EXPECT_EQ(cut, labels);
  EXPECT_EQ(j["outputs"]["labeling_cut"], (dir / "out/labeling_cut.txt").string());
  EXPECT_EQ(j["charts"], 6);
  EXPECT_EQ(j["corners"], 8);
  EXPECT_EQ(j["boundaries"], 12);
  EXPECT_NEAR(j["fidelity"].get<double>(), 0.0, 1e-9);
  EXPECT_EQ(j["tets"].get<std::size_t>(), mesh.tets.size());
}

TEST(LabelCli, OpenSurfaceExitsTwoWithReason) {
  const fs::path dir = temp_dir("open");
  auto m = test::make_box(1.0, 1.0, 1.0, 2);
  m.cells.pop_back();
  write_surface(dir / "open.obj", m);
  const CliRun r = run_label(dir / "open.obj", dir / "out");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("open"), std::string::npos) << r.err;
}

TEST(LabelCli, NonManifoldSurfaceExitsTwoWithReason) {
  const fs::path dir = temp_dir("nonmanifold");
  auto m = test::make_box(1.0, 1.0, 1.0, 1);
  const int a = m.cells[0][0], b = m.cells[0][1], c = m.num_points();
  m.points.push_back((m.points[a] + m.points[b]) / 2 + core::Vec3(2, 2, 2));
  m.cells.push_back({a, b, c});
  m.cells.push_back({b, a, c});
  write_surface(dir / "fin.obj", m);
  const CliRun r = run_label(dir / "fin.obj", dir / "out");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("manifold"), std::string::npos) << r.err;
}

TEST(LabelCli, SelfIntersectingSurfaceExitsTwoWithReason) {
  const fs::path dir = temp_dir("selfint");
  auto a = test::make_box(1.0, 1.0, 1.0, 1);
  const auto b = test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(0.5, 0.4, 0.3));
  const int off = a.num_points();
  for (const auto& p : b.points) a.points.push_back(p);
  for (const auto& t : b.cells) a.cells.push_back({t[0] + off, t[1] + off, t[2] + off});
  write_surface(dir / "two.obj", a);
  const CliRun r = run_label(dir / "two.obj", dir / "out");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("self-intersect"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace polycube
