// The repairs that never move a surface: a soup of a box becomes the box, counted exactly; a
// triangle using a vertex twice and a repeated one are dropped; a clean mesh comes back bit for
// bit, and so does every shared model. Through the CLI: `info` reports the repairs and the
// repaired surface, `construct` maps a soup OBJ that it used to refuse as open.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "repair/repair.h"
#include "support/shapes.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
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

// Each change is located: the first places of each kind (a vertex, a triangle's centre), so
// `info` can say where to look. Placed exactly: the centres are of the triangles as read.
TEST(Repair, EachRepairSaysWhereItWas) {
  core::TriMesh m = test::make_box(1, 1, 1, 1);
  const core::Tri third = m.cells[3];
  m.cells.push_back({0, 0, 1});
  m.cells.push_back({third[1], third[2], third[0]});
  const core::Vec3 degenerate = (2.0 * m.points[0] + m.points[1]) / 3.0;
  const core::Vec3 repeated = (m.points[third[0]] + m.points[third[1]] + m.points[third[2]]) / 3.0;
  const repair::RepairReport r = repair::repair_surface(m);
  ASSERT_EQ(r.sites.degenerate.size(), 1u);
  EXPECT_EQ(r.sites.degenerate[0], degenerate);
  ASSERT_EQ(r.sites.duplicate.size(), 1u);
  EXPECT_EQ(r.sites.duplicate[0], repeated);
  const std::vector<std::string> where = r.lines(true);
  ASSERT_EQ(where.size(), 2u);
  EXPECT_EQ(where[0], fmt::format("dropped 1 triangles using a vertex twice (at ({:.6g}, {:.6g}, {:.6g}))",
                                  degenerate.x(), degenerate.y(), degenerate.z()));
  EXPECT_EQ(r.lines(false)[0], "dropped 1 triangles using a vertex twice");

  // Many of a kind: the first three, said to be the first.
  const core::TriMesh box = test::make_box(1, 2, 3, 2);
  core::TriMesh soup = test::soup_of(box);
  const repair::RepairReport s = repair::repair_surface(soup);
  EXPECT_EQ(s.sites.merged.size(), repair::RepairReport::kMaxSites);
  for (const core::Vec3& p : s.sites.merged)
    EXPECT_NE(std::find(box.points.begin(), box.points.end(), p), box.points.end());
  EXPECT_NE(s.lines(true)[0].find(" (first at ("), std::string::npos) << s.lines(true)[0];

  // Two boxes touching at a corner: the split vertex is that corner.
  core::TriMesh pinched =
      test::join(test::make_box(1, 1, 1, 2), test::make_box(1, 1, 1, 2, core::Vec3(1, 1, 1)));
  const repair::RepairReport p = repair::repair_surface(pinched);
  ASSERT_EQ(p.sites.split.size(), 1u);
  EXPECT_EQ(p.sites.split[0], core::Vec3(1, 1, 1));
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
  const fs::path dir = test::scratch_dir("repair_cli");
  const core::TriMesh box = test::make_box(1, 2, 1.5, 3);
  io::write_mesh(dir / "soup.obj", core::to_mesh_data(test::soup_of(box)));
  const auto info = test::run_cli("--json info " + (dir / "soup.obj").string());
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const nlohmann::json j = nlohmann::json::parse(info.out);
  ASSERT_EQ(j["repairs"].size(), 1u);
  EXPECT_EQ(j["repairs"][0].get<std::string>().rfind(
                fmt::format("merged {} vertices at the same coordinates as another (first at (",
                            3 * box.cells.size() - box.points.size()),
                0),
            0u)
      << j["repairs"][0];
  EXPECT_TRUE(j["surface"]["closed"].get<bool>());
  // Where: info names the first places (the test above checks them exactly).
  const auto text = test::run_cli("info " + (dir / "soup.obj").string());
  EXPECT_NE(text.out.find("as another (first at ("), std::string::npos) << text.out;
  const auto r = test::run_cli(
      fmt::format("construct {} -o {}", (dir / "soup.obj").string(), (dir / "map").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("merged"), std::string::npos) << r.err;  // the repair is said
  EXPECT_TRUE(fs::exists(dir / "map" / "polycube.mesh"));
}

}  // namespace
}  // namespace polycube
