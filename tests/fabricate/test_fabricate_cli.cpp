// `polycube fabricate`: the affine T's map is cut into its two boxes; the part STLs re-read as
// closed surfaces whose volumes are the boxes' images; parts.json says the same; bad input exits
// 2. From a shape (a built-in sample): construct, simplify and the parts in one command, every
// output re-read (STL, 3MF, PLY, VTK), PrusaSlicer's own manifold check when it is installed;
// a chamber splits the parts until each stands in it; run --fabricate adds the stage.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "io/three_mf.h"

#include "fabricate_fixtures.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace polycube {
namespace {

namespace fs = std::filesystem;

//! A fresh folder of this test process: ctest runs the tests of this file as parallel
//! processes, so a fixed name would let one process delete another's outputs.
fs::path fresh_dir(const std::string& name) { return test::scratch_dir(name); }

double enclosed_volume(const core::TriMesh& m) {
  double v = 0;
  for (const auto& t : m.cells) v += m.points[t[0]].dot(m.points[t[1]].cross(m.points[t[2]])) / 6.0;
  return v;
}

TEST(FabricateCli, TheTIsCutIntoTwoPartsWrittenAsStlAndJson) {
  const test::AffineT t = test::affine_t();
  const fs::path dir = fresh_dir("fabricate_t");
  io::write_polycube_map(dir / "model.mesh", dir / "polycube.mesh", t.map);
  const auto r =
      test::run_cli("--json fabricate " + (dir / "model.mesh").string() + " " +
                    (dir / "polycube.mesh").string() + " -o " + (dir / "parts").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "parts" / "parts.json"));
  EXPECT_EQ(j["parts_count"], 2);
  EXPECT_EQ(j["failing_parts"], 0);
  ASSERT_EQ(j["parts"].size(), 2u);
  const double det = t.A.determinant();
  double total = 0;
  for (const auto& p : j["parts"]) {
    EXPECT_TRUE(p["ok"].get<bool>());
    const core::TriMesh m = io::read_surface(dir / "parts" / p["file"].get<std::string>());
    const core::SurfaceReport topo = core::analyze_surface(m);
    EXPECT_TRUE(topo.closed);
    EXPECT_TRUE(topo.manifold);
    EXPECT_TRUE(topo.consistently_oriented);
    EXPECT_EQ(topo.degenerate_faces, 0);
    const double v = enclosed_volume(m);
    EXPECT_NEAR(v, p["volume"].get<double>(), 1e-6 * v);  // STL stores single-precision floats
    total += v;
  }
  EXPECT_NEAR(total, 4 * det, 1e-6 * total);
}

TEST(FabricateCli, AFolderWrittenBeforeKeepsNoEarlierPartButKeepsOtherFiles) {
  const test::AffineT t = test::affine_t();
  const fs::path dir = fresh_dir("fabricate_again");
  io::write_polycube_map(dir / "model.mesh", dir / "polycube.mesh", t.map);
  fs::create_directories(dir / "parts" / "print");
  for (const fs::path& p : {dir / "parts" / "part_07.stl", dir / "parts" / "print" / "part_07.stl",
                            dir / "parts" / "notes.txt"})
    std::ofstream(p) << "earlier\n";
  const auto r = test::run_cli("-q fabricate " + (dir / "model.mesh").string() + " " +
                               (dir / "polycube.mesh").string() + " -o " + (dir / "parts").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "parts" / "part_07.stl"));
  EXPECT_FALSE(fs::exists(dir / "parts" / "print" / "part_07.stl"));
  EXPECT_TRUE(fs::exists(dir / "parts" / "notes.txt"));  // not ours: left alone
  EXPECT_TRUE(fs::exists(dir / "parts" / "part_01.stl"));
}

