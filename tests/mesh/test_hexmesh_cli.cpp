// `polycube hexmesh` / `polycube quadmesh` end to end: files written and read back, the snapping
// refusal (exit 3), determinism, and outside readers (`polycube quality`, VTK 9 when present).
#include "core/topology.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "structure/analytic_maps.h"
#include "structure/cli_runner.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <fstream>

namespace polycube::test {
namespace {

namespace fs = std::filesystem;

struct Files {
  fs::path dir;
  std::string args;  // "'model' 'polycube'"
};

Files write_map(const std::string& name, const core::PolycubeMap& m) {
  Files f;
  f.dir = temp_folder(name);
  io::write_polycube_map(f.dir / "model.mesh", f.dir / "polycube.mesh", m);
  f.args = quoted(f.dir / "model.mesh");
  f.args += ' ';
  f.args += quoted(f.dir / "polycube.mesh");
  return f;
}

std::string q(const fs::path& p) { return quoted(p); }

TEST(HexmeshCli, WritesHexMeshAndTwin) {
  const Files f = write_map("hexmesh", l_shape(2).map);
  const Cli r = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.mesh") +
                             " --scale 4 --polycube-out " + q(f.dir / "hexpc.mesh") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["hexes"], 192);
  EXPECT_EQ(j["quads"], 224);
  EXPECT_EQ(j["points_failed"], 0);
  EXPECT_EQ(j["snapping"]["defects"].size(), 0u);
  const core::MeshData hex = io::read_mesh(f.dir / "hex.mesh");
  const core::MeshData twin = io::read_mesh(f.dir / "hexpc.mesh");
  ASSERT_EQ(hex.hexes.size(), 192u);
  EXPECT_EQ(twin.hexes, hex.hexes);
  for (std::size_t v = 0; v < hex.points.size(); ++v) {
    for (int a = 0; a < 3; ++a) EXPECT_EQ(twin.points[v][a], std::round(twin.points[v][a]));
    EXPECT_LT((hex.points[v] - twin.points[v] / 4.0).norm(), 1e-9);  // identity map
  }
  EXPECT_EQ(core::analyze_volume(core::hexes_of(hex)).inverted_cells, 0);
  fs::remove_all(f.dir);
}

TEST(HexmeshCli, TextSummaryAndTargetCount) {
  const Files f = write_map("hexmesh_text", l_shape(1).map);
  const Cli r = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.vtk") + " --hexes 3000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("hexes "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("points located"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("time: locate"), std::string::npos) << r.out;
  const core::MeshData hex = io::read_mesh(f.dir / "hex.vtk");
  EXPECT_NEAR(static_cast<double>(hex.hexes.size()), 3000.0, 750.0);
  // --scale and --hexes exclude each other: usage error
  EXPECT_EQ(
      run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "x.mesh") + " --scale 2 --hexes 10")
          .exit_code,
      1);
  fs::remove_all(f.dir);
}

// --refine-near takes model-space points: on the identity L at scale 4, the point (0.5, 0.25,
// 0.5) doubles the cells of its x, y and z unit intervals (Grid.RefineNear... counts the same
// 1,024 hexes); a malformed point is refused with a message naming the option, and nothing is
// written.
TEST(HexmeshCli, RefineNearDoublesTheCellsAroundAModelPoint) {
  const Files f = write_map("hexmesh_refine", l_shape(2).map);
  const Cli r = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.mesh") +
                             " --scale 4 --refine-near 0.5,0.25,0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["hexes"], 8 * 8 * 8 + 4 * 8 * 8 + 8 * 4 * 8);
  EXPECT_EQ(core::analyze_volume(core::hexes_of(io::read_mesh(f.dir / "hex.mesh"))).inverted_cells, 0);
  const Cli bad = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "bad.mesh") + " --scale 4 --refine-near 0.5,0.25");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_NE(bad.err.find("--refine-near: '0.5,0.25' is not a point x,y,z"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(f.dir / "bad.mesh"));
  fs::remove_all(f.dir);
}

TEST(QuadmeshCli, WritesClosedQuadSurface) {
  const Files f = write_map("quadmesh", l_shape(2).map);
  const Cli r =
      run_polycube("quadmesh " + f.args + " -o " + q(f.dir / "quad.obj") + " --scale 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const core::MeshData d = io::read_mesh(f.dir / "quad.obj");
  EXPECT_EQ(d.quads.size(), static_cast<std::size_t>(kLArea * 9));
  const core::SurfaceReport rep = core::analyze_surface(core::quads_of(d));
  EXPECT_TRUE(rep.closed);
  EXPECT_TRUE(rep.manifold);
  EXPECT_EQ(rep.genus, 0);
  fs::remove_all(f.dir);
}

TEST(HexmeshCli, NaiveSnappingDefectsAreRefused) {
  // [0,2]x[0,1]x[0,1] with a 0.3 high step on its left half: at scale 1, z = 1 and z = 1.3 merge
  const GridMap g = make_grid_map(
      uniform(0, 2, 4), uniform(0, 1, 2), {0, 0.5, 1, 1.3},
      [](const Vec3& c) { return c.z() < 1 || c.x() < 1; }, [](const Vec3& p) { return p; });
  const Files f = write_map("hexmesh_snap", g.map);
  const Cli r = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.mesh") + " --scale 1");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("corners merged: corners"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--allow-defects"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(f.dir / "hex.mesh"));
  const Cli a = run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.mesh") +
                             " --scale 1 --allow-defects --json");
  EXPECT_EQ(a.exit_code, 0) << a.err;
  EXPECT_TRUE(fs::exists(f.dir / "hex.mesh"));
  const auto j = nlohmann::json::parse(a.out);
  bool merged = false;
  for (const auto& d : j["snapping"]["defects"]) merged = merged || d["kind"] == "corners merged";
  EXPECT_TRUE(merged);
  // at scale 10 the same map grids cleanly
  EXPECT_EQ(run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex10.mesh") + " --scale 10")
                .exit_code,
            0);
  fs::remove_all(f.dir);
}

