// Reports on the shared hex meshes, the comparison with VTK's vtkMeshQuality (Verdict), and the
// `polycube quality` command.
#include "quality/report.h"

#include "core/topology.h"
#include "io/mesh_io.h"
#include "independent_counts.h"
#include "quality_fixtures.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>

namespace polycube::quality {
namespace {

namespace fs = std::filesystem;

fs::path data_file(const std::string& name) { return fs::path(POLYCUBE_DATA_DIR) / "hex" / name; }

//! A fresh temporary folder, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() /
           ("polycube_quality_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

//! Consistency of a hex report, whatever the mesh.
void expect_consistent(const HexReport& r) {
  EXPECT_EQ(r.sj.count, r.hexes);
  EXPECT_EQ(std::accumulate(r.sj.histogram.begin(), r.sj.histogram.end(), 0), r.hexes);
  EXPECT_LE(r.sj.min, r.sj.average);
  EXPECT_LE(r.sj.average, r.sj.max);
  EXPECT_LE(r.sj.max, 1.0);
  EXPECT_EQ(r.sj.histogram[0], r.sj.inverted + r.sj.invalid);
  ASSERT_TRUE(r.singularities && r.domains);
  EXPECT_EQ(r.singularities->singular_edges,
            r.singularities->boundary_singular_edges + r.singularities->interior_singular_edges);
  ASSERT_EQ(static_cast<int>(r.domains->block_id.size()), r.hexes);
  const std::set<int> ids(r.domains->block_id.begin(), r.domains->block_id.end());
  EXPECT_EQ(static_cast<int>(ids.size()), r.domains->domains);
  EXPECT_EQ(*ids.begin(), 0);
  EXPECT_EQ(*ids.rbegin(), r.domains->domains - 1);
}

TEST(HexReport, SyntheticMeshes) {
  const auto box = hex_report(test::gridded_box(2, 2, 2, 2));
  expect_consistent(box);
  EXPECT_EQ(box.hexes, 64);
  EXPECT_NEAR(box.sj.min, 1.0, 1e-12);
  EXPECT_EQ(box.singularities->singular_vertices, 8);
  EXPECT_EQ(box.singularities->singular_edges, 48);
  EXPECT_EQ(box.domains->domains, 1);
  EXPECT_EQ(box.surface_singular_vertices, 8);
  EXPECT_EQ(box.surface_domains, 6);

  // The independent reference gives the hand-derived counts too (a box: 8 corners, 12 edges
  // of 4 lattice edges each, one block, 6 patches; padded: 1 core block + 6 padding blocks).
  const test::IndependentCounts ref = test::independent_counts(test::gridded_box(2, 2, 2, 2));
  EXPECT_EQ(ref.singular_vertices, 8);
  EXPECT_EQ(ref.singular_edges, 48);
  EXPECT_EQ(ref.boundary_singular_edges, 48);
  EXPECT_EQ(ref.domains, 1);
  EXPECT_EQ(ref.surface_singular_vertices, 8);
  EXPECT_EQ(ref.surface_domains, 6);
  EXPECT_EQ(test::independent_counts(test::padded_box(2)).domains, 7);

  const auto padded = hex_report(test::padded_box(2));
  expect_consistent(padded);
  EXPECT_EQ(padded.domains->domains, 7);
  EXPECT_TRUE(padded.sj.all_positive());
  EXPECT_EQ(padded.surface_domains, 6);
  const auto fields = padded.fields();
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].name, "scaled_jacobian");
  EXPECT_EQ(fields[1].name, "block_id");

