// End-to-end tests of `polycube construct`: the outputs read back and consistent with the report,
// exit code 2 on bad input, exit code 3 when no certified map is reached, and the files
// `--keep-failed` promises (README: the best attempt as uncertified_*.mesh), read back.
#include "core/polycube_map.h"
#include "core/topology.h"
#include "core/types.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "structure/structure.h"
#include "structure/validate.h"

#include "cli/run_cli.h"
#include "cli/surface_file.h"
#include "support/shapes.h"
#include "support/scratch.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace polycube {
namespace {

namespace fs = std::filesystem;

using test::CliResult;

fs::path temp_dir(const std::string& name) { return test::scratch_dir("polycube_construct_cli_test_" + name); }

using test::write_surface;

//! `polycube construct IN -o OUT <more>` with quoted paths.
CliResult construct(const fs::path& in, const fs::path& out, const std::string& more = "") {
  return test::run_cli("construct \"" + in.string() + "\" -o \"" + out.string() + "\" " + more);
}

//! A closed, manifold surface of 4 triangles: no labeling of 4 triangles has the 6 charts a
//! polycube needs at least, so no construction can succeed.
core::TriMesh tetrahedron() {
  core::TriMesh t;
  t.points = {core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)};
  t.cells = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return t;
}

//! The tets of a `.mesh` file's `Triangles` block checked against its tets: the boundary faces
//! (faces of exactly one tet), each once, with one label in 0..5 each.
void expect_labeled_boundary(const core::MeshData& d, const std::string& what) {
  ASSERT_EQ(d.triangle_labels.size(), d.triangles.size()) << what;
  for (int l : d.triangle_labels) {
    EXPECT_GE(l, 0) << what;
    EXPECT_LE(l, 5) << what;
  }
  const core::TetBoundary b = core::boundary(core::tets_of(d));
  std::vector<std::array<int, 3>> expected, got;
  for (const auto& f : b.surface.cells) {
    std::array<int, 3> k{b.vertex_map[f[0]], b.vertex_map[f[1]], b.vertex_map[f[2]]};
    std::sort(k.begin(), k.end());
    expected.push_back(k);
  }
  for (const auto& t : d.triangles) {
    std::array<int, 3> k{t[0], t[1], t[2]};
    std::sort(k.begin(), k.end());
    got.push_back(k);
  }
  std::sort(expected.begin(), expected.end());
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, expected) << what << ": the Triangles block is not the tets' boundary";
}

//! On an axis-aligned box every boundary triangle's label is the axis of its outward model normal
//! (the labeling of a box has fidelity 0), for every triangle of the Triangles block.
void expect_box_labels(const core::MeshData& d, const std::string& what) {
  ASSERT_EQ(d.triangle_labels.size(), d.triangles.size()) << what;
  std::set<int> used;
  for (std::size_t i = 0; i < d.triangles.size(); ++i) {
    const auto& t = d.triangles[i];
    const core::Vec3 n = (d.points[t[1]] - d.points[t[0]]).cross(d.points[t[2]] - d.points[t[0]]);
    EXPECT_EQ(d.triangle_labels[i], core::dominant_axis_label(n)) << what << ": triangle " << i;
    used.insert(d.triangle_labels[i]);
  }
  EXPECT_EQ(used.size(), 6u) << what;
}