//! Reads every part the output folder's parts.json lists: closed, manifold, outward, their
//! volumes adding up to the solid's; the 3MF holds them all; the exploded views have every
//! triangle. Returns parts.json.
nlohmann::json expect_outputs(const fs::path& dir) {
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(dir / "parts.json"));
  EXPECT_EQ(j["failing_parts"], 0);
  double total = 0;
  std::size_t triangles = 0;
  for (const auto& p : j["parts"]) {
    const core::TriMesh m = io::read_surface(dir / p["file"].get<std::string>());
    const core::SurfaceReport topo = core::analyze_surface(m);
    EXPECT_TRUE(topo.closed && topo.manifold && topo.consistently_oriented) << p["file"];
    EXPECT_FALSE(p["flat_sides"].empty()) << p["file"];
    total += enclosed_volume(m);
    triangles += m.cells.size();
    if (p["print_file"].is_null()) continue;
    // Print-ready: the same solid moved rigidly onto the bed.
    const core::TriMesh on_bed = io::read_surface(dir / p["print_file"].get<std::string>());
    EXPECT_EQ(on_bed.cells.size(), m.cells.size()) << p["print_file"];
    EXPECT_NEAR(enclosed_volume(on_bed), enclosed_volume(m), 1e-5 * enclosed_volume(m));
    const core::BoundingBox box = core::bounding_box(on_bed.points);
    EXPECT_NEAR(box.min.z(), 0.0, 1e-5 * (box.max - box.min).norm()) << p["print_file"];
  }
  const double solid = j["solid_volume"].get<double>();
  EXPECT_NEAR(total, solid, 1e-5 * solid);  // STL floats
  const auto assembly = io::read_3mf(dir / "parts.3mf");
  EXPECT_EQ(assembly.size(), j["parts"].size());
  for (const char* view : {"exploded.ply", "exploded.vtk"}) {
    const core::MeshData d = io::read_mesh(dir / view);
    EXPECT_EQ(d.triangles.size(), triangles) << view;
    EXPECT_FALSE(d.cell_data.empty()) << view;
  }
  return j;
}

//! PrusaSlicer's --info on a file: the number of "manifold = yes" and "manifold = no" lines, or
//! {-1, -1} when it did not run.
std::pair<int, int> prusa_manifold(const fs::path& file) {
  const fs::path out = file.string() + ".info.txt";
  const int status = std::system(
      ("prusa-slicer --info '" + file.string() + "' > '" + out.string() + "' 2>&1").c_str());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return {-1, -1};
  std::ifstream in(out);
  std::string line;
  std::pair<int, int> n{0, 0};
  while (std::getline(in, line)) {
    n.first += line == "manifold = yes" ? 1 : 0;
    n.second += line == "manifold = no" ? 1 : 0;
  }
  return n;
}

//! The flange sample's parts, made once for the tests below (construct + simplify + cut).
const fs::path& flange_parts() {
  static const fs::path dir = [] {
    const fs::path d = fresh_dir("fabricate_flange");
    test::run_cli("sample flange -o " + (d / "flange.obj").string());
    const auto r = test::run_cli("-q fabricate " + (d / "flange.obj").string() + " -o " +
                                 (d / "out").string());
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return d / "out" / "parts";
  }();
  return dir;
}

TEST(FabricateCli, AShapeIsMappedSimplifiedAndCutInOneCommand) {
  const nlohmann::json j = expect_outputs(flange_parts());
  EXPECT_GT(j["parts_count"].get<int>(), 1);
  EXPECT_LE(j["parts_count"].get<int>(), j["boxes"].get<int>());
  EXPECT_TRUE(fs::exists(flange_parts().parent_path() / "simplify" / "model.mesh"));
}