  ReportOptions lean;
  lean.structure = false;
  lean.surface_layout = false;
  lean.keep_per_element = false;
  const auto r = hex_report(test::padded_box(2), lean);
  EXPECT_FALSE(r.singularities.has_value());
  EXPECT_EQ(r.surface_domains, -1);
  EXPECT_TRUE(r.fields().empty());
  EXPECT_DOUBLE_EQ(r.sj.average, padded.sj.average);
}

TEST(HexReport, DistanceToTarget) {
  const auto hexes = test::gridded_box(1, 1, 1, 2);
  core::TriMesh target = triangulate(core::boundary(hexes).surface);
  for (auto& p : target.points) p.z() += 0.1;
  ReportOptions o;
  o.target = &target;
  o.distance.tolerance = 0.02;  // the maximum is at vertices
  const auto r = hex_report(hexes, o);
  ASSERT_TRUE(r.distance.has_value());
  EXPECT_NEAR(r.distance->hausdorff, 0.1, 1e-12);
}

TEST(QuadAndTetReports, Basics) {
  const auto q = quad_report(core::boundary(test::gridded_box(1, 1, 1, 3)).surface);
  EXPECT_EQ(q.quads, 54);
  EXPECT_NEAR(q.sj.min, 1.0, 1e-12);
  EXPECT_EQ(q.singularities->singular_vertices, 8);
  EXPECT_EQ(q.domains->domains, 6);
  EXPECT_EQ(q.fields().size(), 2u);
  const auto t = tet_report(test::tet_grid(2));
  EXPECT_EQ(t.tets, 48);
  EXPECT_TRUE(t.sj.all_positive());
  EXPECT_EQ(t.fields().size(), 1u);
}

class DataMeshes : public ::testing::TestWithParam<std::pair<const char*, int>> {};

TEST_P(DataMeshes, ConsistentReport) {
  const auto [name, expected_hexes] = GetParam();
  const fs::path path = data_file(name);
  if (!fs::exists(path)) GTEST_SKIP() << path << " not found";
  const core::HexMesh m = core::hexes_of(io::read_mesh(path));
  const HexReport r = hex_report(m);
  expect_consistent(r);
  EXPECT_EQ(r.hexes, expected_hexes);  // README of the shared data
  // Published, valid meshes: nothing inverted or degenerate.
  EXPECT_EQ(r.sj.inverted, 0);
  EXPECT_EQ(r.sj.invalid, 0);
  EXPECT_GT(r.sj.min, 0.0);
  EXPECT_GT(r.singularities->singular_vertices, 0);
  EXPECT_GT(r.singularities->singular_edges, 0);
  EXPECT_GE(r.domains->domains, 1);
  // Every printed count checked against the independent count from the raw cells.
  const test::IndependentCounts ref = test::independent_counts(m);
  EXPECT_EQ(r.singularities->singular_edges, ref.singular_edges);
  EXPECT_EQ(r.singularities->boundary_singular_edges, ref.boundary_singular_edges);
  EXPECT_EQ(r.singularities->interior_singular_edges, ref.interior_singular_edges);
  EXPECT_EQ(r.singularities->singular_vertices, ref.singular_vertices);
  EXPECT_EQ(r.domains->domains, ref.domains);
  EXPECT_EQ(r.surface_singular_vertices, ref.surface_singular_vertices);
  EXPECT_EQ(r.surface_domains, ref.surface_domains);
  std::cout << name << ": #H " << r.hexes << "  mSJ " << r.sj.min << "  aSJ " << r.sj.average
            << "  #Sv " << r.singularities->singular_vertices << "  #Se "
            << r.singularities->singular_edges << "  #D " << r.domains->domains << "  surface #sv "
            << r.surface_singular_vertices << "  #dom " << r.surface_domains << "\n";
  // Deterministic: a second run gives identical per-element results.
  const HexReport again = hex_report(m);
  EXPECT_EQ(again.sj.values, r.sj.values);
  EXPECT_EQ(again.domains->block_id, r.domains->block_id);
}

INSTANTIATE_TEST_SUITE_P(Quality, DataMeshes,
                         ::testing::Values(std::make_pair("rockerarm.mesh", 10600),
                                           std::make_pair("ellipsoid.mesh", 6816)));

bool python_vtk_available() {
  return std::system(
             "/usr/bin/python3 -c 'import vtkmodules.vtkFiltersVerdict, vtkmodules.vtkIOLegacy' "
             "> /dev/null 2>&1") == 0;
}

//! Per-cell values computed by VTK's vtkMeshQuality for each mesh (written by our VTK writer),
//! with one Python run.
std::vector<std::vector<double>> vtk_scaled_jacobian(const std::vector<core::MeshData>& meshes,
                                                     const fs::path& dir) {
  std::string cmd = "/usr/bin/python3 '" POLYCUBE_QUALITY_TEST_DIR "/vtk_scaled_jacobian.py'";
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const fs::path in = dir / ("mesh" + std::to_string(i) + ".vtk");
    io::write_mesh(in, meshes[i]);
    cmd += " '" + in.string() + "' '" + (dir / ("sj" + std::to_string(i) + ".txt")).string() + "'";
  }
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::vector<std::vector<double>> values(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    std::ifstream f(dir / ("sj" + std::to_string(i) + ".txt"));
    for (double v; f >> v;) values[i].push_back(v);
  }
  return values;
}

