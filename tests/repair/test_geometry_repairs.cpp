// The repairs beyond welding: pinched vertices split, triangles turned outward (cavities kept
// facing in), and on request the largest component, hole filling and the alpha wrap; each
// counted exactly, each result checked as construct checks its input. Through the CLI: each
// defect is refused with its remedy named, and goes through `construct` with that remedy.
#include "cli/run_cli.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"
#include "support/shapes.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace polycube {
namespace {

namespace fs = std::filesystem;

//! Whether construct would take it (closed, manifold, no self-intersection).
bool usable(const core::TriMesh& m, std::string* why = nullptr) {
  try {
    construct::check_closed_surface(m);
    return true;
  } catch (const core::InputError& e) {
    if (why) *why = e.what();
    return false;
  }
}

TEST(GeometryRepair, AnInwardBoxIsTurnedOutward) {
  core::TriMesh m = test::turned(test::make_box(2, 3, 4, 3));
  ASSERT_LT(core::signed_volume(m), 0);
  const repair::RepairReport r = repair::repair_surface(m);
  EXPECT_EQ(r.turned_triangles, static_cast<int>(m.cells.size()));
  EXPECT_NEAR(core::signed_volume(m), 24.0, 1e-9);
  // Turned again: nothing left to do.
  EXPECT_FALSE(repair::repair_surface(m).changed());
}

TEST(GeometryRepair, ACavityKeepsFacingIntoItAndIsTurnedWhenItFacesOut) {
  const core::TriMesh outer = test::make_box(10, 10, 10, 2);
  const core::TriMesh inner = test::make_box(2, 2, 2, 1, core::Vec3(4, 4, 4));
  core::TriMesh right = test::join(outer, test::turned(inner));  // the cavity's triangles face into it
  const core::TriMesh before = right;
  EXPECT_FALSE(repair::repair_surface(right).changed());
  EXPECT_EQ(right.cells, before.cells);

  core::TriMesh wrong = test::join(outer, inner);  // the cavity's triangles face into the solid
  const repair::RepairReport r = repair::repair_surface(wrong);
  EXPECT_EQ(r.turned_triangles, static_cast<int>(inner.cells.size()));
  EXPECT_NEAR(core::signed_volume(wrong), 1000.0 - 8.0, 1e-9);
}

TEST(GeometryRepair, APinchedVertexBecomesOneVertexPerSheet) {
  // Two boxes touching at one corner, sharing its vertex after the weld.
  core::TriMesh m = test::join(test::make_box(1, 1, 1, 2), test::make_box(1, 1, 1, 2, core::Vec3(1, 1, 1)));
  const repair::RepairReport r = repair::repair_surface(m);
  EXPECT_EQ(r.merged_vertices, 1);
  EXPECT_EQ(r.split_vertices, 1);
  const core::SurfaceReport s = core::analyze_surface(m);
  EXPECT_EQ(s.nonmanifold_vertices, 0);
  EXPECT_TRUE(s.manifold && s.closed);
  EXPECT_EQ(s.components, 2);
  // The solids still touch: construct refuses, naming the wrap.
  std::string why;
  EXPECT_FALSE(usable(m, &why));
  EXPECT_NE(why.find("--repair wrap"), std::string::npos) << why;
}

TEST(GeometryRepair, TheLargestComponentIsKeptOnRequest) {
  const core::TriMesh big = test::make_box(10, 10, 10, 2);
  core::TriMesh m = test::join(big, test::make_box(1, 1, 1, 1, core::Vec3(20, 0, 0)));
  repair::RepairOptions o;
  o.largest_component = true;
  const repair::RepairReport r = repair::repair_surface(m, o);
  EXPECT_EQ(r.dropped_components, 1);
  EXPECT_EQ(r.dropped_triangles, 12);
  EXPECT_EQ(m.points, big.points);
  EXPECT_EQ(m.cells, big.cells);
}

TEST(GeometryRepair, HolesUpToTheSizeAreClosed) {
  core::TriMesh box = test::make_box(4, 4, 4, 4);
  core::TriMesh open;
  open.points = box.points;
  for (const core::Tri& t : box.cells)  // the top face removed: one hole of 16 edges
    if (!(box.points[t[0]].z() == 4 && box.points[t[1]].z() == 4 && box.points[t[2]].z() == 4)) open.cells.push_back(t);
  core::remove_unreferenced_points(open);
  std::string why;
  ASSERT_FALSE(usable(open, &why));
  EXPECT_NE(why.find("--repair holes"), std::string::npos) << why;

  repair::RepairOptions o;
  o.fill_holes = true;
  o.max_hole_edges = 15;
  core::TriMesh too_big = open;
  const repair::RepairReport kept = repair::repair_surface(too_big, o);
  EXPECT_EQ(kept.filled_holes, 0);
  EXPECT_EQ(kept.open_holes, 1);

  o.max_hole_edges = 16;
  const repair::RepairReport r = repair::repair_surface(open, o);
  EXPECT_EQ(r.filled_holes, 1);
  EXPECT_GE(r.hole_triangles, 14);  // at least the 16-gon's triangulation
  EXPECT_TRUE(usable(open, &why)) << why;
  // The faired patch continues the walls' tangents: a low dome over the flat hole, not below it.
  EXPECT_GT(core::signed_volume(open), 64.0);
  EXPECT_LT(core::signed_volume(open), 64.0 * 1.15);
}

TEST(GeometryRepair, TheWrapMakesOverlappingBoxesOneClosedSolid) {
  core::TriMesh m = test::join(test::make_box(10, 10, 10, 3), test::make_box(10, 10, 10, 3, core::Vec3(5, 5, 5)));
  std::string why;
  ASSERT_FALSE(usable(m, &why));
  repair::RepairOptions o;
  o.wrap = true;
  const repair::RepairReport r = repair::repair_surface(m, o);
  EXPECT_TRUE(r.wrapped);
  EXPECT_EQ(r.wrap_triangles, static_cast<int>(m.cells.size()));
  EXPECT_TRUE(usable(m, &why)) << why;
  const core::SurfaceReport s = core::analyze_surface(m);
  EXPECT_EQ(s.components, 1);
  EXPECT_EQ(s.genus, 0);
  // The union's volume, 1875, within what the offset (0.1 % of the diagonal) and the alpha
  // (1 %, rounding the edges) change.
  EXPECT_NEAR(core::signed_volume(m), 1875.0, 1875.0 * 0.05);
}

fs::path fresh_dir(const std::string& name) { return test::scratch_dir(name); }

TEST(GeometryRepairCli, EachDefectIsRefusedWithItsRemedyAndGoesThroughWithIt) {
  const fs::path dir = fresh_dir("repair_remedies");
  core::TriMesh box = test::make_box(10, 10, 10, 4);
  core::TriMesh open;
  open.points = box.points;
  for (const core::Tri& t : box.cells)
    if (!(box.points[t[0]].x() == 10 && box.points[t[1]].x() == 10 && box.points[t[2]].x() == 10)) open.cells.push_back(t);
  core::remove_unreferenced_points(open);
  const struct {
    const char* name;
    core::TriMesh mesh;
    const char* remedy;
  } cases[] = {
      {"open", open, "--repair holes"},
      {"overlap", test::join(test::make_box(10, 10, 10, 3), test::make_box(10, 10, 10, 3, core::Vec3(5, 5, 5))),
       "--repair wrap"},
      {"pinched", test::join(box, test::make_box(10, 10, 10, 4, core::Vec3(10, 10, 10))), "--repair wrap"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path input = dir / (std::string(c.name) + ".obj");
    io::write_mesh(input, core::to_mesh_data(c.mesh));
    const auto refused = test::run_cli("construct '" + input.string() + "' -o '" + (dir / c.name).string() + "'");
    EXPECT_EQ(refused.exit_code, 2);
    // One error line (after the warnings that list the default repairs), naming the remedy.
    const std::size_t error = refused.err.find("polycube: error: ");
    ASSERT_NE(error, std::string::npos) << refused.err;
    const std::string line = refused.err.substr(error);
    EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 1) << refused.err;
    EXPECT_NE(line.find(c.remedy), std::string::npos) << refused.err;
    // The wrap at a coarser alpha than the default (0.05 of the diagonal instead of 0.01): the
    // construction of the finer wrap takes minutes (bench/RESULTS.md), too long for a unit test.
    const std::string remedy = std::string(c.remedy) + (c.remedy == std::string("--repair wrap") ? " --wrap-alpha 0.05" : "");
    const auto done =
        test::run_cli("construct '" + input.string() + "' -o '" + (dir / c.name).string() + "' " + remedy);
    EXPECT_EQ(done.exit_code, 0) << done.err;
    EXPECT_TRUE(fs::exists(dir / c.name / "polycube.mesh"));
    // `polycube repair` writes the same repair as a file of its own.
    const fs::path out = dir / (std::string(c.name) + "_repaired.obj");
    const auto repaired = test::run_cli("--json repair '" + input.string() + "' -o '" + out.string() + "' " + remedy);
    ASSERT_EQ(repaired.exit_code, 0) << repaired.err;
    const nlohmann::json j = nlohmann::json::parse(repaired.out);
    EXPECT_TRUE(j["usable"].get<bool>());
    EXPECT_FALSE(j["repairs"].empty());
    EXPECT_TRUE(usable(io::read_surface(out)));
  }
  fs::remove_all(dir);
}

TEST(GeometryRepairCli, RunReportsTheRepairsItMade) {
  const fs::path dir = fresh_dir("repair_run_report");
  io::write_mesh(dir / "inward.obj", core::to_mesh_data(test::turned(test::make_box(10, 20, 15, 4))));
  const auto r = test::run_cli("-q run '" + (dir / "inward.obj").string() + "' -o '" + (dir / "out").string() +
                               "' --hexes 300 --no-optimize");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(dir / "out" / "report.json"));
  ASSERT_EQ(report["repairs"].size(), 1u);
  EXPECT_EQ(report["repairs"][0], "turned 192 triangles to face consistently and outward");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polycube
