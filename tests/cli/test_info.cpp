// `polycube info --json` on every model of ../shared/data reports the counts (and, for
// surfaces, the genus) listed in ../shared/data/README.md. The expected values are read from
// that README's tables, so the test follows the data it checks.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_cli.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using polycube::test::run_cli;

namespace {

struct Expected {
  std::string folder;  // surface, tet, hex
  std::string file;
  long vertices = -1;
  long elements = -1;  // triangles, tets or hexes
  int genus = -1;      // surfaces only
};

std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, '|')) {
    const auto b = cell.find_first_not_of(' ');
    const auto e = cell.find_last_not_of(' ');
    cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return cells;  // cells[0] is the empty text before the first '|'
}

// Reads the tables under "## surface/", "## tet/", "## hex/" of the data README.
std::vector<Expected> read_readme(const fs::path& readme) {
  std::vector<Expected> rows;
  std::ifstream in(readme);
  std::string line, folder;
  while (std::getline(in, line)) {
    if (line.rfind("## ", 0) == 0) {
      folder = line.substr(3, line.find('/') - 3);
      continue;
    }
    if (folder.empty() || line.empty() || line[0] != '|') continue;
    const auto c = split_row(line);
    if (c.size() < 4 || c[1] == "file" || c[1].find("---") != std::string::npos) continue;
    Expected e;
    e.folder = folder;
    e.file = c[1];
    e.vertices = std::stol(c[2]);
    e.elements = std::stol(c[3]);
    if (folder == "surface" && c.size() > 4) e.genus = std::stoi(c[4]);
    rows.push_back(e);
  }
  return rows;
}

}  // namespace

TEST(CliInfo, SharedDataCountsAndGenusMatchTheDataReadme) {
  const fs::path data(POLYCUBE_DATA_DIR);
  if (!fs::exists(data / "README.md")) GTEST_SKIP() << "no shared data at " << data;
  const auto rows = read_readme(data / "README.md");
  ASSERT_GE(rows.size(), 15u) << "the data README's tables were not parsed";
  for (const Expected& e : rows) {
    SCOPED_TRACE(e.folder + "/" + e.file);
    const fs::path file = data / e.folder / e.file;
    ASSERT_TRUE(fs::exists(file));
    const auto r = run_cli("info --json '" + file.string() + "'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["vertices"].get<long>(), e.vertices);
    const char* key = e.folder == "surface" ? "triangles" : e.folder == "tet" ? "tetrahedra" : "hexahedra";
    EXPECT_EQ(j[key].get<long>(), e.elements);
    if (e.genus >= 0) {
      EXPECT_EQ(j["genus"].get<int>(), e.genus);
      EXPECT_TRUE(j["surface"]["closed"].get<bool>());
      EXPECT_TRUE(j["surface"]["manifold"].get<bool>());
    }
  }
}

TEST(CliInfo, VolumeQualitySummaryAgreesWithTheQualityCommand) {
  const fs::path data(POLYCUBE_DATA_DIR);
  for (const char* rel : {"hex/rockerarm.mesh", "hex/ellipsoid.mesh", "tet/B0.mesh"}) {
    const fs::path file = data / rel;
    if (!fs::exists(file)) GTEST_SKIP() << "missing " << file;
    SCOPED_TRACE(rel);
    const auto info = run_cli("info --json '" + file.string() + "'");
    const auto quality = run_cli("quality --json '" + file.string() + "'");
    ASSERT_EQ(info.exit_code, 0) << info.err;
    ASSERT_EQ(quality.exit_code, 0) << quality.err;
    const auto ji = nlohmann::json::parse(info.out);
    const auto jq = nlohmann::json::parse(quality.out)["scaled_jacobian"];
    const auto& js = ji[std::string(rel).rfind("hex", 0) == 0 ? "hexahedra_report" : "tetrahedra_report"]["scaled_jacobian"];
    EXPECT_DOUBLE_EQ(js["min"].get<double>(), jq["min"].get<double>());
    EXPECT_DOUBLE_EQ(js["average"].get<double>(), jq["average"].get<double>());
    EXPECT_EQ(js["inverted"].get<int>(), jq["inverted"].get<int>());
    EXPECT_GT(js["min"].get<double>(), 0.0);  // the shared meshes have no inverted element
  }
}

TEST(CliInfo, MissingFileIsBadInput) {
  const auto r = run_cli("info /nonexistent/model.obj");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("model.obj"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST(CliInfo, EveryReaderGivesExitTwoOnAMissingFile) {
  const std::string m = "/nonexistent/m.mesh", p = "/nonexistent/p.mesh";
  for (const std::string& args :
       {"info " + m, "convert " + m + " /tmp/x.vtk", "quality " + m, "label " + m + " -o /tmp/pc_missing",
        "construct " + m + " -o /tmp/pc_missing", "structure " + m + " " + p, "hexmesh " + m + " " + p + " -o /tmp/x.mesh",
        "quadmesh " + m + " " + p + " -o /tmp/x.vtk", "simplify " + m + " " + p + " -o /tmp/pc_missing"}) {
    const auto r = run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find("/nonexistent/"), std::string::npos) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

TEST(CliInfo, UsageErrorsExitWithOne) {
  EXPECT_EQ(run_cli("").exit_code, 1);
  EXPECT_EQ(run_cli("no-such-subcommand").exit_code, 1);
  EXPECT_EQ(run_cli("info").exit_code, 1);
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  EXPECT_EQ(run_cli("info --help").exit_code, 0);
}

// A number out of its range is refused in plain words (not the largest double printed in full),
// and nan or infinity are refused too (a range check alone lets nan through).
TEST(CliInfo, NumbersOutOfRangeAreRefusedInPlainWords) {
  const struct {
    const char* args;
    const char* said;
  } cases[] = {
      {"run in.obj -o out --hexes 0", "--hexes: must be a positive number, got 0"},
      {"run in.obj -o out --hexes inf", "--hexes: must be a positive number, got inf"},
      {"fabricate in.obj -o out --chamber 0 10 10", "--chamber: must be a positive number, got 0"},
      {"run in.obj -o out --padding-min-sj nan", "--padding-min-sj: must be a number from -1 to 1, got nan"},
      {"fabricate in.obj -o out --overhang 91", "--overhang: must be a number from 0 to 90, got 91"},
      {"run in.obj -o out --hexes many", "--hexes: 'many' is not a number"},
  };
  for (const auto& c : cases) {
    const auto r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 1) << c.args;
    EXPECT_NE(r.err.find(c.said), std::string::npos) << c.args << ": " << r.err;
    EXPECT_LT(r.err.size(), 200u) << c.args << ": " << r.err;
  }
}