//! Compare our per-element values with VTK's to 1e-6 (valid elements; Verdict calls degenerate
//! ones 1e30, we call them invalid).
void expect_matches_vtk(const ScaledJacobianSummary& ours, const std::vector<double>& vtk) {
  ASSERT_EQ(vtk.size(), ours.values.size());
  int compared = 0;
  for (std::size_t i = 0; i < vtk.size(); ++i) {
    if (ours.values[i] == kInvalidScaledJacobian && vtk[i] > 1.0) continue;  // degenerate
    ++compared;
    ASSERT_NEAR(ours.values[i], vtk[i], 1e-6) << "element " << i;
  }
  EXPECT_EQ(compared + ours.invalid, static_cast<int>(vtk.size()));
}

TEST(VtkComparison, PerturbedGridWithInvertedHexes) {
  if (!python_vtk_available()) GTEST_SKIP() << "python3 with vtk not available";
  TempDir tmp;
  // A 6^3 grid whose interior vertices move randomly by up to 0.45 cells: many distorted and
  // some inverted hexes.
  core::HexMesh m = test::gridded_box(1, 1, 1, 6);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(-0.45 / 6, 0.45 / 6);
  for (auto& p : m.points)
    if (p.minCoeff() > 1e-9 && p.maxCoeff() < 1 - 1e-9) p += core::Vec3(u(rng), u(rng), u(rng));
  const auto ours = scaled_jacobian(m);
  EXPECT_GT(ours.inverted, 0);

  // Tets and quads too.
  core::TetMesh t = test::tet_grid(3);
  for (auto& p : t.points) p += core::Vec3(u(rng), u(rng), u(rng));
  core::QuadMesh q = core::boundary(m).surface;
  for (auto& p : q.points) p += core::Vec3(u(rng), u(rng), u(rng));

  const auto vtk = vtk_scaled_jacobian(
      {core::to_mesh_data(m), core::to_mesh_data(t), core::to_mesh_data(q)}, tmp.path);
  expect_matches_vtk(ours, vtk[0]);
  expect_matches_vtk(scaled_jacobian(t), vtk[1]);
  expect_matches_vtk(scaled_jacobian(q), vtk[2]);
}

TEST(VtkComparison, DataMeshes) {
  if (!python_vtk_available()) GTEST_SKIP() << "python3 with vtk not available";
  std::vector<core::HexMesh> meshes;
  for (const char* name : {"rockerarm.mesh", "ellipsoid.mesh"}) {
    const fs::path path = data_file(name);
    if (fs::exists(path)) meshes.push_back(core::hexes_of(io::read_mesh(path)));
  }
  if (meshes.empty()) GTEST_SKIP() << "no shared hex mesh found";
  TempDir tmp;
  std::vector<core::MeshData> data;
  for (const auto& m : meshes) data.push_back(core::to_mesh_data(m));
  const auto vtk = vtk_scaled_jacobian(data, tmp.path);
  for (std::size_t i = 0; i < meshes.size(); ++i)
    expect_matches_vtk(scaled_jacobian(meshes[i]), vtk[i]);
}

TEST(QualityCommand, TableJsonAndVtk) {
  const fs::path cli = POLYCUBE_CLI;
  if (!fs::exists(cli)) GTEST_SKIP() << "polycube command not built";
  TempDir tmp;
  const fs::path in = tmp.path / "padded.mesh", out = tmp.path / "out.vtk",
                 json = tmp.path / "out.json";
  io::write_mesh(in, core::to_mesh_data(test::padded_box(2)));
  std::string cmd = "'" + cli.string() + "' quality '" + in.string() + "' --vtk '" + out.string() +
                    "' > '" + (tmp.path / "table.txt").string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream table(tmp.path / "table.txt");
  std::stringstream text;
  text << table.rdbuf();
  EXPECT_NE(text.str().find("#D"), std::string::npos) << text.str();

  // The VTK output carries the two cell fields.
  const core::MeshData d = io::read_mesh(out);
  ASSERT_EQ(d.hexes.size(), 32u);  // 2^3 core hexes + 6 * 2^2 padding hexes
  std::set<std::string> names;
  for (const auto& f : d.cell_data) names.insert(f.name);
  EXPECT_TRUE(names.count("scaled_jacobian"));
  EXPECT_TRUE(names.count("block_id"));

  cmd = "'" + cli.string() + "' --json quality '" + in.string() + "' > '" + json.string() + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream jf(json);
  std::stringstream js;
  js << jf.rdbuf();
  EXPECT_NE(js.str().find("\"domains\": 7"), std::string::npos) << js.str();

  // A missing file is bad input (exit code 2).
  cmd = "'" + cli.string() + "' quality '" + (tmp.path / "missing.mesh").string() +
        "' > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  EXPECT_TRUE(WIFEXITED(rc));
  EXPECT_EQ(WEXITSTATUS(rc), 2);
}

}  // namespace
}  // namespace polycube::quality