TEST(FabricateCli, PrusaSlicerFindsEveryPartManifold) {
  if (std::system("command -v prusa-slicer >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "prusa-slicer not installed";
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(flange_parts() / "parts.json"));
  for (const auto& p : j["parts"]) {
    const auto [yes, no] = prusa_manifold(flange_parts() / p["file"].get<std::string>());
    EXPECT_EQ(yes, 1) << p["file"];
    EXPECT_EQ(no, 0) << p["file"];
  }
  const auto [yes, no] = prusa_manifold(flange_parts() / "parts.3mf");
  EXPECT_EQ(yes, static_cast<int>(j["parts"].size()));
  EXPECT_EQ(no, 0);
}

TEST(FabricateCli, AChamberSplitsThePartsUntilEachStandsInIt) {
  const fs::path map = flange_parts().parent_path() / "simplify";
  const fs::path out = flange_parts().parent_path() / "chamber";
  const nlohmann::json free = nlohmann::json::parse(std::ifstream(flange_parts() / "parts.json"));
  // A chamber a third of the largest part's longest side: every such part must be split.
  double longest = 0;
  for (const auto& p : free["parts"]) {
    const auto& b = p["bounding_box"];
    for (int a = 0; a < 3; ++a)
      longest = std::max(longest, b["max"][a].get<double>() - b["min"][a].get<double>());
  }
  const double c = longest / 3;
  const auto r = test::run_cli(
      fmt::format("-q fabricate {} {} -o {} --chamber {} {} {}", (map / "model.mesh").string(),
                  (map / "polycube.mesh").string(), out.string(), c, c, c));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = expect_outputs(out);
  EXPECT_GT(j["parts_count"].get<int>(), free["parts_count"].get<int>());
  EXPECT_EQ(j["unfit_parts"], 0);
  for (const auto& p : j["parts"]) ASSERT_FALSE(p["base"].is_null()) << p["file"];
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FabricateCli, TheSameMapGivesTheSameFilesByteForByte) {
  const fs::path map = flange_parts().parent_path() / "simplify";
  const fs::path a = flange_parts().parent_path() / "again_a", b = a.parent_path() / "again_b";
  for (const fs::path& out : {a, b}) {
    const auto r = test::run_cli("-q fabricate " + (map / "model.mesh").string() + " " +
                                 (map / "polycube.mesh").string() + " -o " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  int compared = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path name = fs::relative(entry.path(), a);
    if (name == "parts.json") continue;  // holds the times
    EXPECT_EQ(bytes(entry.path()), bytes(b / name)) << name;
    ++compared;
  }
  EXPECT_GT(compared, 4);
}

TEST(FabricateCli, AChamberNothingFitsIsRefusedWithTheRemedy) {
  const fs::path map = flange_parts().parent_path() / "simplify";
  const fs::path out = flange_parts().parent_path() / "tiny";
  const auto r = test::run_cli("fabricate " + (map / "model.mesh").string() + " " +
                               (map / "polycube.mesh").string() + " -o " + out.string() +
                               " --chamber 0.01 0.01 0.01");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("larger chamber"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out / "parts.json"));
}

TEST(FabricateCli, RunWithFabricateWritesThePartsBesideTheMesh) {
  const fs::path d = fresh_dir("run_fabricate");
  test::run_cli("sample l-bracket -o " + (d / "l.obj").string());
  const auto r = test::run_cli("-q --json run " + (d / "l.obj").string() + " -o " +
                               (d / "out").string() + " --hexes 500 --no-optimize --fabricate");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_GT(report["fabricate"]["parts"].get<int>(), 1);
  expect_outputs(d / "out" / "parts");
  EXPECT_TRUE(fs::exists(d / "out" / "hex.mesh"));
}

// The map `run` makes of the flange has cut planes through vertices of the input, where the
// exact cuts leave edges shorter than a rounding step; rounded as they were, 4 of its 9 parts
// self-intersected (parts.cpp collapses those edges before rounding).
TEST(FabricateCli, RunWithFabricateCutsTheFlangesMapIntoPartsThatPassTheirChecks) {
  const fs::path d = fresh_dir("run_fabricate_flange");
  test::run_cli("sample flange -o " + (d / "flange.obj").string());
  const auto r = test::run_cli("-q --json run " + (d / "flange.obj").string() + " -o " + (d / "out").string() +
                               " --hexes 1000 --no-optimize --fabricate");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = expect_outputs(d / "out" / "parts");
  EXPECT_EQ(j["failing_parts"], 0);
  for (const auto& p : j["parts"]) {
    EXPECT_TRUE(p["ok"].get<bool>()) << p["file"];
    EXPECT_FALSE(p["self_intersecting"].get<bool>()) << p["file"];
  }
}

TEST(FabricateCli, CheckFabFindsTheFlatSidesOfATAndItsBestBase) {
  // A T of 4 unit cubes (the stem under the bar), written as a surface made elsewhere.
  core::HexMesh h = test::hex_grid(3, 1, 2);
  h.cells.erase(h.cells.begin() + 2);  // cell (2, 0, 0)
  h.cells.erase(h.cells.begin());      // cell (0, 0, 0)
  const fs::path dir = fresh_dir("check_fab");
  io::write_mesh(dir / "t.stl",
                 core::to_mesh_data(core::boundary(test::tetrahedralize(h)).surface));
  const auto r = test::run_cli("--json check-fab " + (dir / "t.stl").string() + " --vtk " +
                               (dir / "t.vtk").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["flat_sides"].size(), 9u);  // z = 0, 1, 2; x = 0, 1, 2, 3; y = 0, 1
  double area = 0;
  for (const auto& s : j["flat_sides"]) area += s["area"].get<double>();
  EXPECT_NEAR(area, 18.0, 1e-5);
  // Best: lying on its face (no support, the largest such side).
  const auto& best = j["flat_sides"][j["print_base"].get<int>()];
  EXPECT_NEAR(std::abs(best["normal"][1].get<double>()), 1.0, 1e-6);
  EXPECT_EQ(best["support_percent"].get<double>(), 0.0);
  EXPECT_EQ(j["four_axis"]["unreached_percent"].get<double>(), 0.0);
  EXPECT_EQ(io::read_mesh(dir / "t.vtk").cell_data.size(), 4u);
  const auto bad = test::run_cli("check-fab /nonexistent.stl");
  EXPECT_EQ(bad.exit_code, 2);
}

TEST(FabricateCli, AMissingMapIsBadInput) {
  const auto r =
      test::run_cli("fabricate /nonexistent/model.mesh /nonexistent/polycube.mesh -o /tmp/x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error"), std::string::npos);
}

}  // namespace
}  // namespace polycube
