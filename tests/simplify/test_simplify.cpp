// The whole simplification: fitting, certification, determinism, and the `polycube simplify`
// command.
#include "simplify/simplify.h"
#include "core/errors.h"
#include "io/polycube_map_io.h"
#include "structure/structure.h"
#include "structure/validate.h"
#include "cli/run_cli.h"
#include "polycube_fixtures.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace polycube {
namespace {

namespace fs = std::filesystem;

TEST(Simplify, CombIsFittedCertifiedAndCoarser) {
  const auto map = test::comb(0.1);
  simplify::SimplifyOptions o;
  o.align.scale = 10.0;
  const auto r = simplify::simplify_map(map, o);
  ASSERT_TRUE(r.fit.certified) << (r.fit.failures.empty() ? "" : r.fit.failures.front());
  EXPECT_LT(r.after.hex_domains, r.before.hex_domains);
  EXPECT_LT(r.after.quad_domains, r.before.quad_domains);
  // certified independently: valid map, same structure, integer corners, model untouched
  EXPECT_NO_THROW(structure::validate_map(r.fit.map));
  EXPECT_EQ(r.fit.map.model, map.model);
  EXPECT_EQ(r.fit.map.tets, map.tets);
  const auto s0 = structure::extract_structure(map);
  const auto s1 = structure::extract_structure(r.fit.map);
  EXPECT_TRUE(simplify::compare_structures(s0, s1).empty());
  for (const auto& c : s1.corners)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(c.position[a], std::round(c.position[a]));
  // the two notch floors are one plane
  double y_floor1 = -1, y_floor2 = -2;
  for (std::size_t c = 0; c < s0.corners.size(); ++c) {
    if (s0.corners[c].position == core::Vec3(2, 1.0, 0)) y_floor1 = s1.corners[c].position.y();
    if (s0.corners[c].position == core::Vec3(3, 1.1, 0)) y_floor2 = s1.corners[c].position.y();
  }
  EXPECT_EQ(y_floor1, y_floor2);
}

// The fallbacks (simplify.h), reached by counting the first steps as failed: each step gives
// up alignments, so the coarsening lost shows in #D; every step's map is certified.
TEST(Simplify, FallbackStepsGiveUpAlignmentsAndSayWhatWasLost) {
  const auto map = test::comb(0.1);
  simplify::SimplifyOptions o;
  o.align.scale = 10.0;
  const auto aligned = simplify::simplify_map(map, o);
  ASSERT_TRUE(aligned.fit.certified);
  EXPECT_EQ(aligned.step, simplify::SimplifyStep::Aligned);
  EXPECT_TRUE(aligned.tried.empty());

  o.inject_failed_steps = 1;  // nothing inverted to point at: a single alignment iteration
  const auto fewer = simplify::simplify_map(map, o);
  ASSERT_TRUE(fewer.fit.certified);
  EXPECT_EQ(fewer.step, simplify::SimplifyStep::FewerAlignments);
  ASSERT_EQ(fewer.tried.size(), 1u);
  EXPECT_EQ(fewer.tried[0], "aligned: injected failure");
  EXPECT_EQ(fewer.alignment.iterations.size(), 1u);
  EXPECT_EQ(fewer.alignment.planes_after[1], 4);  // the notch floors stay apart (see LambdaMinOne...)
  EXPECT_GT(fewer.after.hex_domains, aligned.after.hex_domains);

  o.inject_failed_steps = 2;
  const auto unaligned = simplify::simplify_map(map, o);
  ASSERT_TRUE(unaligned.fit.certified);
  EXPECT_EQ(unaligned.step, simplify::SimplifyStep::Unaligned);
  EXPECT_EQ(unaligned.tried.size(), 2u);
  EXPECT_TRUE(unaligned.alignment.aligned.empty());
  EXPECT_EQ(unaligned.after.hex_domains, unaligned.before.hex_domains);
  EXPECT_NO_THROW(structure::validate_map(unaligned.fit.map));

  o.inject_failed_steps = 3;
  const auto none = simplify::simplify_map(map, o);
  EXPECT_FALSE(none.fit.certified);
  EXPECT_EQ(none.step, simplify::SimplifyStep::None);
  EXPECT_EQ(none.tried.size(), 3u);

  o.inject_failed_steps = 1;
  o.fallbacks = false;
  const auto off = simplify::simplify_map(map, o);
  EXPECT_FALSE(off.fit.certified);
  EXPECT_EQ(off.step, simplify::SimplifyStep::None);
  EXPECT_EQ(off.tried.size(), 1u);
}

TEST(Simplify, DeterministicIncludingTheFit) {
  const auto map = test::grid_polycube({0, 1, 2, 3, 4, 5}, {0, 1.0, 1.1, 3}, {0, 1}, [](int i, int j, int) { return i == 1 ? j == 0 : i == 3 ? j <= 1 : true; }, [](const core::Vec3& p) { return core::Vec3(p.x() + 0.1 * std::sin(p.y()), p.y() * (1 + 0.05 * p.x()), p.z() + 0.1 * p.x() * p.y()); });
  simplify::SimplifyOptions o;
  o.align.scale = 10.0;
  const auto r1 = simplify::simplify_map(map, o);
  const auto r2 = simplify::simplify_map(map, o);
  EXPECT_EQ(r1.fit.map.polycube, r2.fit.map.polycube);
  EXPECT_EQ(r1.alignment.corners, r2.alignment.corners);
  EXPECT_EQ(r1.after.hex_domains, r2.after.hex_domains);
}

TEST(Simplify, InvalidMapIsRefused) {
  auto map = test::comb(0.1);
  std::swap(map.tets[0][0], map.tets[0][1]);  // inverted tet
  EXPECT_THROW(simplify::simplify_map(map), core::InputError);
}

class SimplifyCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) / ("pc_simplify_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    io::write_polycube_map(dir_ / "model.mesh", dir_ / "polycube.mesh", test::comb(0.1));
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(SimplifyCli, WritesTheCertifiedMapAndReport) {
  const auto out = dir_ / "out";
  const auto r = test::run_cli("simplify \"" + (dir_ / "model.mesh").string() + "\" \"" + (dir_ / "polycube.mesh").string() +
                               "\" -o \"" + out.string() + "\" --scale 10 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out / "model.mesh"));
  ASSERT_TRUE(fs::exists(out / "polycube.mesh"));
  std::ifstream in(out / "report.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["corners"].get<int>(), 24);
  EXPECT_LT(j["domains"]["hex_after"].get<int>(), j["domains"]["hex_before"].get<int>());
  EXPECT_TRUE(j["fit"]["certified"].get<bool>());
  const auto m = io::read_polycube_map(out / "model.mesh", out / "polycube.mesh");
  EXPECT_NO_THROW(structure::validate_map(m));
  // stdout (--json) is the same report
  const auto js = nlohmann::json::parse(r.out);
  EXPECT_EQ(js["domains"], j["domains"]);
}

TEST_F(SimplifyCli, MismatchedFilesAreBadInput) {
  io::write_polycube_map(dir_ / "m2.mesh", dir_ / "p2.mesh", test::c_with_bump(0.1));
  const auto r = test::run_cli("simplify \"" + (dir_ / "model.mesh").string() + "\" \"" + (dir_ / "p2.mesh").string() +
                               "\" -o \"" + (dir_ / "bad").string() + "\"");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad" / "model.mesh"));
}

}  // namespace
}  // namespace polycube