TEST(HexmeshCli, Deterministic) {
  const GridMap g = l_shape(
      2, [](const Vec3& p) { return Vec3(p.x() + 0.2 * std::sin(p.z() * 3), p.y(), p.z()); });
  const Files f = write_map("hexmesh_det", g.map);
  for (const char* name : {"a.mesh", "b.mesh"})
    ASSERT_EQ(
        run_polycube("hexmesh " + f.args + " -o " + q(f.dir / name) + " --scale 3.3").exit_code, 0);
  EXPECT_EQ(read_file(f.dir / "a.mesh"), read_file(f.dir / "b.mesh"));
  fs::remove_all(f.dir);
}

TEST(HexmeshCli, QualityReadsTheMeshBack) {
  const Files f = write_map("hexmesh_quality", l_shape(2).map);
  ASSERT_EQ(
      run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.mesh") + " --scale 2").exit_code,
      0);
  const Cli r = run_polycube("quality " + q(f.dir / "hex.mesh") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["cells"], 24);
  EXPECT_NEAR(j["scaled_jacobian"]["min"].get<double>(), 1.0, 1e-9);  // unit cubes
  EXPECT_EQ(j["scaled_jacobian"]["inverted"], 0);
  EXPECT_EQ(j["domains"], 3);  // the L splits into three blocks at its concave edge
  fs::remove_all(f.dir);
}

TEST(HexmeshCli, Vtk9ReadsTheVtkFiles) {
  // VTK 9.1 (ParaView's reader) when python3-vtk9 is installed
  if (std::system("/usr/bin/python3 -c 'import vtkmodules.vtkIOLegacy' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3-vtk9 not installed";
  const Files f = write_map("hexmesh_vtk", l_shape(2).map);
  ASSERT_EQ(
      run_polycube("hexmesh " + f.args + " -o " + q(f.dir / "hex.vtk") + " --scale 2").exit_code,
      0);
  ASSERT_EQ(run_polycube("structure " + f.args + " -o " + q(f.dir / "s.vtk")).exit_code, 0);
  const fs::path script = f.dir / "check.py";
  {
    std::ofstream py(script);
    py << "import sys\n"
          "from vtkmodules.vtkIOLegacy import vtkUnstructuredGridReader\n"
          "from vtkmodules.vtkFiltersVerdict import vtkMeshQuality\n"
          "def read(p):\n"
          "    r = vtkUnstructuredGridReader(); r.SetFileName(p); r.Update()\n"
          "    if r.GetErrorCode() != 0: sys.exit(2)\n"
          "    return r.GetOutput()\n"
          "g = read(sys.argv[1])\n"
          "q = vtkMeshQuality(); q.SetInputData(g); q.SetHexQualityMeasureToScaledJacobian(); "
          "q.Update()\n"
          "a = q.GetOutput().GetCellData().GetArray('Quality')\n"
          "lo = min(a.GetValue(i) for i in range(a.GetNumberOfTuples()))\n"
          "s = read(sys.argv[2])\n"
          "print(g.GetNumberOfCells(), lo, s.GetNumberOfCells(), "
          "s.GetCellData().GetNumberOfArrays())\n";
  }
  const std::string out_file = (f.dir / "vtk_out.txt").string();
  ASSERT_EQ(std::system(("/usr/bin/python3 " + q(script) + " " + q(f.dir / "hex.vtk") + " " +
                         q(f.dir / "s.vtk") + " > " + q(out_file) + " 2>&1")
                            .c_str()),
            0)
      << read_file(out_file);
  std::istringstream in(read_file(out_file));
  int hexes = 0, cells = 0, arrays = 0;
  double min_sj = 0;
  in >> hexes >> min_sj >> cells >> arrays;
  EXPECT_EQ(hexes, 24);
  EXPECT_NEAR(min_sj, 1.0, 1e-9);
  EXPECT_GT(cells, 0);
  EXPECT_EQ(arrays, 5);
  fs::remove_all(f.dir);
}

}  // namespace
}  // namespace polycube::test
