// `polycube fabricate`: the affine T's map is cut into its two boxes; the part STLs re-read as
// closed surfaces whose volumes are the boxes' images; parts.json says the same; bad input exits 2.
#include "cli/run_cli.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"

#include "fabricate_fixtures.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>

namespace polycube {
namespace {

namespace fs = std::filesystem;

double enclosed_volume(const core::TriMesh& m) {
  double v = 0;
  for (const auto& t : m.cells) v += m.points[t[0]].dot(m.points[t[1]].cross(m.points[t[2]])) / 6.0;
  return v;
}

TEST(FabricateCli, TheTIsCutIntoTwoPartsWrittenAsStlAndJson) {
  const test::AffineT t = test::affine_t();
  const fs::path dir = fs::path(::testing::TempDir()) / "fabricate_t";
  fs::remove_all(dir);
  fs::create_directories(dir);
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

TEST(FabricateCli, AMissingMapIsBadInput) {
  const auto r =
      test::run_cli("fabricate /nonexistent/model.mesh /nonexistent/polycube.mesh -o /tmp/x");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("error"), std::string::npos);
}

}  // namespace
}  // namespace polycube
