// `polycube pad`: global padding and a facet file, the report, the VTK fields, bad input.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "quality/scaled_jacobian.h"
#include "support/fixtures.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace polycube {
namespace {

namespace fs = std::filesystem;

struct PadCli : ::testing::Test {
  fs::path dir;
  void SetUp() override {
    dir = fs::path(::testing::TempDir()) /
          ("pc_pad_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(dir);
    io::write_mesh(dir / "hex.mesh", core::to_mesh_data(test::hex_grid(4, 4, 4, 0.5)));
    io::write_mesh(dir / "cube.obj", core::to_mesh_data(test::make_box(2, 2, 2, 2)));
  }
  void TearDown() override { fs::remove_all(dir); }
  std::string p(const std::string& name) const {
    std::string quoted(1, '\'');
    quoted += (dir / name).string();
    quoted += '\'';
    return quoted;
  }
  nlohmann::json report() const {
    std::ifstream f(dir / "report.json");
    return nlohmann::json::parse(f);
  }
};

TEST_F(PadCli, GlobalPaddingWritesTheMeshTheLayerAndTheReport) {
  const auto r = test::run_cli("pad " + p("hex.mesh") + " --target " + p("cube.obj") + " -o " + p("out.mesh") +
                               " --vtk " + p("out.vtk") + " --report " + p("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("#Sv"), std::string::npos) << r.out;
  const core::HexMesh out = core::hexes_of(io::read_mesh(dir / "out.mesh"));
  EXPECT_EQ(out.num_cells(), 64 + 96);  // one hex per boundary facet (6 x 16)
  EXPECT_TRUE(quality::scaled_jacobian(out).all_positive());
  const core::MeshData vtk = io::read_mesh(dir / "out.vtk");
  const auto layer = std::find_if(vtk.cell_data.begin(), vtk.cell_data.end(),
                                  [](const core::Field& f) { return f.name == "padding_layer"; });
  ASSERT_NE(layer, vtk.cell_data.end());
  EXPECT_EQ(std::count(layer->values.begin(), layer->values.end(), 1.0), 96);
  const nlohmann::json j = report();
  EXPECT_EQ(j["added_hexes"], 96);
  EXPECT_EQ(j["before"]["hexes"], 64);
  EXPECT_EQ(j["after"]["hexes"], 160);
  EXPECT_EQ(j["before"]["singular_vertices"], 8);
  EXPECT_EQ(j["after"]["singular_vertices"], 16);
  EXPECT_EQ(j["before"]["singular_edges"], 48);
  EXPECT_EQ(j["after"]["singular_edges"], 56);  // 48 interior of valence 3, 8 pillars
  EXPECT_EQ(j["before"]["multi_boundary_hexes"], 8 + 12 * 2);  // corners, then the edges' middles
  EXPECT_EQ(j["after"]["multi_boundary_hexes"], 0);
  EXPECT_TRUE(j["check"]["ok"].get<bool>());
  EXPECT_LT(j["hausdorff"]["relative"].get<double>(), 0.009);
  EXPECT_GE(j["seconds"]["insertion"].get<double>(), 0.0);
}

TEST_F(PadCli, AFacetFileSelectsTheFacets) {
  // All 16 facets of the plane x = 1: a sheet across the grid.
  const core::HexMesh grid = test::hex_grid(4, 4, 4, 0.5);
  const auto faces = core::unique_faces(grid);
  std::ofstream f(dir / "facets.txt");
  f << "# the plane x = 1\n\n";
  int written = 0;
  for (const auto& q : faces.faces)
    if (std::all_of(q.begin(), q.end(), [&](int v) { return grid.points[v].x() == 1.0; })) {
      f << q[0] << " " << q[1] << " " << q[2] << " " << q[3] << "\n";
      ++written;
    }
  f.close();
  ASSERT_EQ(written, 16);
  const auto r = test::run_cli("pad " + p("hex.mesh") + " --target " + p("cube.obj") + " -o " + p("out.vtk") +
                               " --facets " + p("facets.txt") + " --report " + p("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = report();
  EXPECT_EQ(j["added_hexes"], 16);
  EXPECT_EQ(j["after"]["singular_vertices"], 8);  // a 5 x 4 x 4 grid
  EXPECT_EQ(j["after"]["singular_edges"], 52);
}

TEST_F(PadCli, AnInvalidFacetSetIsOneLineExitTwoAndNoOutput) {
  const core::HexMesh grid = test::hex_grid(4, 4, 4, 0.5);
  const auto faces = core::unique_faces(grid);
  std::ofstream f(dir / "facets.txt");
  for (int k = 0; k < faces.num_faces(); ++k)
    if (!faces.is_boundary(k)) {
      const auto& q = faces.faces[k];
      f << q[3] << " " << q[2] << " " << q[1] << " " << q[0] << "\n";
      break;
    }
  f.close();
  const auto r = test::run_cli("pad " + p("hex.mesh") + " --target " + p("cube.obj") + " -o " + p("out.mesh") +
                               " --facets " + p("facets.txt"));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("invalid padding facet set"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out.mesh"));
  for (const char* bad : {"1 2 3", "a b c d", "0 1 2 3"}) {
    std::ofstream g(dir / "bad.txt");
    g << bad << "\n";
    g.close();
    const auto rb = test::run_cli("pad " + p("hex.mesh") + " --target " + p("cube.obj") + " -o " + p("out.mesh") +
                                  " --facets " + p("bad.txt"));
    EXPECT_EQ(rb.exit_code, 2) << bad << ": " << rb.err;
    EXPECT_EQ(std::count(rb.err.begin(), rb.err.end(), '\n'), 1) << rb.err;
  }
  const auto rt = test::run_cli("pad " + p("cube.obj") + " --target " + p("cube.obj") + " -o " + p("out.mesh"));
  EXPECT_EQ(rt.exit_code, 2) << rt.err;
  EXPECT_FALSE(fs::exists(dir / "out.mesh"));
}

TEST_F(PadCli, SelectivePaddingPadsWhereTheMeshIsDistortedAndNothingElsewhere) {
  {
    const auto r = test::run_cli("pad " + p("hex.mesh") + " --target " + p("cube.obj") + " -o " + p("none.mesh") +
                                 " --selective --report " + p("report.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("nothing to pad"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "none.mesh"));
    EXPECT_EQ(report()["added_hexes"], 0);
  }
  // A chamfered edge (its facets meet at 180°): HF along it, PF completes it; the target is the
  // chamfered mesh's own boundary.
  core::HexMesh m = test::hex_grid(4, 4, 4, 0.5);
  for (core::Vec3& q : m.points)
    if (q.y() == 0.0 && q.z() == 2.0) q = core::Vec3(q.x(), 0.25, 1.75);
  io::write_mesh(dir / "chamfer.mesh", core::to_mesh_data(m));
  const auto r = test::run_cli("pad " + p("chamfer.mesh") + " --target " + p("chamfer.mesh") + " -o " + p("out.vtk") +
                               " --selective --plan-vtk " + p("plan.vtk") + " --report " + p("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = report();
  EXPECT_GE(j["analysis"]["hard_facets"].get<int>(), 8);  // the 8 facets along the chamfer at least
  EXPECT_TRUE(j["selection"]["optimal"].get<bool>());
  EXPECT_EQ(j["added_hexes"], j["selection"]["selected_facets"]);
  EXPECT_LT(j["added_hexes"].get<int>(), 96);  // fewer than global padding
  EXPECT_TRUE(j["check"]["ok"].get<bool>());
  const core::MeshData plan = io::read_mesh(dir / "plan.vtk");
  std::vector<std::string> names;
  for (const auto& f : plan.cell_data) names.push_back(f.name);
  EXPECT_EQ(names, (std::vector<std::string>{"distortion", "propagated", "hard", "padded"}));
  EXPECT_TRUE(quality::scaled_jacobian(core::hexes_of(io::read_mesh(dir / "out.vtk"))).all_positive());
}

}  // namespace
}  // namespace polycube
