//! End-to-end tests of `polycube sample`: listing, writing, and the exit codes of bad requests.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "samples/samples.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <string>

namespace {

namespace fs = std::filesystem;
using polycube::test::run_cli;

fs::path temp_dir() {
  static const fs::path d = polycube::test::scratch_dir("polycube_sample_cli");
  return d;
}

TEST(SampleCli, ListNamesEverySample) {
  const auto r = run_cli("sample --list");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& s : polycube::samples::list_samples())
    EXPECT_NE(r.out.find(s.name), std::string::npos) << r.out;
}

TEST(SampleCli, ListAsJson) {
  const auto r = run_cli("sample --list --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto list = polycube::samples::list_samples();
  ASSERT_EQ(j.at("samples").size(), list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    EXPECT_EQ(j["samples"][i]["name"], list[i].name);
    EXPECT_EQ(j["samples"][i]["genus"], list[i].genus);
    EXPECT_FALSE(j["samples"][i]["description"].get<std::string>().empty());
  }
}

// The file written by the command holds the same surface as the library makes in this process
// (so generation is also deterministic across processes), and it is closed of genus 1.
TEST(SampleCli, WritesTheSampleAndReportsCounts) {
  const fs::path out = temp_dir() / "ring.off";
  fs::remove(out);
  const auto r = run_cli("sample ring -o '" + out.string() + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const polycube::core::TriMesh read = polycube::io::read_surface(out);
  const polycube::core::TriMesh made = polycube::samples::make_sample("ring");
  EXPECT_EQ(j.at("triangles"), read.num_cells());
  EXPECT_EQ(j.at("vertices"), read.num_points());
  EXPECT_EQ(j.at("genus"), 1);
  ASSERT_EQ(read.num_cells(), made.num_cells());
  ASSERT_EQ(read.num_points(), made.num_points());
  EXPECT_EQ(read.cells, made.cells);
  for (int i = 0; i < read.num_points(); ++i)
    ASSERT_LE((read.points[i] - made.points[i]).norm(), 1e-9) << "vertex " << i;
  const auto report = polycube::core::analyze_surface(read);
  EXPECT_TRUE(report.closed && report.manifold);
  EXPECT_EQ(report.genus, 1);
}

TEST(SampleCli, UnknownNameIsBadInput) {
  const fs::path out = temp_dir() / "teapot.obj";
  fs::remove(out);
  const auto r = run_cli("sample teapot -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("box-cylinder"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(SampleCli, UnsupportedExtensionIsBadInput) {
  const fs::path out = temp_dir() / "ring.xyz";
  const auto r = run_cli("sample ring -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST(SampleCli, MissingOutputIsUsageError) {
  EXPECT_EQ(run_cli("sample ring").exit_code, 1);
  EXPECT_EQ(run_cli("sample").exit_code, 1);
}

}  // namespace
