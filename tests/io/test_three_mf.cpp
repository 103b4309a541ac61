// 3MF assemblies: round trip of names, geometry and colours; refusals leave nothing behind; and,
// when PrusaSlicer is installed, a slicer's own check that every written object is manifold.
#include "io/three_mf.h"

#include "core/errors.h"
#include "core/topology.h"
#include "fixtures.h"

#include "support/files.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace polycube::io {
namespace {

namespace fs = std::filesystem;
using polycube::test::quoted;
using polycube::test::slurp;

//! The perturbed unit cube of the fixtures scaled to \p size mm, moved by \p offset, as
//! outward triangles (each quad split 0-1-2, 0-2-3).
core::TriMesh cube(double size, const core::Vec3& offset) {
  const core::MeshData q = test::cube_quads();
  core::TriMesh m;
  for (const core::Vec3& p : q.points) m.points.push_back(size * p + offset);
  for (const core::Quad& c : q.quads) {
    m.cells.push_back({c[0], c[1], c[2]});
    m.cells.push_back({c[0], c[2], c[3]});
  }
  return m;
}

std::vector<ThreeMfObject> two_cubes() {
  return {{"base", cube(20.0, {0, 0, 0}), {230, 40, 30}},
          {"lid part", cube(10.0, {25.125, -3.3, 7.0 / 3.0}), {20, 90, 210}}};
}

//! Equal to the precision three_mf.h promises: 2^-22 |x| + 1e-6 (two float ulps and the six
//! decimals lib3mf 1.8 prints).
void expect_float_equal(const std::vector<core::Vec3>& a, const std::vector<core::Vec3>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_LE(std::abs(a[i][k] - b[i][k]), 0x1p-22 * std::abs(a[i][k]) + 1e-6)
          << "vertex " << i << " coordinate " << k << ": " << a[i][k] << " vs " << b[i][k];
}

std::size_t files_in(const fs::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::recursive_directory_iterator(dir)) ++n;
  return n;
}

TEST(ThreeMf, RoundTripKeepsNamesGeometryAndColours) {
  test::TempDir dir("three_mf");
  const std::vector<ThreeMfObject> objects = two_cubes();
  const fs::path file = dir / "parts.3mf";
  write_3mf(file, objects);
  EXPECT_EQ(files_in(dir.path()), 1u);  // no temporary file left

  const std::vector<ThreeMfObject> back = read_3mf(file);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < back.size(); ++i) {
    SCOPED_TRACE(objects[i].name);
    EXPECT_EQ(back[i].name, objects[i].name);
    EXPECT_EQ(back[i].rgb, objects[i].rgb);
    ASSERT_EQ(back[i].mesh.points.size(), 8u);
    ASSERT_EQ(back[i].mesh.cells.size(), 12u);
    EXPECT_EQ(back[i].mesh.cells, objects[i].mesh.cells);
    expect_float_equal(back[i].mesh.points, objects[i].mesh.points);
    const core::SurfaceReport r = core::analyze_surface(back[i].mesh);
    EXPECT_TRUE(r.closed && r.manifold && r.consistently_oriented);
    EXPECT_GT(core::signed_volume(back[i].mesh), 0.0);  // outward, as written
  }
}

TEST(ThreeMf, TheSameObjectsGiveTheSameFileByteForByte) {
  test::TempDir dir("three_mf_same");
  write_3mf(dir / "a.3mf", two_cubes());
  write_3mf(dir / "b.3mf", two_cubes());
  const std::string a = slurp(dir / "a.3mf");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, slurp(dir / "b.3mf"));  // lib3mf's random UUIDs replaced by content-derived ones
  std::vector<ThreeMfObject> moved = two_cubes();
  moved[1].mesh.points[0].x() += 1.0;
  write_3mf(dir / "c.3mf", moved);
  EXPECT_NE(a, slurp(dir / "c.3mf"));
}

TEST(ThreeMf, MissingFolderThrowsAndLeavesNothing) {
  test::TempDir dir("three_mf_missing");
  const fs::path file = dir / "no_such_folder" / "parts.3mf";
  EXPECT_THROW(write_3mf(file, two_cubes()), core::InputError);
  EXPECT_FALSE(fs::exists(file.parent_path()));
  EXPECT_EQ(files_in(dir.path()), 0u);
}

TEST(ThreeMf, RefusesNothingToWriteAndBadTriangles) {
  test::TempDir dir("three_mf_empty");
  try {
    write_3mf(dir / "none.3mf", {});
    FAIL() << "an empty object list was written";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no objects"), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line";
  }
  std::vector<ThreeMfObject> objects = two_cubes();
  objects[1].mesh.cells.clear();
  EXPECT_THROW(write_3mf(dir / "empty_object.3mf", objects), core::InputError);
  objects = two_cubes();
  objects[0].mesh.cells[3][1] = 8;  // out of range
  EXPECT_THROW(write_3mf(dir / "bad_index.3mf", objects), core::InputError);
  objects = two_cubes();
  objects[1].mesh.cells[5][2] = objects[1].mesh.cells[5][0];  // degenerate: 3MF forbids it
  EXPECT_THROW(write_3mf(dir / "degenerate.3mf", objects), core::InputError);
  EXPECT_EQ(files_in(dir.path()), 0u);
}

TEST(ThreeMf, ReadingRefusesMissingAndNon3mfFiles) {
  test::TempDir dir("three_mf_read");
  EXPECT_THROW(read_3mf(dir / "absent.3mf"), core::InputError);
  const fs::path junk = dir / "junk.3mf";
  std::ofstream(junk) << "not a zip package\n";
  try {
    read_3mf(junk);
    FAIL() << "junk was read";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(junk.string()), std::string::npos) << e.what();
  }
}

TEST(ThreeMf, PrusaSlicerFindsEveryObjectManifold) {
  if (std::system("command -v prusa-slicer >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "prusa-slicer not installed";
  test::TempDir dir("three_mf_prusa");
  const fs::path file = dir / "parts.3mf";
  write_3mf(file, two_cubes());
  const fs::path out = dir / "info.txt";
  const int status =
      std::system(("prusa-slicer --info " + quoted(file) + " > " + quoted(out) + " 2>&1").c_str());
  const std::string info = slurp(out);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << info;
  // One "manifold = yes" line per object, none "no".
  std::size_t yes = 0;
  for (std::size_t at = info.find("manifold = yes"); at != std::string::npos;
       at = info.find("manifold = yes", at + 1))
    ++yes;
  EXPECT_EQ(yes, 2u) << info;
  EXPECT_EQ(info.find("manifold = no"), std::string::npos) << info;
}

}  // namespace
}  // namespace polycube::io
