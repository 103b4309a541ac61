// The whole chain on the two shapes whose optimized boundary used to fold over itself between
// positive hexes (bunny, fandisk): label "heavy", not in `make test` (about 8 minutes on 2
// cores; `make test-heavy`). The final mesh is checked again here, independently of the
// pipeline's own check: no inverted hex, a boundary that does not cross itself, and a
// structure no finer than before the simplification.
#include "core/types.h"
#include "io/mesh_io.h"
#include "optimize/foldover_check.h"
#include "quality/scaled_jacobian.h"

#include "cli/run_cli.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace polycube {
namespace {

namespace fs = std::filesystem;

void run_chain(const std::string& model) {
  const fs::path input = fs::path(POLYCUBE_DATA_DIR) / "surface" / (model + ".obj");
  if (!fs::exists(input)) GTEST_SKIP() << input << " not found";
  const fs::path out = test::scratch_dir("polycube_run_heavy_" + model) / "out";
  const test::CliResult r =
      test::run_cli("run \"" + input.string() + "\" -o \"" + out.string() + "\" --hexes 10000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(out / "report.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_TRUE(j.at("ok").get<bool>());
  EXPECT_LE(j.at("hex_domains_after").get<int>(), j.at("hex_domains_before").get<int>());
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  ASSERT_GT(hex.num_cells(), 5000);
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(hex);
  EXPECT_EQ(sj.inverted + sj.invalid, 0);
  EXPECT_GT(sj.min, 0.0);
  const optimize::FoldoverReport check = optimize::check_foldover(hex);
  EXPECT_TRUE(check.ok()) << check.reason();
  EXPECT_EQ(check.boundary_self_intersections, 0);
  fs::remove_all(out);
}

TEST(RunHeavy, Bunny) { run_chain("bunny"); }
TEST(RunHeavy, Fandisk) { run_chain("fandisk"); }

}  // namespace
}  // namespace polycube
