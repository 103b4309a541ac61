// The repairs that never move a surface: a soup of a box becomes the box, counted exactly; a
// triangle using a vertex twice and a repeated one are dropped; a clean mesh comes back bit for
// bit, and so does every shared model. Through the CLI: `info` reports the repairs and the
// repaired surface, `construct` maps a soup OBJ that it used to refuse as open.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <filesystem>

namespace polycube {
namespace {

namespace fs = std::filesystem;

TEST(Repair, ASoupOfABoxBecomesTheBox) {
  const core::TriMesh box = test::make_box(1, 2, 3, 2);
  core::TriMesh soup = test::soup_of(box);
  const repair::RepairReport r = repair::repair_surface(soup);
  EXPECT_EQ(r.merged_vertices, static_cast<int>(3 * box.cells.size() - box.points.size()));
  EXPECT_EQ(r.degenerate_triangles, 0);
  EXPECT_EQ(r.duplicate_triangles, 0);
  EXPECT_EQ(r.unused_vertices, 0);
  EXPECT_EQ(soup.points.size(), box.points.size());
  EXPECT_EQ(soup.cells.size(), box.cells.size());
  const core::SurfaceReport topo = core::analyze_surface(soup);
  EXPECT_TRUE(topo.closed && topo.manifold && topo.consistently_oriented);
  EXPECT_EQ(r.lines().size(), 1u);
}

TEST(Repair, DegenerateAndRepeatedTrianglesAndUnusedVerticesAreDropped) {
  core::TriMesh m = test::make_box(1, 1, 1, 1);
  const core::TriMesh clean = m;
  m.labels.assign(m.cells.size(), 7);
  m.cells.push_back({0, 0, 1});                                      // uses vertex 0 twice
  m.cells.push_back({m.cells[3][1], m.cells[3][2], m.cells[3][0]});  // triangle 3, turned
  m.labels.push_back(1);
  m.labels.push_back(2);
  m.points.push_back({5, 5, 5});  // of no triangle
  const repair::RepairReport r = repair::repair_surface(m);
  EXPECT_EQ(r.degenerate_triangles, 1);
  EXPECT_EQ(r.duplicate_triangles, 1);
  EXPECT_EQ(r.unused_vertices, 1);
  EXPECT_EQ(r.merged_vertices, 0);
  EXPECT_EQ(m.points, clean.points);
  EXPECT_EQ(m.cells, clean.cells);
  EXPECT_EQ(m.labels, std::vector<int>(clean.cells.size(), 7));
  EXPECT_EQ(r.lines().size(), 3u);
}

TEST(Repair, ATriangleTurnedTheOtherWayIsNotARepeat) {
  core::TriMesh m = test::make_box(1, 1, 1, 1);
  m.cells.push_back({m.cells[0][0], m.cells[0][2], m.cells[0][1]});
  const std::size_t n = m.cells.size();
  EXPECT_FALSE(repair::repair_surface(m).changed());
  EXPECT_EQ(m.cells.size(), n);  // not the repairs' to judge: the closed-surface check refuses it
}

TEST(Repair, EverySharedSurfaceNeedsNothing) {
  const fs::path dir = fs::path(POLYCUBE_DATA_DIR) / "surface";
  if (!fs::exists(dir)) GTEST_SKIP() << dir << " not found";
  int models = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".obj") continue;
    core::TriMesh m = io::read_surface(entry.path());
    const core::TriMesh before = m;
    const repair::RepairReport r = repair::repair_surface(m);
    EXPECT_FALSE(r.changed()) << entry.path() << ": "
                              << (r.lines().empty() ? "" : r.lines().front());
    EXPECT_EQ(m.points, before.points) << entry.path();
    EXPECT_EQ(m.cells, before.cells) << entry.path();
    ++models;
  }
  EXPECT_GT(models, 0);
}

TEST(RepairCli, InfoReportsTheRepairsAndConstructMapsASoup) {
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("repair_cli_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const core::TriMesh box = test::make_box(1, 2, 1.5, 3);
  io::write_mesh(dir / "soup.obj", core::to_mesh_data(test::soup_of(box)));
  const auto info = test::run_cli("--json info " + (dir / "soup.obj").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  ASSERT_EQ(j["repairs"].size(), 1u);
  EXPECT_EQ(j["repairs"][0], fmt::format("merged {} vertices at the same coordinates as another",
                                         3 * box.cells.size() - box.points.size()));
  EXPECT_TRUE(j["surface"]["closed"].get<bool>());
  const auto r = test::run_cli(
      fmt::format("construct {} -o {}", (dir / "soup.obj").string(), (dir / "map").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("merged"), std::string::npos) << r.err;  // the repair is said
  EXPECT_TRUE(fs::exists(dir / "map" / "polycube.mesh"));
}

}  // namespace
}  // namespace polycube
