// The whole chain on one organic shared model at about 5,000 hexes, in `make test` (the large
// models at 10k-20k hexes stay in `make test-heavy`). Every claim is checked again from the
// files `run` wrote, independently of the pipeline's own checks and of its report: both maps
// certified by the tests' own certifier (exact predicates, its own boundary extraction), the
// same tets in both, no inverted hex, a boundary that does not cross itself, and the boundary
// within the thesis's Hausdorff bound (0.9 % of the diagonal), also by a vertex-sampled distance
// computed here with CGAL's AABB tree.
#include "core/topology.h"
#include "core/types.h"
#include "io/mesh_io.h"
#include "optimize/foldover_check.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include "cli/run_cli.h"
#include "support/certifier.h"
#include "support/exact_geometry.h"
#include "support/scratch.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace polycube {
namespace {

namespace fs = std::filesystem;
using test::farthest_from;

constexpr double kHausdorffBound = 0.009;  // thesis §4.5

//! The map written under `dir` (model.mesh + polycube.mesh) passes the independent certifier.
void expect_certified_map(const fs::path& dir, std::vector<core::Tet>* tets) {
  const core::MeshData model = io::read_mesh(dir / "model.mesh");
  const core::MeshData poly = io::read_mesh(dir / "polycube.mesh");
  ASSERT_EQ(model.tets, poly.tets) << dir;
  ASSERT_EQ(model.points.size(), poly.points.size()) << dir;
  ASSERT_EQ(model.triangle_labels.size(), model.triangles.size()) << dir;
  const test::Verdict v =
      test::independent_check(model.tets, model.points, poly.points, model.triangles, model.triangle_labels);
  EXPECT_TRUE(test::certified(v)) << dir << ": bad model " << v.bad_model << ", bad polycube " << v.bad_polycube
                                  << ", off plane " << v.off_plane << ", wrong facing " << v.wrong_facing;
  EXPECT_EQ(v.boundary_faces, static_cast<int>(model.triangles.size())) << dir;
  *tets = model.tets;
}

TEST(RunOrganic, MoaiCompletesWithinTheBoundAtFiveThousandHexes) {
  const fs::path input = fs::path(POLYCUBE_DATA_DIR) / "surface" / "moai.obj";
  if (!fs::exists(input)) GTEST_SKIP() << input << " not found";
  const fs::path out = test::scratch_dir("polycube_run_organic") / "out";
  const test::CliResult r =
      test::run_cli("run \"" + input.string() + "\" -o \"" + out.string() + "\" --hexes 5000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream f(out / "report.json");
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_TRUE(j.at("ok").get<bool>());

  // Both maps certified, with the same connectivity (the simplification moves positions only).
  std::vector<core::Tet> constructed, simplified;
  expect_certified_map(out / "construct", &constructed);
  expect_certified_map(out / "simplify", &simplified);
  EXPECT_EQ(constructed, simplified);

  // The final hex mesh: about the hexes asked for, none inverted, no boundary crossing.
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  EXPECT_GT(hex.num_cells(), 3500);
  EXPECT_LT(hex.num_cells(), 6500);
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(hex);
  EXPECT_EQ(sj.inverted + sj.invalid, 0);
  EXPECT_GT(sj.min, 0.0);
  const optimize::FoldoverReport folds = optimize::check_foldover(hex);
  EXPECT_TRUE(folds.ok()) << folds.reason();

  // Within the bound: the symmetric Hausdorff distance from the files, and a vertex-sampled
  // distance both ways computed here (a lower bound of the same quantity).
  const core::TriMesh surface = io::read_surface(input);
  const double diagonal = core::bounding_box(surface.points).extent().norm();
  EXPECT_LE(quality::hausdorff_distance(hex, surface).relative, kHausdorffBound);
  const core::QuadMesh quads = core::boundary(hex).surface;
  core::TriMesh hex_boundary;
  hex_boundary.points = quads.points;
  for (const auto& q : quads.cells) {
    hex_boundary.cells.push_back({q[0], q[1], q[2]});
    hex_boundary.cells.push_back({q[0], q[2], q[3]});
  }
  std::vector<core::Vec3> used;
  for (const auto& q : quads.cells)
    for (const int v : q) used.push_back(quads.points[v]);
  EXPECT_LE(farthest_from(used, surface) / diagonal, kHausdorffBound);
  EXPECT_LE(farthest_from(surface.points, hex_boundary) / diagonal, kHausdorffBound);
  fs::remove_all(out);
}

}  // namespace
}  // namespace polycube