TEST(ConstructCli, BoxWritesACertifiedMapThatReadsBackWithTheReportsCounts) {
  const fs::path dir = temp_dir("box");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult r = construct(dir / "box.obj", dir / "out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const core::PolycubeMap map = io::read_polycube_map(dir / "out" / "model.mesh", dir / "out" / "polycube.mesh");
  const structure::MapDiagnosis d = structure::diagnose_map(map);
  EXPECT_TRUE(d.valid()) << (d.failures.empty() ? "" : d.failures.front());
  std::ifstream jf(dir / "out" / "report.json");
  const auto j = nlohmann::json::parse(jf);
  EXPECT_TRUE(j["certified"].get<bool>());
  EXPECT_EQ(j["tets"].get<int>(), map.num_tets());
  EXPECT_EQ(j["vertices"].get<int>(), map.num_vertices());
  const structure::PolycubeStructure s = structure::extract_structure(map);
  EXPECT_EQ(static_cast<int>(s.charts.size()), 6);  // a box
  EXPECT_EQ(static_cast<int>(s.corners.size()), 8);
  EXPECT_EQ(j["charts"], 6);
  EXPECT_EQ(j["corners"], 8);
  // labeling.txt: one label per Triangles entry of model.mesh, the same as its references.
  const core::MeshData model = io::read_mesh(dir / "out" / "model.mesh");
  expect_labeled_boundary(model, "model.mesh");
  expect_box_labels(model, "model.mesh");
  std::ifstream lf(dir / "out" / "labeling.txt");
  std::vector<int> labels;
  for (int l; lf >> l;) labels.push_back(l);
  EXPECT_EQ(labels, model.triangle_labels);
  EXPECT_EQ(j["boundary_triangles"].get<std::size_t>(), labels.size());
}

// A solid with a cavity: the inner shell is a second boundary, with its own 6 charts and 8
// corners, and the map is certified (it used to stop at TetGen filling the cavity).
TEST(ConstructCli, ABoxWithACavityMapsBothShells) {
  const fs::path dir = temp_dir("cavity");
  core::TriMesh solid = test::make_box(3.0, 3.0, 3.0, 3);
  const core::TriMesh inner = test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(1, 1, 1));
  const int off = solid.num_points();
  for (const auto& p : inner.points) solid.points.push_back(p);
  for (const auto& t : inner.cells) solid.cells.push_back({t[0] + off, t[2] + off, t[1] + off});
  write_surface(dir / "cavity.obj", solid);
  const CliResult r = construct(dir / "cavity.obj", dir / "out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const core::PolycubeMap map = io::read_polycube_map(dir / "out" / "model.mesh", dir / "out" / "polycube.mesh");
  const structure::MapDiagnosis d = structure::diagnose_map(map);
  EXPECT_TRUE(d.valid()) << (d.failures.empty() ? "" : d.failures.front());
  const structure::PolycubeStructure s = structure::extract_structure(map);
  EXPECT_EQ(static_cast<int>(s.charts.size()), 12);
  EXPECT_EQ(static_cast<int>(s.corners.size()), 16);
}

TEST(ConstructCli, NoPossibleLabelingExitsThreeWithTheReasonAndWritesNothing) {
  const fs::path dir = temp_dir("tetrahedron");
  write_surface(dir / "tetrahedron.obj", tetrahedron());
  // Four triangles cannot be labeled; without the coarse surface's refinement, nothing is tried.
  const CliResult r = construct(dir / "tetrahedron.obj", dir / "out",
                                "--coarse-edge-ratio 0 --keep-failed \"" + (dir / "kept").string() + "\"");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("no valid polycube labeling"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  // One short line: the count, the first reason, not every attempt's (they are alike here).
  EXPECT_LT(r.err.size(), 400u) << r.err;
  EXPECT_NE(r.err.find("attempt(s) failed; the first: compactness 1: "), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // No attempt got as far as a deformation: there is no attempt to keep (README), not even a folder.
  EXPECT_FALSE(fs::exists(dir / "kept"));
}

TEST(ConstructCli, BadInputExitsTwoWithOneLineAndWritesNothing) {
  const fs::path dir = temp_dir("bad");
  auto open = test::make_box(1.0, 1.0, 1.0, 2);
  open.cells.pop_back();
  write_surface(dir / "open.obj", open);
  std::ofstream(dir / "garbage.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  auto two = test::make_box(1.0, 1.0, 1.0, 1);
  const auto b = test::make_box(1.0, 1.0, 1.0, 1, core::Vec3(0.5, 0.4, 0.3));
  const int off = two.num_points();
  for (const auto& p : b.points) two.points.push_back(p);
  for (const auto& t : b.cells) two.cells.push_back({t[0] + off, t[1] + off, t[2] + off});
  write_surface(dir / "two.obj", two);
  for (const auto& [file, says] : std::vector<std::pair<std::string, std::string>>{
           {"open.obj", "open"}, {"garbage.obj", "garbage.obj"}, {"two.obj", "self-intersect"}, {"missing.obj", "missing.obj"}}) {
    SCOPED_TRACE(file);
    const CliResult r = construct(dir / file, dir / "out", "--keep-failed \"" + (dir / "kept").string() + "\"");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "out"));
    EXPECT_FALSE(fs::exists(dir / "kept"));
  }
}

// No small input makes the certification fail reliably (every small shape tried certifies, even
// with --iterations 1 --refine-rounds 0 --no-boundary-first): the hidden
// `--inject-failure certify` reports the (certified) result as not certified, so what is tested
// is what --keep-failed writes and the exit code, not why an attempt fails.
TEST(ConstructCli, UncertifiedExitsThreeAndKeepFailedWritesTheAttemptReadably) {
  const fs::path dir = temp_dir("uncertified");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const fs::path kept = dir / "kept";
  const CliResult r =
      construct(dir / "box.obj", dir / "out", "--inject-failure certify --keep-failed \"" + kept.string() + "\"");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("polycube: error: polycube map not certified"), std::string::npos) << r.err;
  // Never written as a result.
  EXPECT_FALSE(fs::exists(dir / "out"));
  // The attempt, for diagnosis: two tet meshes with identical Tetrahedra blocks, the boundary
  // triangles labeled, the same in both files.
  ASSERT_TRUE(fs::exists(kept / "uncertified_model.mesh"));
  ASSERT_TRUE(fs::exists(kept / "uncertified_polycube.mesh"));
  const core::PolycubeMap map =
      io::read_polycube_map(kept / "uncertified_model.mesh", kept / "uncertified_polycube.mesh");
  EXPECT_GT(map.num_tets(), 0);
  const core::MeshData model = io::read_mesh(kept / "uncertified_model.mesh");
  const core::MeshData cube = io::read_mesh(kept / "uncertified_polycube.mesh");
  expect_labeled_boundary(model, "uncertified_model.mesh");
  expect_box_labels(model, "uncertified_model.mesh");
  EXPECT_EQ(model.triangles, cube.triangles);
  EXPECT_EQ(model.triangle_labels, cube.triangle_labels);
  // The model positions are the input box's: its bounding box.
  const core::BoundingBox bb = core::bounding_box(map.model);
  EXPECT_NEAR((bb.min - core::Vec3(0, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((bb.max - core::Vec3(1, 2, 1.5)).norm(), 0.0, 1e-12);
  // Without --keep-failed: the same exit code, nothing written.
  const CliResult plain = construct(dir / "box.obj", dir / "out2", "--inject-failure certify");
  EXPECT_EQ(plain.exit_code, 3) << plain.err;
  EXPECT_FALSE(fs::exists(dir / "out2"));
}

//! report.json of a construct output folder.
nlohmann::json construct_report(const fs::path& out) {
  std::ifstream jf(out / "report.json");
  return nlohmann::json::parse(jf);
}

//! A certified map reads back valid from an output folder.
void expect_certified_map(const fs::path& out) {
  const core::PolycubeMap map = io::read_polycube_map(out / "model.mesh", out / "polycube.mesh");
  const structure::MapDiagnosis d = structure::diagnose_map(map);
  EXPECT_TRUE(d.valid()) << (d.failures.empty() ? "" : d.failures.front());
}

//! Construct the box with `injection`: the map must come from the second attempt, certified,
//! the report naming it and, in `tried`, the first attempt's failure; stderr announcing both.
void expect_second_attempt_kept(const std::string& name, const std::string& injection,
                                const std::string& tried) {
  const fs::path dir = temp_dir(name);
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult r = construct(dir / "box.obj", dir / "out", "--inject-failure " + injection);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_certified_map(dir / "out");
  const auto j = construct_report(dir / "out");
  EXPECT_TRUE(j["certified"].get<bool>());
  EXPECT_EQ(j["attempts"].get<int>(), 2);
  EXPECT_NE(j["attempt"].get<std::string>(), "compactness 1");
  EXPECT_EQ(j["tried"].get<std::string>(), tried);
  EXPECT_NE(r.err.find("construct attempt 1/"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("construct attempt 2/"), std::string::npos) << r.err;
}

// Every small shape certifies in the first attempt, so `--inject-failure attempt-1` counts the
// first one as failed: the construction goes on with the next attempt of its plan, says so on
// stderr, and the report names the attempt that gave the map and what was tried before.
TEST(ConstructCli, AFailedAttemptFallsBackToTheNextAndTheReportNamesBoth) {
  expect_second_attempt_kept("fallback_attempt", "attempt-1", "compactness 1: injected failure");
}

// The fallbacks' labelings (among them the pre-deformed ones) are made only when the first
// attempt fails: a box that certifies at once spends no time pre-deforming; with its first
// attempt's failure injected, the others are labeled, the pre-deformation with them.
TEST(ConstructCli, TheFallbacksAreLabeledOnlyWhenTheFirstAttemptFails) {
  const fs::path dir = temp_dir("lazy_fallbacks");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult first = construct(dir / "box.obj", dir / "first", "");
  ASSERT_EQ(first.exit_code, 0) << first.err;
  const auto j1 = construct_report(dir / "first");
  EXPECT_EQ(j1["attempts"].get<int>(), 1);
  EXPECT_EQ(j1["seconds"]["predeform"].get<double>(), 0.0);
  const CliResult second = construct(dir / "box.obj", dir / "second", "--inject-failure attempt-1");
  ASSERT_EQ(second.exit_code, 0) << second.err;
  const auto j2 = construct_report(dir / "second");
  EXPECT_EQ(j2["attempts"].get<int>(), 2);
  EXPECT_GT(j2["seconds"]["predeform"].get<double>(), 0.0);
}

// An attempt whose tets are all positive and whose triangles all face their labels can still
// fail the certification (its polycube boundary crossing itself elsewhere). The plan then goes on
// to the next attempt instead of stopping with that one: `--inject-failure uncertified-attempt-1`
// refuses the first attempt's certificate.
TEST(ConstructCli, AnAttemptThatFailsCertificationFallsBackToTheNext) {
  expect_second_attempt_kept("fallback_uncertified", "uncertified-attempt-1",
                             "compactness 1: not certified: injected failure");
}

// Past the time limit no new attempt starts: the best attempt so far (here the first, whose
// failure was injected but whose map is valid) is certified and kept, and the report says the
// budget ran out.
TEST(ConstructCli, PastTheTimeLimitTheBestAttemptSoFarIsKept) {
  const fs::path dir = temp_dir("budget");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult r = construct(dir / "box.obj", dir / "out", "--inject-failure attempt-1 --time-limit 1e-6");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_certified_map(dir / "out");
  const auto j = construct_report(dir / "out");
  EXPECT_EQ(j["attempts"].get<int>(), 1);
  EXPECT_EQ(j["attempt"].get<std::string>(), "compactness 1");
  EXPECT_NE(j["tried"].get<std::string>().find("time limit of 1e-06 s reached after 1 attempt(s)"), std::string::npos)
      << j["tried"];
  EXPECT_EQ(r.err.find("construct attempt 2/"), std::string::npos) << r.err;
}

// A surface whose every attempt fails certification: the message names the alpha wrap as a
// remedy (it closes slits thinner than the tets, where homer's attempts stay folded), unless the
// surface is the wrap already. The first attempt's certificate is refused and the budget lets
// no other start.
TEST(ConstructCli, AnUncertifiedSurfaceNamesTheWrapAsTheRemedyUnlessItIsTheWrap) {
  const fs::path dir = temp_dir("wrap_remedy");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const std::string refused = "--inject-failure uncertified-attempt-1 --time-limit 1e-6";
  const std::string remedy = "may construct after --repair wrap";
  const CliResult plain = construct(dir / "box.obj", dir / "out", refused);
  EXPECT_EQ(plain.exit_code, 3) << plain.err;
  EXPECT_NE(plain.err.find("polycube map not certified"), std::string::npos) << plain.err;
  EXPECT_NE(plain.err.find(remedy), std::string::npos) << plain.err;
  const CliResult wrapped = construct(dir / "box.obj", dir / "out_wrapped", refused + " --repair wrap --wrap-alpha 0.05");
  EXPECT_EQ(wrapped.exit_code, 3) << wrapped.err;
  EXPECT_NE(wrapped.err.find("polycube map not certified"), std::string::npos) << wrapped.err;
  EXPECT_EQ(wrapped.err.find(remedy), std::string::npos) << wrapped.err;
}

//! Options (lines starting with "  -") in a --help text.
std::vector<std::string> listed_options(const std::string& help) {
  std::vector<std::string> options;
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("  -", 0) == 0) options.push_back(line.substr(2, line.find_first_of(" {", 2) - 2));
  return options;
}

// A surface finer than --max-triangles is decimated before the construction, and the report and
// the summary say so; the map's boundary is the decimated surface (refined only by the
// construction's own splits), within the tolerance of the input. (A surface under the count is
// left alone: FineSurface tests in test_construct.cpp.)
TEST(ConstructCli, ASurfaceFinerThanMaxTrianglesIsDecimatedAndTheReportSaysSo) {
  const fs::path dir = temp_dir("decimate");
  const core::TriMesh dense = test::make_sphere(1.0, 32, 64);  // 3,968 triangles
  write_surface(dir / "sphere.obj", dense);
  const CliResult r =
      construct(dir / "sphere.obj", dir / "out", "--max-triangles 3000 --decimate-to 2000 --decimation-tolerance 0.005");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("of the surface decimated from 3968 to"), std::string::npos) << r.out;
  std::ifstream jf(dir / "out" / "report.json");
  const auto j = nlohmann::json::parse(jf);
  EXPECT_TRUE(j["certified"].get<bool>());
  ASSERT_TRUE(j["surface_decimated"].is_object()) << j.dump(2);
  EXPECT_EQ(j["surface_decimated"]["triangles_before"].get<int>(), dense.num_cells());
  const int after = j["surface_decimated"]["triangles_after"].get<int>();
  EXPECT_LE(after, 2000);
  EXPECT_GT(after, 0);
  EXPECT_NEAR(j["surface_decimated"]["tolerance"].get<double>(), 0.005 * core::bounding_box(dense.points).diagonal(),
              1e-9);
  const core::PolycubeMap map = io::read_polycube_map(dir / "out" / "model.mesh", dir / "out" / "polycube.mesh");
  EXPECT_GE(static_cast<int>(core::boundary(map.model_mesh()).surface.num_cells()), after);
  const double tolerance = j["surface_decimated"]["tolerance"].get<double>();
  for (const core::Vec3& p : map.model_mesh().points) EXPECT_LE(p.norm(), 1.0 + tolerance) << p.transpose();
}

TEST(ConstructCli, HelpShowsTheUserOptionsAndHelpExpertTheRest) {
  const CliResult user = test::run_cli("construct --help");
  ASSERT_EQ(user.exit_code, 0) << user.err;
  const std::vector<std::string> shown = listed_options(user.out);
  EXPECT_LE(shown.size(), 12u) << user.out;
  for (const char* o : {"--compactness", "--predeform", "--time-limit", "--keep-failed", "--max-triangles", "--help-expert"})
    EXPECT_NE(user.out.find(o), std::string::npos) << o;
  for (const char* o : {"--iterations", "--flow", "--untangle-first", "--inject-failure"})
    EXPECT_EQ(user.out.find(o), std::string::npos) << o << " is an expert or test option";
  EXPECT_NE(user.out.find("--help-expert"), std::string::npos);
  const CliResult expert = test::run_cli("construct --help-expert");
  ASSERT_EQ(expert.exit_code, 0) << expert.err;
  EXPECT_NE(expert.out.find("Expert options:"), std::string::npos);
  for (const char* o : {"--iterations", "--volume-weight", "--refine-rounds", "--no-boundary-first", "--untangle-first",
                        "--flow", "--predeform-retry", "--straighten", "--unfold-moves", "--quality", "--decimate-to",
                        "--decimation-tolerance"})
    EXPECT_NE(expert.out.find(o), std::string::npos) << o;
  EXPECT_EQ(expert.out.find("--inject-failure"), std::string::npos);
  EXPECT_GT(listed_options(expert.out).size(), shown.size());
}

}  // namespace
}  // namespace polycube
