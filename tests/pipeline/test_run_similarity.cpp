// The same shape gives the same result wherever it sits and in whatever unit it comes (issue 24,
// scale and position): `polycube run` on one solid scaled by 1e-6 and 1e6 and moved by 1e7 along
// an axis gives the same structure (charts, corners, domains), the same number of hexes, and the
// same quality and relative distance to the input within small tolerances. Before, the
// simplification's lattice was anchored at the origin of the input's coordinates, so a moved
// model rounded its corners differently (500 hexes, mSJ 0.854 instead of 534 and 0.907 for the
// l-bracket at 500 hexes); the tolerances of the gridding and of fabrication were absolute.
#include "cli/run_cli.h"
#include "cli/surface_file.h"
#include "core/types.h"
#include "io/mesh_io.h"
#include "support/scratch.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace polycube {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) { return test::scratch_dir(name); }

nlohmann::json run_and_report(const fs::path& in, const fs::path& out) {
  const auto r = test::run_cli(
      fmt::format("run \"{}\" -o \"{}\" --hexes 400 --padding none", in.string(), out.string()));
  EXPECT_EQ(r.exit_code, 0) << in << ": " << r.err;
  std::ifstream f(out / "report.json");
  std::stringstream ss;
  ss << f.rdbuf();
  return nlohmann::json::parse(ss.str());
}

TEST(RunSimilarity, ScaledByAMillionthOrAMillionOrMovedFarTheResultIsTheSame) {
  const fs::path dir = temp_dir("run_similarity");
  const auto sample = test::run_cli(
      fmt::format("sample l-bracket --edge-length 4 -o \"{}\"", (dir / "shape.obj").string()));
  ASSERT_EQ(sample.exit_code, 0) << sample.err;
  const core::TriMesh shape = core::triangles_of(io::read_mesh(dir / "shape.obj"));
  const nlohmann::json base = run_and_report(dir / "shape.obj", dir / "base");
  ASSERT_EQ(base["status"], "ok");

  struct Similarity {
    const char* name;
    double scale;
    core::Vec3 move;
  };
  for (const Similarity& s : {Similarity{"micro", 1e-6, core::Vec3::Zero()}, Similarity{"mega", 1e6, core::Vec3::Zero()},
                              Similarity{"moved", 1.0, core::Vec3(1e7, 0, 0)}}) {
    core::TriMesh m = shape;
    for (core::Vec3& p : m.points) p = s.scale * p + s.move;
    const fs::path in = dir / (std::string(s.name) + ".obj");
    test::write_surface(in, m);
    const nlohmann::json j = run_and_report(in, dir / s.name);
    SCOPED_TRACE(s.name);
    ASSERT_EQ(j["status"], "ok");
    for (const char* key : {"charts", "corners", "hex_domains_before", "hex_domains_after", "hexes"})
      EXPECT_EQ(j[key], base[key]) << key;
    EXPECT_EQ(j["final"]["inverted"], 0);
    EXPECT_EQ(j["final"]["domains"], base["final"]["domains"]);
    EXPECT_NEAR(j["final"]["msj"].get<double>(), base["final"]["msj"].get<double>(), 0.02);
    EXPECT_NEAR(j["final"]["asj"].get<double>(), base["final"]["asj"].get<double>(), 0.005);
    EXPECT_NEAR(j["final"]["hausdorff_relative"].get<double>(), base["final"]["hausdorff_relative"].get<double>(),
                0.001);
    // The mesh sits where the input does, in its units.
    const core::BoundingBox want = core::bounding_box(m.points);
    const core::BoundingBox got = core::bounding_box(io::read_mesh(dir / s.name / "hex_optimized.mesh").points);
    EXPECT_LT((got.min - want.min).norm(), 0.01 * want.diagonal());
    EXPECT_LT((got.max - want.max).norm(), 0.01 * want.diagonal());
  }
}

}  // namespace
}  // namespace polycube
