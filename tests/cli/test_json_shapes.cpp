// One JSON shape per result type: every command that reports a scaled-Jacobian summary
// (`optimize`'s before/after, `quality`'s scaled_jacobian) writes the same keys, and the same
// mesh gives the same object.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/run_cli.h"
#include "io/mesh_io.h"
#include "optimize/optimize_fixtures.h"
#include "support/scratch.h"

#include <filesystem>
#include <set>
#include <string>

namespace polycube {
namespace {

namespace fs = std::filesystem;
using test::run_cli;

std::set<std::string> keys(const nlohmann::json& j) {
  std::set<std::string> k;
  for (const auto& [key, value] : j.items()) k.insert(key);
  return k;
}

//! The keys of a scaled-Jacobian summary and of its histogram bins, and the bin counts adding
//! up to the number of cells.
void expect_summary_shape(const nlohmann::json& sj, int cells, const std::string& where) {
  EXPECT_EQ(keys(sj), (std::set<std::string>{"min", "average", "max", "inverted", "invalid", "histogram"})) << where;
  ASSERT_TRUE(sj["histogram"].is_array()) << where;
  int total = 0;
  for (const auto& bin : sj["histogram"]) {
    EXPECT_EQ(keys(bin), (std::set<std::string>{"lower", "upper", "count"})) << where;
    total += bin["count"].get<int>();
  }
  EXPECT_EQ(total, cells) << where;
}

TEST(JsonShapes, OptimizeAndQualityReportTheSameScaledJacobianSummary) {
  const fs::path dir = polycube::test::scratch_dir("pc_json_shapes");
  core::HexMesh m = test::box_grid(3, 3, 3);
  test::perturb(m, 0.04, 3, [](const core::Vec3&) { return true; });
  io::write_mesh(dir / "hex.mesh", core::to_mesh_data(m));
  io::write_mesh(dir / "box.obj", core::to_mesh_data(test::box_surface()));
  const auto q = [&](const char* name) {
    std::string quoted = "'";  // appended, not "'" + ...: GCC 12 warns falsely (-Wrestrict) on that
    quoted += (dir / name).string();
    quoted += '\'';
    return quoted;
  };

  const auto opt = run_cli("optimize " + q("hex.mesh") + " --target " + q("box.obj") + " -o " + q("out.mesh") +
                           " --json");
  ASSERT_EQ(opt.exit_code, 0) << opt.err;
  const nlohmann::json jo = nlohmann::json::parse(opt.out);
  const auto before = run_cli("quality " + q("hex.mesh") + " --json");
  ASSERT_EQ(before.exit_code, 0) << before.err;
  const nlohmann::json jb = nlohmann::json::parse(before.out);
  const auto after = run_cli("quality " + q("out.mesh") + " --json");
  ASSERT_EQ(after.exit_code, 0) << after.err;
  const nlohmann::json ja = nlohmann::json::parse(after.out);

  expect_summary_shape(jo["before"], 27, "optimize before");
  expect_summary_shape(jo["after"], 27, "optimize after");
  expect_summary_shape(jb["scaled_jacobian"], 27, "quality of the input");
  expect_summary_shape(ja["scaled_jacobian"], 27, "quality of the output");
  // The input file is read the same way by both commands: the very same summary.
  EXPECT_EQ(jo["before"], jb["scaled_jacobian"]);
  // The output went through a text file: the same up to its printed precision.
  EXPECT_NEAR(jo["after"]["min"].get<double>(), ja["scaled_jacobian"]["min"].get<double>(), 1e-6);
  EXPECT_EQ(jo["after"]["histogram"], ja["scaled_jacobian"]["histogram"]);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace polycube
