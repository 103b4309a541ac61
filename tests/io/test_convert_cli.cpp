// `polycube convert`: format chains through the command line, and the bad-input corpus
// (tests/data/bad/EXPECTED.txt) — exit code 2, one line on stderr naming the file, no output.
#include "core/errors.h"
#include "fixtures.h"
#include "io/mesh_io.h"

#include "support/files.h"

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace polycube::io {
namespace {

namespace fs = std::filesystem;
using polycube::test::quoted;
using polycube::test::slurp;
using test::expect_points_near;

struct CliRun {
  int code = -1;
  std::string out, err;
};

//! CliRun `polycube <args>` with stdout and stderr captured.
CliRun polycube(const std::string& args, const test::TempDir& dir) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string cmd = quoted(POLYCUBE_CLI) + " " + args + " > " + quoted(out) + " 2> " + quoted(err);
  const int status = std::system(cmd.c_str());
  CliRun r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

TEST(ConvertCli, SurfaceChainObjOffPlyStl) {
  test::TempDir dir("chain_surface");
  const core::MeshData d = test::mixed_surface();
  core::MeshData tri = d;  // STL holds triangles only: the chain's mesh is all triangles
  tri.quads.clear();
  tri.points.resize(6);
  write_mesh(dir / "a.obj", tri);
  struct Step {
    const char *in, *out, *flags;
  };
  const Step chain[] = {{"a.obj", "b.off", ""},          {"b.off", "c.ply", ""},   {"c.ply", "d.ply", "--binary --double"},
                        {"d.ply", "e.stl", ""},          {"e.stl", "f.stl", "--binary"}, {"f.stl", "g.obj", ""}};
  for (const Step& st : chain) {
    const CliRun r = polycube("convert " + quoted(dir / st.in) + " " + quoted(dir / st.out) + " " + st.flags, dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("converted"), std::string::npos);
  }
  const core::MeshData before_stl = read_mesh(dir / "d.ply");
  EXPECT_EQ(before_stl.triangles, tri.triangles);
  expect_points_near(before_stl.points, tri.points, 1e-12);
  // STL numbers vertices by first use and holds single precision: compare by position.
  const core::MeshData end = read_mesh(dir / "g.obj");
  EXPECT_EQ(end.points.size(), tri.points.size());
  test::expect_same_triangles(end, tri, 0x1p-23);
}

TEST(ConvertCli, VolumeChainMeshVtkMshMesh) {
  test::TempDir dir("chain_volume");
  const core::MeshData d = test::volume_mesh();
  write_mesh(dir / "a.mesh", d);
  for (const auto& [in, out] : {std::pair{"a.mesh", "b.vtk"}, {"b.vtk", "c.msh"}, {"c.msh", "d.mesh"},
                                {"d.mesh", "e.msh"}, {"e.msh", "f.vtk"}, {"f.vtk", "g.mesh"}}) {
    const CliRun r = polycube("--json convert " + quoted(dir / in) + " " + quoted(dir / out), dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("\"tets\": 3"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\"hexes\": 2"), std::string::npos) << r.out;
  }
  for (const char* name : {"d.mesh", "g.mesh"}) {
    const core::MeshData r = read_mesh(dir / name);
    expect_points_near(r.points, d.points, 1e-12);
    EXPECT_EQ(r.triangles, d.triangles);
    EXPECT_EQ(r.quads, d.quads);
    EXPECT_EQ(r.tets, d.tets);
    EXPECT_EQ(r.hexes, d.hexes);
    EXPECT_EQ(r.tet_labels, d.tet_labels);
    EXPECT_EQ(r.hex_labels, d.hex_labels);
    EXPECT_EQ(r.triangle_labels, d.triangle_labels);
  }
}

TEST(ConvertCli, MissingFileAndUsage) {
  test::TempDir dir("missing");
  CliRun r = polycube("convert " + quoted(dir / "nope.obj") + " " + quoted(dir / "x.mesh"), dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("nope.obj: no such file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "x.mesh"));
  r = polycube("convert", dir);
  EXPECT_EQ(r.code, 1);
}

struct BadCase {
  std::string file, substring, out_ext;
};

std::vector<BadCase> bad_cases() {
  std::vector<BadCase> cases;
  std::ifstream in(fs::path(POLYCUBE_TEST_DATA_DIR) / "bad" / "EXPECTED.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> col;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '\t');) col.push_back(c);
    if (col.size() < 2) continue;
    cases.push_back({col[0], col[1], col.size() > 2 ? col[2] : "mesh"});
  }
  return cases;
}

TEST(BadCorpus, EveryFileFailsWithOneClearLine) {
  const fs::path bad = fs::path(POLYCUBE_TEST_DATA_DIR) / "bad";
  const std::vector<BadCase> cases = bad_cases();
  ASSERT_GE(cases.size(), 24u);
  test::TempDir dir("bad");
  std::set<std::string> listed;
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.file);
    listed.insert(c.file);
    ASSERT_TRUE(fs::exists(bad / c.file));
    const fs::path out = dir / ("out." + c.out_ext);
    const CliRun r = polycube("convert " + quoted(bad / c.file) + " " + quoted(out), dir);
    EXPECT_EQ(r.code, 2) << r.err;
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << "not exactly one line: " << r.err;
    EXPECT_NE(r.err.find(c.substring), std::string::npos) << r.err;
    // The file at fault is named: the input, or the output when the writer refuses.
    const std::string named = c.out_ext == "mesh" ? c.file : out.filename().string();
    EXPECT_NE(r.err.find(named), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 0) << "leftover files";
  }
  // Every file of the corpus has its expected error.
  for (const auto& e : fs::directory_iterator(bad)) {
    const std::string name = e.path().filename().string();
    if (name != "EXPECTED.txt") {
      EXPECT_TRUE(listed.count(name)) << name << " is not in EXPECTED.txt";
    }
  }
}

}  // namespace
}  // namespace polycube::io
