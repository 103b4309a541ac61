// End-to-end tests of `polycube run`: every output read back with the project's readers and
// checked against report.json and against what the shape must give; exit codes and what is kept
// when each stage fails; refusal of bad input before any heavy work; determinism.
#include "core/polycube_map.h"
#include "core/topology.h"
#include "core/types.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "quality/domains.h"
#include "quality/scaled_jacobian.h"
#include "samples/solid.h"
#include "structure/structure.h"
#include "structure/validate.h"

#include "cli/run_cli.h"
#include "cli/surface_file.h"
#include "support/shapes.h"
#include "support/scratch.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
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

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

fs::path temp_dir(const std::string& name) { return test::scratch_dir("polycube_run_test_" + name); }

CliResult run(const std::string& args) { return test::run_cli("run " + args); }

//! `polycube run IN -o OUT <more>` with quoted paths.
CliResult run(const fs::path& in, const fs::path& out, const std::string& more) {
  std::string args = "\"";  // appended, not "..." + std::string&& (a false -Wrestrict of GCC 12)
  args += in.string();
  args += "\" -o \"";
  args += out.string();
  args += "\" ";
  args += more;
  return run(args);
}

using test::write_surface;

nlohmann::json read_report(const fs::path& out) { return nlohmann::json::parse(slurp(out / "report.json")); }

//! The cell field `name` of a mesh read from a file (empty when absent).
std::vector<double> cell_field(const core::MeshData& d, const std::string& name) {
  for (const auto& f : d.cell_data)
    if (f.name == name) return f.values;
  return {};
}

// What each stage writes, from pipeline.h's list of the output folder.
struct StageFiles {
  std::string stage;
  std::vector<std::string> files;
};
const std::vector<StageFiles> kStageFiles = {
    {"construct", {"construct/model.mesh", "construct/polycube.mesh"}},
    {"simplify", {"simplify/model.mesh", "simplify/polycube.mesh"}},
    {"hexmesh", {"hex.mesh", "quad.vtk"}},
    {"optimize", {"hex_optimized.mesh"}},
    {"quality", {"hex_quality.vtk"}},
};

//! A run stopped at `stage` with exit code `code`: the stage named on stderr and in report.json,
//! the stages before it recorded as successful and none after it, every file of the stages that
//! ran before it (`ran`, in order, "input" first) present and listed, no file of the failing or
//! later stages.
void expect_stopped_at(const CliResult& r, const fs::path& out, const std::string& stage, int code,
                       const std::vector<std::string>& ran) {
  EXPECT_EQ(r.exit_code, code) << r.err;
  EXPECT_NE(r.err.find("polycube: error: stage " + stage + " failed: "), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(out / "report.json"));
  const auto j = read_report(out);
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failure"]["stage"], stage);
  for (const auto& f : j["files"]) EXPECT_TRUE(fs::path(f.get<std::string>()).is_relative()) << f;  // to the report
  const std::string reason = j["failure"]["reason"].get<std::string>();
  EXPECT_FALSE(reason.empty());
  EXPECT_NE(r.err.find(reason), std::string::npos) << "the reason of report.json is not on stderr: " << r.err;
  // stages: those before, all ok, then the failing one, and nothing after it
  const auto& stages = j["stages"];
  ASSERT_EQ(stages.size(), ran.size() + 1) << stages.dump();
  for (std::size_t i = 0; i < ran.size(); ++i) {
    EXPECT_EQ(stages[i]["stage"], ran[i]);
    EXPECT_TRUE(stages[i]["ok"].get<bool>()) << ran[i];
  }
  EXPECT_EQ(stages.back()["stage"], stage);
  EXPECT_FALSE(stages.back()["ok"].get<bool>());
  // files: the earlier stages' present and listed (and nothing else listed), the rest absent
  std::set<std::string> listed;
  for (const auto& f : j["files"]) listed.insert((out / f.get<std::string>()).lexically_normal().string());
  std::set<std::string> kept;
  for (const auto& sf : kStageFiles) {
    const bool before = std::find(ran.begin(), ran.end(), sf.stage) != ran.end();
    for (const auto& f : sf.files) {
      if (before) {
        EXPECT_TRUE(fs::exists(out / f)) << f << " of stage " << sf.stage << " is not kept";
        kept.insert((out / f).lexically_normal().string());
      } else {
        EXPECT_FALSE(fs::exists(out / f)) << f << " written although stage " << sf.stage << " did not succeed";
      }
    }
  }
  EXPECT_EQ(listed, kept) << j["files"].dump();
}

//! The map under `dir` read back: a valid polycube map (exact orientation in both spaces,
//! axis-aligned closed boundary) with the report's counts.
core::PolycubeMap expect_valid_map(const fs::path& dir, const nlohmann::json& j) {
  const core::PolycubeMap map = io::read_polycube_map(dir / "model.mesh", dir / "polycube.mesh");
  const structure::MapDiagnosis d = structure::diagnose_map(map);
  EXPECT_TRUE(d.valid()) << dir << ": " << (d.failures.empty() ? "" : d.failures.front());
  EXPECT_EQ(map.num_tets(), j["tets"].get<int>()) << dir;
  const structure::PolycubeStructure s = structure::extract_structure(map);
  EXPECT_EQ(static_cast<int>(s.charts.size()), j["charts"].get<int>()) << dir;
  EXPECT_EQ(static_cast<int>(s.corners.size()), j["corners"].get<int>()) << dir;
  return map;
}

class RunBox : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = temp_dir("box");
    write_surface(dir_ / "box.obj", test::make_box(1.0, 2.0, 1.5, 4));
    result_ = run(fmt::format("\"{}\" -o \"{}\" --hexes 3000", (dir_ / "box.obj").string(), (dir_ / "out").string()));
  }
  static fs::path dir_;
  static CliResult result_;
};
fs::path RunBox::dir_;
CliResult RunBox::result_;

TEST_F(RunBox, EveryStageSucceedsAndTheSummaryNamesThem) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  for (const char* stage : {"construct", "simplify", "hexmesh", "optimize", "pad", "quality", "total"})
    EXPECT_NE(result_.out.find(std::string("| ") + stage + " |"), std::string::npos) << result_.out;
}

TEST_F(RunBox, ReportRecordsEveryStageAndListsExactlyTheFilesWritten) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = read_report(out);
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_FALSE(j.contains("failure"));
  // The report says which program made it and how it was called.
  EXPECT_NE(test::run_cli("--version").out.find("polycube " + j["version"].get<std::string>()), std::string::npos);
  EXPECT_NE(j["command"].get<std::string>().find(" run "), std::string::npos) << j["command"];
  EXPECT_NE(j["command"].get<std::string>().find("--hexes 3000"), std::string::npos) << j["command"];
  // Selective padding by default: a box's map does not distort it, so nothing is padded.
  const std::vector<std::string> order{"input", "construct", "simplify", "hexmesh", "optimize", "pad", "quality"};
  EXPECT_EQ(j["padding"]["applied"], "none (nothing to pad)");
  EXPECT_EQ(j["padding"]["hard_facets"].get<int>(), 0);
  EXPECT_EQ(j["padding"]["selected_facets"].get<int>(), 0);
  EXPECT_EQ(j["padding"]["plan_solver"], "none (the empty set)");
  EXPECT_TRUE(j["padding"]["plan_optimal"].get<bool>());
  ASSERT_EQ(j["stages"].size(), order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    EXPECT_EQ(j["stages"][i]["stage"], order[i]);
    EXPECT_TRUE(j["stages"][i]["ok"].get<bool>());
    EXPECT_GE(j["stages"][i]["seconds"].get<double>(), 0.0);
  }
  std::set<std::string> listed, expected;
  for (const auto& f : j["files"]) listed.insert((out / f.get<std::string>()).lexically_normal().string());
  for (const auto& sf : kStageFiles)
    for (const auto& f : sf.files) {
      EXPECT_TRUE(fs::exists(out / f)) << f;
      expected.insert((out / f).lexically_normal().string());
    }
  EXPECT_EQ(listed, expected) << j["files"].dump();
}

TEST_F(RunBox, BothMapsReadBackValidWithIdenticalTetBlocksAndTheReportsCounts) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = read_report(out);
  // A box: 6 charts meeting at 8 corners, whatever the tet mesh.
  EXPECT_EQ(j["charts"], 6);
  EXPECT_EQ(j["corners"], 8);
  const core::PolycubeMap built = expect_valid_map(out / "construct", j);
  const core::PolycubeMap simplified = expect_valid_map(out / "simplify", j);
  // The simplification moves polycube positions only: same tets, same model positions.
  EXPECT_EQ(simplified.tets, built.tets);
  EXPECT_EQ(simplified.model, built.model);
  // ... and puts every corner on the integer lattice.
  for (const auto& c : structure::extract_structure(simplified).corners)
    for (int a = 0; a < 3; ++a) EXPECT_EQ(c.position[a], std::round(c.position[a])) << "corner at vertex " << c.vertex;
  // The model is the input box [0,1]x[0,2]x[0,1.5]: its bounding box, in both maps.
  const core::Vec3 lo = core::bounding_box(built.model).min, hi = core::bounding_box(built.model).max;
  EXPECT_NEAR((lo - core::Vec3(0, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((hi - core::Vec3(1, 2, 1.5)).norm(), 0.0, 1e-12);
  // A box is one block before and after simplification.
  EXPECT_EQ(j["hex_domains_before"], 1);
  EXPECT_EQ(j["hex_domains_after"], 1);
  EXPECT_EQ(j["quad_domains_after"], 6);
}

TEST_F(RunBox, HexMeshesReadBackWithTheReportsCountsAndQuality) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = read_report(out);
  const core::HexMesh gridded = core::hexes_of(io::read_mesh(out / "hex.mesh"));
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  ASSERT_FALSE(gridded.cells.empty());
  // The optimization moves vertices only.
  EXPECT_EQ(hex.cells, gridded.cells);
  EXPECT_EQ(hex.points.size(), gridded.points.size());
  EXPECT_EQ(static_cast<int>(gridded.cells.size()), j["hexes"].get<int>());
  // The target was 3000 hexes; the simplified box is scaled by an integer, so within a factor 2.
  EXPECT_GT(hex.cells.size(), 1500u);
  EXPECT_LT(hex.cells.size(), 6000u);
  // The gridded figures of the report are those of hex.mesh.
  const quality::ScaledJacobianSummary g = quality::scaled_jacobian(gridded);
  EXPECT_EQ(g.inverted + g.invalid, j["gridded"]["inverted"].get<int>());
  EXPECT_NEAR(g.min, j["gridded"]["msj"].get<double>(), 1e-12);
  EXPECT_NEAR(g.average, j["gridded"]["asj"].get<double>(), 1e-12);
  // The final mesh: every hex positive, the report's figures, one block.
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(hex);
  EXPECT_EQ(sj.inverted, 0);
  EXPECT_EQ(sj.invalid, 0);
  EXPECT_GT(sj.min, 0.0);
  EXPECT_EQ(j["final"]["inverted"].get<int>(), 0);
  EXPECT_NEAR(sj.min, j["final"]["msj"].get<double>(), 1e-12);
  EXPECT_NEAR(sj.average, j["final"]["asj"].get<double>(), 1e-12);
  EXPECT_EQ(quality::hex_domains(hex).domains, 1);
  EXPECT_EQ(j["final"]["domains"], 1);
  EXPECT_LE(j["final"]["hausdorff_relative"].get<double>(), 0.009);
  // The gridded hexes fill the box: volume 1 x 2 x 1.5. The map takes chart planes to the box's
  // faces and polycube edges to its edges, so every boundary lattice point lands on the box's
  // boundary (flat: no chord is lost).
  EXPECT_NEAR(core::signed_volume(core::boundary(gridded).surface), 3.0, 1e-9);
}

TEST_F(RunBox, HexQualityVtkIsTheFinalMeshWithItsQualityAndBlocks) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = read_report(out);
  const core::MeshData vtk = io::read_mesh(out / "hex_quality.vtk");
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  EXPECT_TRUE(vtk.tets.empty() && vtk.quads.empty() && vtk.triangles.empty());
  EXPECT_EQ(vtk.hexes, hex.cells);
  EXPECT_EQ(vtk.points, hex.points);  // both written in the shortest form that reads back exactly
  const std::vector<double> sj = cell_field(vtk, "scaled_jacobian");
  ASSERT_EQ(sj.size(), hex.cells.size());
  const quality::ScaledJacobianSummary mine = quality::scaled_jacobian(hex);
  EXPECT_NEAR(*std::min_element(sj.begin(), sj.end()), mine.min, 1e-12);
  EXPECT_NEAR(*std::min_element(sj.begin(), sj.end()), j["final"]["msj"].get<double>(), 1e-12);
  EXPECT_LE(*std::max_element(sj.begin(), sj.end()), 1.0 + 1e-12);
  const std::vector<double> block = cell_field(vtk, "block_id");
  ASSERT_EQ(block.size(), hex.cells.size());
  EXPECT_EQ(std::set<double>(block.begin(), block.end()).size(), static_cast<std::size_t>(j["final"]["domains"].get<int>()));
}

TEST_F(RunBox, QuadVtkIsTheBoundaryOfTheGriddedMeshWithSixPatches) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path out = dir_ / "out";
  const auto j = read_report(out);
  const core::MeshData vtk = io::read_mesh(out / "quad.vtk");
  EXPECT_TRUE(vtk.hexes.empty() && vtk.tets.empty() && vtk.triangles.empty());
  ASSERT_FALSE(vtk.quads.empty());
  EXPECT_EQ(static_cast<int>(vtk.quads.size()), j["quads"].get<int>());
  // The quad mesh is the lattice's boundary: as many quads as hex.mesh has boundary faces, the
  // same points, a closed surface enclosing the box's volume.
  const core::HexMesh gridded = core::hexes_of(io::read_mesh(out / "hex.mesh"));
  const core::HexBoundary b = core::boundary(gridded);
  EXPECT_EQ(vtk.quads.size(), b.surface.cells.size());
  core::QuadMesh quads = core::quads_of(vtk);
  core::remove_unreferenced_points(quads);
  std::set<std::array<double, 3>> quad_points, boundary_points;
  for (const auto& p : quads.points) quad_points.insert({p.x(), p.y(), p.z()});
  for (const auto& p : b.surface.points) boundary_points.insert({p.x(), p.y(), p.z()});
  EXPECT_EQ(quad_points, boundary_points);
  EXPECT_NEAR(core::signed_volume(quads), 3.0, 1e-9);
  const std::vector<double> sj = cell_field(vtk, "scaled_jacobian");
  ASSERT_EQ(sj.size(), vtk.quads.size());
  EXPECT_GT(*std::min_element(sj.begin(), sj.end()), 0.0);
  // The patches of a box's quad mesh are its 6 faces, the report's #dom after simplification.
  const std::vector<double> patch = cell_field(vtk, "patch_id");
  ASSERT_EQ(patch.size(), vtk.quads.size());
  EXPECT_EQ(std::set<double>(patch.begin(), patch.end()).size(), 6u);
  EXPECT_EQ(static_cast<int>(std::set<double>(patch.begin(), patch.end()).size()),
            j["quad_domains_after"].get<int>());
}

TEST_F(RunBox, SameInputSameOutput) {
  ASSERT_EQ(result_.exit_code, 0) << result_.err;
  const fs::path again = dir_ / "again";
  fs::create_directories(again);
  const CliResult r = run(fmt::format("\"{}\" -o \"{}\" --hexes 3000", (dir_ / "box.obj").string(), (again / "out").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir_ / "out" / "hex_optimized.mesh"), slurp(again / "out" / "hex_optimized.mesh"));
  EXPECT_EQ(slurp(dir_ / "out" / "simplify" / "polycube.mesh"), slurp(again / "out" / "simplify" / "polycube.mesh"));
}

TEST(RunCli, OneThreadOrTwoWriteTheSameFiles) {
  // A shape with work for every parallel loop: an optimizer that iterates, selective padding.
  // The runs also ask the BLAS and OpenMP for 1, the default (a thread per core) and 3 threads of
  // their own: the solver keeps them on one, since a threaded BLAS rounds differently with each
  // thread count.
  const fs::path dir = temp_dir("threads");
  ASSERT_EQ(test::run_cli(fmt::format("sample box-cylinder -o \"{}\"", (dir / "bc.obj").string())).exit_code, 0);
  const std::vector<std::pair<std::string, int>> runs = {{"1", 1}, {"2", 2}, {"2-blas", 2}};
  for (const auto& [name, threads] : runs) {
    if (name != "2") {
      const char* blas = name == "1" ? "1" : "3";
      setenv("OPENBLAS_NUM_THREADS", blas, 1);
      setenv("OMP_NUM_THREADS", blas, 1);
    }
    const CliResult r = test::run_cli(fmt::format("-q --threads {} run \"{}\" -o \"{}\" --hexes 500", threads,
                                                  (dir / "bc.obj").string(), (dir / name).string()));
    unsetenv("OPENBLAS_NUM_THREADS");
    unsetenv("OMP_NUM_THREADS");
    ASSERT_EQ(r.exit_code, 0) << name << ": " << r.err;
  }
  const auto files_of = [&](const std::string& name) {
    const nlohmann::json report = read_report(dir / name);
    std::vector<std::string> files;  // the report lists them relative to the output folder
    for (const auto& f : report["files"]) files.push_back(f.get<std::string>());
    return files;
  };
  const std::vector<std::string> files = files_of("1");
  ASSERT_GE(files.size(), 8u);
  for (const auto& [name, threads] : runs) {
    EXPECT_EQ(files_of(name), files) << name;
    for (const std::string& f : files) {
      if (f == "report.json") continue;
      const std::string first = slurp(dir / "1" / f);
      ASSERT_FALSE(first.empty()) << f;
      EXPECT_TRUE(first == slurp(dir / name / f)) << name << " " << f << " differs";
    }
  }
}

TEST(RunCli, OpenSurfaceStopsWithExitTwoBeforeAnyHeavyWork) {
  const fs::path dir = temp_dir("open");
  auto m = test::make_box(1.0, 1.0, 1.0, 2);
  m.cells.pop_back();
  write_surface(dir / "open.obj", m);
  const CliResult r = run(fmt::format("\"{}\" -o \"{}\"", (dir / "open.obj").string(), (dir / "out").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("stage input failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("open"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "construct"));
  EXPECT_FALSE(fs::exists(dir / "out" / "hex.mesh"));
  const auto j = nlohmann::json::parse(slurp(dir / "out" / "report.json"));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["failure"]["stage"], "input");
  expect_stopped_at(r, dir / "out", "input", 2, {});
}

TEST(RunCli, NonManifoldSurfaceStopsWithExitTwo) {
  const fs::path dir = temp_dir("nonmanifold");
  auto m = test::make_box(1.0, 1.0, 1.0, 1);
  const int a = m.cells[0][0], b = m.cells[0][1], c = m.num_points();
  m.points.push_back((m.points[a] + m.points[b]) / 2 + core::Vec3(2, 2, 2));
  m.cells.push_back({a, b, c});
  m.cells.push_back({b, a, c});
  write_surface(dir / "fin.obj", m);
  const CliResult r = run(fmt::format("\"{}\" -o \"{}\"", (dir / "fin.obj").string(), (dir / "out").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("manifold"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "construct"));
}

// A closed, manifold surface with 4 triangles: a polycube has at least 6 charts and a labeling
// gives each triangle one label, so no labeling can be valid and the construction must fail --
// exit 3 (the algorithm found no result; the file itself is fine), no map written.
TEST(RunCli, ConstructFailureExitsThreeAndWritesNoMap) {
  const fs::path dir = temp_dir("construct_fails");
  core::TriMesh tet;
  tet.points = {core::Vec3(0, 0, 0), core::Vec3(1, 0, 0), core::Vec3(0, 1, 0), core::Vec3(0, 0, 1)};
  tet.cells = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  write_surface(dir / "tetrahedron.obj", tet);
  // Four triangles cannot be labeled; without the coarse surface's refinement, nothing is tried.
  const CliResult r = run(dir / "tetrahedron.obj", dir / "out", "--hexes 100 --coarse-edge-ratio 0");
  expect_stopped_at(r, dir / "out", "construct", 3, {"input"});
  EXPECT_NE(r.err.find("no valid polycube labeling"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "construct"));
  const auto j = read_report(dir / "out");
  EXPECT_TRUE(j["tets"].is_null()) << j["tets"];  // the construction's figures stay "not computed": null
  EXPECT_TRUE(j["hexes"].is_null()) << j["hexes"];
  // The summary table is printed for a failure of the algorithm (not for bad input).
  EXPECT_NE(r.out.find("| construct |"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAILED"), std::string::npos) << r.out;
}

// Construct's last fallback (pipeline/input.h): when no attempt on the surface as read can be
// certified (here: counted so by `--inject-failure construct-unwrapped`), its alpha wrap is
// constructed, the chain fits the wrap, and the report names the fallback, why it was taken and
// the final mesh's distance to both surfaces. With --no-wrap-fallback the same failure stops
// the chain at construct.
TEST(RunCli, AnUncertifiedSurfaceFallsBackToItsAlphaWrapAndTheReportSaysSo) {
  const fs::path dir = temp_dir("wrap_fallback");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const std::string coarse_wrap = "--hexes 200 --padding none --wrap-alpha 0.1 --wrap-offset 0.01";
  const CliResult r = run(dir / "box.obj", dir / "out", coarse_wrap + " --inject-failure construct-unwrapped");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  ASSERT_TRUE(j["construct_fallback"].is_object()) << j["construct_fallback"];
  EXPECT_TRUE(j["construct_fallback"]["taken"].get<std::string>().starts_with("alpha wrap (")) << j["construct_fallback"];
  EXPECT_NE(j["construct_fallback"]["why"].get<std::string>().find("injected failure"), std::string::npos);
  EXPECT_NE(r.out.find("alpha wrap"), std::string::npos) << r.out;
  expect_valid_map(dir / "out" / "construct", j);
  EXPECT_EQ(j["final"]["inverted"], 0);
  // The wrap lies about its offset (1 % of the diagonal) outside the box: the mesh that fits it
  // is farther from the box than from the wrap.
  const double to_wrap = j["final"]["hausdorff_relative"].get<double>();
  const double to_box = j["final"]["hausdorff_unwrapped_relative"].get<double>();
  EXPECT_GT(to_box, to_wrap);
  EXPECT_GT(to_box, 0.005);

  const CliResult off = run(dir / "box.obj", dir / "off", coarse_wrap + " --no-wrap-fallback --inject-failure construct-unwrapped");
  expect_stopped_at(off, dir / "off", "construct", 3, {"input"});
  EXPECT_NE(off.err.find("injected failure"), std::string::npos) << off.err;
  EXPECT_TRUE(read_report(dir / "off")["construct_fallback"].is_null());
}

// A mesh beyond the distance bound (counted so by `--inject-failure final-distance`) is made
// again with a labeling of a third of the compactness, in a folder of its own whose files then
// replace the first chain's; `--no-labeling-fallback` keeps the first mesh.
TEST(RunCli, AMeshBeyondTheDistanceBoundIsMadeAgainWithAMoreFaithfulLabelingAndTheReportSaysSo) {
  const fs::path dir = temp_dir("labeling_fallback");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 200 --padding none --inject-failure final-distance");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  ASSERT_TRUE(j["labeling_fallback"].is_object()) << j["labeling_fallback"];
  EXPECT_TRUE(j["labeling_fallback"]["kept"].get<bool>());
  EXPECT_DOUBLE_EQ(j["labeling_fallback"]["compactness"].get<double>(), 0.3);
  EXPECT_TRUE(j["labeling_fallback"]["why_not"].is_null());
  EXPECT_EQ(j["construct_attempt"], "compactness 0.3");
  EXPECT_EQ(j["construct_attempts"], 1);
  EXPECT_DOUBLE_EQ(j["labeling_fallback"]["hausdorff_relative_retry"].get<double>(),
                   j["final"]["hausdorff_relative"].get<double>());
  EXPECT_NE(r.out.find("labeling fallback"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("more faithful labeling"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "faithful-labeling"));
  for (const auto& f : j["files"]) EXPECT_TRUE(fs::exists(dir / "out" / f.get<std::string>())) << f;
  expect_valid_map(dir / "out" / "construct", j);
  EXPECT_EQ(j["final"]["inverted"], 0);

  EXPECT_EQ(j["labeling_fallback"]["reason"], "distance");

  // A mesh poor in mSJ (counted so) gets the same retry.
  const CliResult poor = run(dir / "box.obj", dir / "poor", "--hexes 200 --padding none --inject-failure final-quality");
  ASSERT_EQ(poor.exit_code, 0) << poor.err;
  const auto q = read_report(dir / "poor");
  ASSERT_TRUE(q["labeling_fallback"].is_object()) << q["labeling_fallback"];
  EXPECT_EQ(q["labeling_fallback"]["reason"], "quality");
  EXPECT_TRUE(q["labeling_fallback"]["kept"].get<bool>());
  EXPECT_DOUBLE_EQ(q["labeling_fallback"]["msj_retry"].get<double>(), q["final"]["msj"].get<double>());
  EXPECT_EQ(q["construct_attempt"], "compactness 0.3");

  // An interrupted retry's folder is removed by the next run into the same folder.
  fs::create_directories(dir / "off" / "faithful-labeling");
  std::ofstream(dir / "off" / "faithful-labeling" / "hex.mesh") << "stale";
  const CliResult off =
      run(dir / "box.obj", dir / "off", "--hexes 200 --padding none --no-labeling-fallback --inject-failure final-distance");
  EXPECT_FALSE(fs::exists(dir / "off" / "faithful-labeling"));
  ASSERT_EQ(off.exit_code, 0) << off.err;
  const auto k = read_report(dir / "off");
  EXPECT_TRUE(k["labeling_fallback"].is_null());
  EXPECT_EQ(k["construct_attempt"], "compactness 1");
}

// A chain that ends at optimize without a valid mesh (counted so by `--inject-failure optimize`)
// gets the same retry; its valid mesh is the run's, whatever its distance: exit 0, the first
// chain's failure in the report, none of its files left.
TEST(RunCli, AChainWithoutAValidMeshIsMadeAgainWithAMoreFaithfulLabeling) {
  const fs::path dir = temp_dir("labeling_fallback_optimize");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 200 --padding none --inject-failure optimize");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  ASSERT_TRUE(j["labeling_fallback"].is_object()) << j["labeling_fallback"];
  EXPECT_EQ(j["labeling_fallback"]["reason"], "optimize");
  EXPECT_TRUE(j["labeling_fallback"]["kept"].get<bool>());
  EXPECT_NE(j["labeling_fallback"]["failure_first"].get<std::string>().find("optimize: injected failure"),
            std::string::npos)
      << j["labeling_fallback"]["failure_first"];
  EXPECT_TRUE(j["labeling_fallback"]["hausdorff_relative_first"].is_null());
  EXPECT_DOUBLE_EQ(j["labeling_fallback"]["hausdorff_relative_retry"].get<double>(),
                   j["final"]["hausdorff_relative"].get<double>());
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["construct_attempt"], "compactness 0.3");
  EXPECT_NE(r.out.find("gave no valid mesh"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir / "out" / "faithful-labeling"));
  for (const auto& f : j["files"]) EXPECT_TRUE(fs::exists(dir / "out" / f.get<std::string>())) << f;
  expect_valid_map(dir / "out" / "construct", j);
  const core::HexMesh hex = core::hexes_of(io::read_mesh(dir / "out" / "hex_optimized.mesh"));
  EXPECT_EQ(quality::scaled_jacobian(hex).inverted, 0);
  EXPECT_EQ(j["final"]["inverted"], 0);

  // Without the optimizer a gridded mesh is what was asked for: no retry.
  const CliResult bare = run(dir / "box.obj", dir / "bare", "--hexes 100 --no-optimize --inject-failure quality");
  expect_stopped_at(bare, dir / "bare", "quality", 3, {"input", "construct", "simplify", "hexmesh"});
  EXPECT_TRUE(read_report(dir / "bare")["labeling_fallback"].is_null());
}

// A surface with a slit narrower than the wrap's ball (a square plate with a slot cut from one
// side): when its first attempt fails (counted so by `--inject-failure construct-attempt-1`),
// the wrap is constructed next, before the plan's other attempts. The same failure on a box,
// which has no such gap, is followed by the plan's second attempt on the box itself.
TEST(RunCli, ASurfaceWithASlitGetsItsWrapRightAfterAFailingFirstAttempt) {
  const fs::path dir = temp_dir("slit_wrap");
  const samples::detail::Polygon2 slotted = {{0, 0}, {10, 0}, {10, 4.9}, {3, 4.9}, {3, 5.1}, {10, 5.1}, {10, 10}, {0, 10}};
  samples::detail::RemeshParams remesh;
  remesh.target_edge_length = 0.5;
  write_surface(dir / "slotted.obj", samples::detail::remesh(samples::detail::prism(slotted, {}, 0.0, 3.0), remesh));
  const std::string options =
      "--hexes 300 --padding none --wrap-alpha 0.05 --wrap-offset 0.005 --inject-failure construct-attempt-1";
  const CliResult slit = run(dir / "slotted.obj", dir / "slit", options);
  ASSERT_EQ(slit.exit_code, 0) << slit.err;
  const auto j = read_report(dir / "slit");
  ASSERT_TRUE(j["construct_fallback"].is_object()) << j["construct_fallback"];
  EXPECT_TRUE(j["construct_fallback"]["taken"].get<std::string>().starts_with("alpha wrap ("));
  EXPECT_NE(j["construct_fallback"]["why"].get<std::string>().find("first attempt"), std::string::npos)
      << j["construct_fallback"]["why"];
  EXPECT_EQ(j["final"]["inverted"], 0);

  write_surface(dir / "box.obj", test::make_box(10.0, 10.0, 3.0, 4));
  const CliResult box = run(dir / "box.obj", dir / "box", options);
  ASSERT_EQ(box.exit_code, 0) << box.err;
  const auto b = read_report(dir / "box");
  EXPECT_TRUE(b["construct_fallback"].is_null()) << b["construct_fallback"];
  EXPECT_EQ(b["construct_attempts"], 2);
}

// The same kind of solid with the defaults: its four triangles are split until they can be
// labeled, and its tips, sharper than a cube's corners, are held to be polycube corners (left
// inside a chart, a tip's tets stayed inverted: issue 24).
TEST(RunCli, ATetrahedronRunsThroughWithItsTipsMadeCorners) {
  const fs::path dir = temp_dir("tetrahedron_runs");
  const core::TriMesh tet = test::regular_tetrahedron();
  write_surface(dir / "tetrahedron.obj", tet);
  const CliResult r = run(dir / "tetrahedron.obj", dir / "out", "--hexes 300");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("the surface is too coarse"), std::string::npos) << r.err;
  const auto j = read_report(dir / "out");
  EXPECT_EQ(j["coarse_surface_refined"]["tip_corners"], 4) << j["coarse_surface_refined"];
  EXPECT_EQ(j["final"]["inverted"], 0);
  EXPECT_GT(j["final"]["msj"].get<double>(), 0.0);
}

// A surface finer than --max-triangles is decimated for the construction; the hex mesh is still
// fitted to, and its distance measured against, the input surface.
TEST(RunCli, AFineSurfaceIsDecimatedForTheConstructionAndTheMeshFitsTheInput) {
  const fs::path dir = temp_dir("decimated");
  const core::TriMesh sphere = test::make_sphere(1.0, 32, 64);  // 3,968 triangles
  write_surface(dir / "sphere.obj", sphere);
  const CliResult r = run(dir / "sphere.obj", dir / "out",
                          "--hexes 500 --padding none --max-triangles 3000 --decimate-to 300 --decimation-tolerance 0.02");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("the surface decimated from 3968 to"), std::string::npos) << r.out;
  const auto j = read_report(dir / "out");
  EXPECT_EQ(j["surface_decimated"]["triangles_before"], 3968) << j["surface_decimated"];
  EXPECT_LE(j["surface_decimated"]["triangles_after"].get<int>(), 300) << j["surface_decimated"];
  EXPECT_EQ(j["final"]["inverted"], 0);
  EXPECT_LE(j["final"]["hausdorff_relative"].get<double>(), 0.009);
  // The construction's solid is the decimated one: its triangles cut chords well inside the
  // sphere. The final mesh's boundary is fitted to the input sphere instead: on average its
  // vertices are on it.
  const core::PolycubeMap map = io::read_polycube_map(dir / "out" / "construct" / "model.mesh",
                                                      dir / "out" / "construct" / "polycube.mesh");
  const core::TetBoundary model = core::boundary(map.model_mesh());
  double model_centroids = 0.0;
  for (const core::Tri& t : model.surface.cells)
    model_centroids +=
        (model.surface.points[t[0]] + model.surface.points[t[1]] + model.surface.points[t[2]]).norm() / 3.0;
  model_centroids /= static_cast<double>(model.surface.num_cells());
  EXPECT_LT(model_centroids, 0.997);
  const core::HexMesh hex = core::hexes_of(io::read_mesh(dir / "out" / "hex.mesh"));
  const core::QuadMesh skin = core::boundary(hex).surface;
  double mean = 0.0;
  for (const core::Vec3& p : skin.points) mean += p.norm();
  mean /= static_cast<double>(skin.points.size());
  EXPECT_NEAR(mean, 1.0, 2e-3);
}

// No small input makes the simplification (nor, below, the optimization and the quality stage)
// fail reliably: a failure there is a limitation of the algorithm that the algorithm's work
// keeps moving. The hidden --inject-failure STAGE (pipeline.h) makes the stage fail at its start
// the way a real failure does (a GeometryError), so the handling of the failure is what is
// tested: exit code, stage named, earlier results kept and readable, nothing later written.
TEST(RunCli, SimplifyFailureExitsThreeAndKeepsTheConstructedMap) {
  const fs::path dir = temp_dir("simplify_fails");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 100 --inject-failure simplify");
  expect_stopped_at(r, dir / "out", "simplify", 3, {"input", "construct"});
  EXPECT_NE(r.err.find("injected failure"), std::string::npos) << r.err;
  const auto j = read_report(dir / "out");
  expect_valid_map(dir / "out" / "construct", j);
  EXPECT_TRUE(j["hex_domains_after"].is_null()) << j["hex_domains_after"];
  EXPECT_TRUE(j["hexes"].is_null()) << j["hexes"];
  EXPECT_NE(r.out.find("| simplify |"), std::string::npos) << r.out;
}

// The simplification's fallbacks (simplify.h), reached by `--inject-failure simplify-step-N`
// (the first N steps count as failed; a box's fit always certifies): each gives a valid mesh,
// and the report names the step that gave the map and why the earlier ones failed. When every
// step fails the unsimplified map is meshed: no simplify/ map is written.
TEST(RunCli, SimplifyFallsBackStepByStepAndTheReportNamesTheStep) {
  const fs::path dir = temp_dir("simplify_fallbacks");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const char* expected[] = {"fewer alignments", "unaligned", "unsimplified"};
  for (int n = 1; n <= 3; ++n) {
    SCOPED_TRACE(n);
    const fs::path out = dir / ("out" + std::to_string(n));
    const CliResult r = run(dir / "box.obj", out, "--hexes 200 --inject-failure simplify-step-" + std::to_string(n));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = read_report(out);
    EXPECT_TRUE(j["ok"].get<bool>());
    EXPECT_EQ(j["construct_attempt"], "compactness 1");
    EXPECT_EQ(j["construct_attempts"], 1);
    EXPECT_EQ(j["simplify_step"], expected[n - 1]);
    ASSERT_EQ(j["simplify_tried"].size(), static_cast<std::size_t>(n));
    EXPECT_EQ(j["simplify_tried"][0], "aligned: injected failure");
    EXPECT_EQ(j["final"]["inverted"], 0);
    EXPECT_GT(j["hexes"].get<int>(), 0);
    // A box is one block whatever the step: nothing is lost.
    EXPECT_EQ(j["hex_domains_before"], 1);
    EXPECT_EQ(j["hex_domains_after"], 1);
    EXPECT_NE(r.out.find(std::string("| simplify | ")), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(expected[n - 1]), std::string::npos) << r.out;
    expect_valid_map(out / "construct", j);
    if (n < 3)
      expect_valid_map(out / "simplify", j);
    else
      EXPECT_FALSE(fs::exists(out / "simplify"));
  }
}

//! hex.mesh is the gridding that was optimized: the final mesh has its hexes, as many as the
//! report says.
void expect_final_mesh_is_the_gridding(const fs::path& out, const nlohmann::json& j) {
  const core::HexMesh gridded = core::hexes_of(io::read_mesh(out / "hex.mesh"));
  const core::HexMesh final_mesh = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
  EXPECT_EQ(gridded.cells, final_mesh.cells);
  EXPECT_EQ(static_cast<int>(final_mesh.cells.size()), j["hexes"].get<int>());
}

// The optimizer's fallbacks (pipeline.h), reached by `--inject-failure optimize-step-N` (the
// first N optimized meshes count as failing the fold-over check): the same grid with the paper's
// slower untangling schedule, then the mesh padded selectively (nothing to pad on a box), then
// globally, then the map gridded again with its own sizing, then twice as fine; the report names
// the fallback that passed, and hex.mesh is the gridding that was optimized. When all fail, the
// stage fails with exit 3.
TEST(RunCli, OptimizeFallsBackToPaddingThenNewGriddingsAndTheReportNamesThem) {
  const fs::path dir = temp_dir("optimize_fallbacks");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const char* expected[] = {"slower untangling schedule", "global padding", "map sizing", "finer grid (2x hexes)"};
  int hexes[4] = {0, 0, 0, 0};
  for (int n = 1; n <= 4; ++n) {
    SCOPED_TRACE(n);
    const fs::path out = dir / ("out" + std::to_string(n));
    const CliResult r = run(dir / "box.obj", out, "--hexes 200 --inject-failure optimize-step-" + std::to_string(n));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = read_report(out);
    EXPECT_EQ(j["optimize_fallback"], expected[n - 1]);
    EXPECT_EQ(j["optimize_tried"][0], "first grid: injected failure");
    if (n == 1) {
      // The same gridding optimized again: its hexes, no padding.
      EXPECT_NE(r.out.find("optimized again with a slower untangling schedule"), std::string::npos) << r.out;
      ASSERT_EQ(j["optimize_tried"].size(), 1u);
      EXPECT_EQ(j["final"]["inverted"], 0);
      expect_final_mesh_is_the_gridding(out, j);
      EXPECT_FALSE(fs::exists(out / "hex_padded.mesh"));
      continue;
    }
    // The box's hexes are all good: selective padding finds nothing to pad and passes on.
    ASSERT_EQ(j["optimize_tried"].size(), static_cast<std::size_t>(n + 1));
    EXPECT_EQ(j["optimize_tried"][1], "slower untangling schedule: injected failure");
    EXPECT_EQ(j["optimize_tried"][2], "selective padding: nothing to pad");
    EXPECT_EQ(j["final"]["inverted"], 0);
    const core::HexMesh gridded = core::hexes_of(io::read_mesh(out / "hex.mesh"));
    const core::HexMesh final_mesh = core::hexes_of(io::read_mesh(out / "hex_optimized.mesh"));
    EXPECT_EQ(static_cast<int>(gridded.cells.size()), j["hexes"].get<int>());
    hexes[n - 1] = j["hexes"].get<int>();
    if (n == 2) {
      // The padded mesh: the gridded hexes and one more per boundary quad, the layer flagged.
      EXPECT_NE(r.out.find("fell back to global padding"), std::string::npos) << r.out;
      EXPECT_EQ(j["padding"]["applied"], "global (optimize fallback)");
      EXPECT_EQ(j["padding"]["added_hexes"].get<int>(), j["quads"].get<int>());
      EXPECT_EQ(final_mesh.num_cells(), gridded.num_cells() + j["quads"].get<int>());
      EXPECT_EQ(core::hexes_of(io::read_mesh(out / "hex_padded.mesh")).cells, final_mesh.cells);
      EXPECT_TRUE(fs::exists(out / "hex_padded.vtk"));
      continue;
    }
    // hex.mesh is the gridding that was optimized: same hexes as the final mesh, as reported;
    // the padded mesh that was tried is not left behind.
    EXPECT_NE(r.out.find(fmt::format("regridded: {}", expected[n - 1])), std::string::npos) << r.out;
    EXPECT_EQ(gridded.cells, final_mesh.cells);
    EXPECT_EQ(j["padding"]["applied"], "none (nothing to pad)");  // the default selective padding
    EXPECT_FALSE(fs::exists(out / "hex_padded.mesh"));
  }
  EXPECT_GT(hexes[3], hexes[2]);  // twice the target: a finer grid
  // Every fallback of the optimizer failing, the chain stops there (the labeling fallback, which
  // would run the chain again, is tested on its own).
  const CliResult r = run(dir / "box.obj", dir / "out5", "--hexes 200 --inject-failure optimize-step-5 --no-labeling-fallback");
  expect_stopped_at(r, dir / "out5", "optimize", 3, {"input", "construct", "simplify", "hexmesh"});
  EXPECT_EQ(read_report(dir / "out5")["optimize_tried"].size(), 5u);
}

// A mesh whose boundary crosses itself (and nothing else wrong) is first optimized again from the
// same grid with a stiffer boundary barrier, before any padding or new gridding: the report names
// that fallback, and the final mesh has the gridded hexes, no more.
TEST(RunCli, ABoundaryThatCrossesItselfIsOptimizedAgainWithAStifferBarrierFirst) {
  const fs::path dir = temp_dir("optimize_crossing");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  // The first n results count as crossing themselves; the run names `fallback`, with the same
  // gridded hexes, no more.
  const auto crossing_run = [&](int n, const std::string& fallback) {
    const fs::path out = dir / ("out" + std::to_string(n));
    const std::string inject = "--inject-failure optimize-crossing-" + std::to_string(n);
    const CliResult r = run(dir / "box.obj", out, "--hexes 200 " + inject);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const auto j = read_report(out);
    EXPECT_EQ(j["optimize_fallback"], fallback);
    EXPECT_EQ(j["optimize_tried"].size(), static_cast<std::size_t>(n));
    EXPECT_EQ(j["optimize_tried"][0], "first grid: injected boundary crossing");
    EXPECT_EQ(j["final"]["inverted"], 0);
    expect_final_mesh_is_the_gridding(out, j);
    return j;
  };
  crossing_run(1, "stiffer boundary barrier");
  // A failure that is not a crossing skips this retry (the padding fallbacks come first there:
  // OptimizeFallsBackToPaddingThenNewGriddingsAndTheReportNamesThem).

  // When the stiffer barrier's mesh crosses itself too, the same grid with the paper's slower
  // untangling schedule comes next, before any padding.
  const auto j = crossing_run(2, "slower untangling schedule");
  EXPECT_EQ(j["optimize_tried"][1], "stiffer boundary barrier: injected boundary crossing");
}

//! The box of the distance tests through run without any fallback: its mesh is on its surface.
nlohmann::json plain_box_run(const fs::path& dir) {
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult plain = run(dir / "box.obj", dir / "plain", "--hexes 200 --padding none");
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  const auto p = read_report(dir / "plain");
  EXPECT_EQ(p["optimize_fallback"], "none");
  EXPECT_TRUE(p["optimize_tried"].empty());
  return p;
}

//! A run whose distance fallback kept the finer grid `name`: named in the report and the summary,
//! more hexes than the first grid's, hex.mesh its gridding, no inverted hex.
void expect_regridded(const CliResult& r, const fs::path& out, const nlohmann::json& j, const std::string& name,
                      int first_hexes) {
  EXPECT_EQ(j["optimize_fallback"], name);
  EXPECT_NE(r.out.find("regridded: " + name), std::string::npos) << r.out;
  EXPECT_GT(j["hexes"].get<int>(), first_hexes);
  expect_final_mesh_is_the_gridding(out, j);
  EXPECT_EQ(j["final"]["inverted"], 0);
}

//! A run whose distance fallback kept nothing has the first grid's files, as a run without the
//! fallback (`plain`) writes them.
void expect_the_first_grids_files(const fs::path& kept, const fs::path& plain, const nlohmann::json& k,
                                  const nlohmann::json& p) {
  EXPECT_EQ(k["hexes"], p["hexes"]);
  for (const char* name : {"hex.mesh", "hex_optimized.mesh"})
    EXPECT_EQ(core::hexes_of(io::read_mesh(kept / name)).points, core::hexes_of(io::read_mesh(plain / name)).points)
        << name;
}

// A valid mesh farther from the input than the optimizer's Hausdorff bound (here: counted so by
// `--inject-failure optimize-distance-1`) is followed by the map gridded twice as fine; the finer
// mesh is kept when valid and closer, and hex.mesh is its gridding. When the finer mesh is not
// closer (`optimize-distance-2`), the first mesh stays and hex.mesh is its gridding again.
TEST(RunCli, AMeshTooFarFromTheInputIsGriddedTwiceAsFine) {
  const fs::path dir = temp_dir("optimize_distance");
  const auto p = plain_box_run(dir);
  ASSERT_FALSE(::testing::Test::HasFailure()) << "the plain run failed";

  const CliResult finer = run(dir / "box.obj", dir / "finer", "--hexes 200 --padding none --inject-failure optimize-distance-1");
  ASSERT_EQ(finer.exit_code, 0) << finer.err;
  const auto f = read_report(dir / "finer");
  expect_regridded(finer, dir / "finer", f, "finer grid for the distance (2x hexes)", p["hexes"].get<int>());
  ASSERT_EQ(f["optimize_tried"].size(), 1u);
  EXPECT_EQ(f["optimize_tried"][0], "first grid: injected distance");

  const CliResult kept = run(dir / "box.obj", dir / "kept", "--hexes 200 --padding none --inject-failure optimize-distance-2");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  const auto k = read_report(dir / "kept");
  EXPECT_EQ(k["optimize_fallback"], "none");
  ASSERT_EQ(k["optimize_tried"].size(), 2u);
  EXPECT_EQ(k["optimize_tried"][0], "first grid: injected distance");
  EXPECT_EQ(k["optimize_tried"][1], "finer grid for the distance (2x hexes): injected distance (not kept)");
  expect_the_first_grids_files(dir / "kept", dir / "plain", k, p);
}

// With --refine-far, a valid mesh farther from the input than the optimizer's Hausdorff bound
// (here: counted so by `--inject-failure optimize-distance-N`) is followed by the map gridded with twice the cells in
// the unit slabs of the polycube that hold the points where it misses the input, then (N = 2: not
// closer either) twice as fine everywhere; a finer mesh is kept when valid and closer, and
// hex.mesh is its gridding. When none is closer (N = 3), the first mesh stays and hex.mesh is its
// gridding again.
TEST(RunCli, WithRefineFarAMeshTooFarIsGriddedFinerNearTheFarPointsThenTwiceAsFine) {
  const fs::path dir = temp_dir("optimize_distance_near");
  const auto p = plain_box_run(dir);
  ASSERT_FALSE(::testing::Test::HasFailure()) << "the plain run failed";
  const int hexes = p["hexes"].get<int>();

  const std::string near_name = "finer grid near the far points (2x cells there)";
  const std::string twice_name = "finer grid for the distance (2x hexes)";
  const CliResult near = run(dir / "box.obj", dir / "near", "--hexes 200 --padding none --refine-far --inject-failure optimize-distance-1");
  ASSERT_EQ(near.exit_code, 0) << near.err;
  const auto n = read_report(dir / "near");
  expect_regridded(near, dir / "near", n, near_name, hexes);
  ASSERT_EQ(n["optimize_tried"].size(), 1u);
  EXPECT_EQ(n["optimize_tried"][0], "first grid: injected distance");
  EXPECT_LE(n["hexes"].get<int>(), 2 * hexes);
  EXPECT_LE(n["final"]["hausdorff_relative"].get<double>(), 0.009);

  const CliResult twice = run(dir / "box.obj", dir / "twice", "--hexes 200 --padding none --refine-far --inject-failure optimize-distance-2");
  ASSERT_EQ(twice.exit_code, 0) << twice.err;
  const auto t = read_report(dir / "twice");
  expect_regridded(twice, dir / "twice", t, twice_name, hexes);
  ASSERT_EQ(t["optimize_tried"].size(), 2u);
  EXPECT_EQ(t["optimize_tried"][1], near_name + ": injected distance (not kept)");

  const CliResult kept = run(dir / "box.obj", dir / "kept", "--hexes 200 --padding none --refine-far --inject-failure optimize-distance-3");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  const auto k = read_report(dir / "kept");
  EXPECT_EQ(k["optimize_fallback"], "none");
  ASSERT_EQ(k["optimize_tried"].size(), 3u);
  EXPECT_EQ(k["optimize_tried"][0], "first grid: injected distance");
  EXPECT_EQ(k["optimize_tried"][1], near_name + ": injected distance (not kept)");
  EXPECT_EQ(k["optimize_tried"][2], twice_name + ": injected distance (not kept)");
  expect_the_first_grids_files(dir / "kept", dir / "plain", k, p);
}

// `--no-simplify` meshes the constructed map, whose chart planes are not on one lattice: on the
// flange sample at 300 hexes no single scale snaps them (corners pushed onto facets), and the
// hexmesh stage stopped there. It now grids with the map's own sizing, and says so.
TEST(RunCli, AnUnsimplifiedMapThatDoesNotSnapAtOneScaleIsGriddedWithItsOwnSizing) {
  const fs::path dir = temp_dir("no_simplify_sizing");
  ASSERT_EQ(test::run_cli(fmt::format("sample flange -o \"{}\"", (dir / "flange.obj").string())).exit_code, 0);
  const CliResult r = run(dir / "flange.obj", dir / "out", "--hexes 300 --no-simplify --no-optimize");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  const std::string why = j["grid_sizing_fallback"];
  EXPECT_EQ(why.rfind("map sizing (snapping the polycube to the lattice broke it", 0), 0u) << why;
  EXPECT_NE(r.out.find("the map's own sizing (one scale did not snap)"), std::string::npos) << r.out;
  const core::HexMesh hex = core::hexes_of(io::read_mesh(dir / "out" / "hex.mesh"));
  EXPECT_EQ(static_cast<int>(hex.cells.size()), j["hexes"].get<int>());
  EXPECT_GT(hex.cells.size(), 0u);
  // A map that snaps keeps one scale and says nothing.
  const CliResult plain = run(dir / "flange.obj", dir / "plain", "--hexes 300 --no-optimize");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(read_report(dir / "plain")["grid_sizing_fallback"], "");
}

TEST(RunCli, GlobalPaddingOnRequestAddsThePadStage) {
  const fs::path dir = temp_dir("padding_global");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 200 --padding global");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  EXPECT_EQ(j["padding"]["applied"], "global");
  EXPECT_EQ(j["optimize_fallback"], "none");
  const core::HexMesh optimized = core::hexes_of(io::read_mesh(dir / "out" / "hex_optimized.mesh"));
  const core::HexMesh padded = core::hexes_of(io::read_mesh(dir / "out" / "hex_padded.mesh"));
  EXPECT_EQ(optimized.num_cells(), j["hexes"].get<int>());
  EXPECT_EQ(padded.num_cells(), optimized.num_cells() + j["quads"].get<int>());
  EXPECT_EQ(j["padding"]["added_hexes"].get<int>(), j["quads"].get<int>());
  EXPECT_GT(j["padding"]["singular_vertices_after"].get<int>(), j["padding"]["singular_vertices_before"].get<int>());
  EXPECT_EQ(j["final"]["inverted"], 0);
  EXPECT_LT(j["final"]["hausdorff_relative"].get<double>(), 0.009);
  // The final quality file is the padded mesh's.
  EXPECT_EQ(static_cast<int>(io::read_mesh(dir / "out" / "hex_quality.vtk").hexes.size()), padded.num_cells());
  bool pad_stage = false;
  for (const auto& s : j["stages"]) pad_stage = pad_stage || (s["stage"] == "pad" && s["ok"].get<bool>());
  EXPECT_TRUE(pad_stage);
}

// Padding must pay for itself: a box's optimized grid is perfect (mSJ 1), its padded corners are
// not, so asking for no loss below 1 keeps the unpadded mesh; the padded one is still written.
TEST(RunCli, APaddedMeshThatLosesQualityIsNotKept) {
  const fs::path dir = temp_dir("padding_not_kept");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 200 --padding global --padding-min-sj 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = read_report(dir / "out");
  const double before = j["padding"]["msj_unpadded"].get<double>(), after = j["padding"]["msj_padded"].get<double>();
  ASSERT_LT(after, before);
  EXPECT_EQ(j["padding"]["applied"].get<std::string>().rfind("global (not kept", 0), 0u) << j["padding"]["applied"];
  EXPECT_NEAR(j["final"]["msj"].get<double>(), before, 1e-12);
  EXPECT_EQ(static_cast<int>(io::read_mesh(dir / "out" / "hex_quality.vtk").hexes.size()), j["hexes"].get<int>());
  EXPECT_TRUE(fs::exists(dir / "out" / "hex_padded.mesh"));
  EXPECT_NE(r.out.find("not kept"), std::string::npos) << r.out;
}

// A second run into the same folder leaves none of the first run's files that it does not write
// itself: after a full run, --no-optimize leaves no hex_optimized.mesh behind.
TEST(RunCli, ARunIntoAFolderWrittenBeforeLeavesNoEarlierOutput) {
  const fs::path dir = temp_dir("again");
  write_surface(dir / "box.obj", test::make_box(1.0, 2.0, 1.5, 2));
  ASSERT_EQ(run(dir / "box.obj", dir / "out", "--hexes 200 --padding global").exit_code, 0);
  ASSERT_TRUE(fs::exists(dir / "out" / "hex_optimized.mesh"));
  std::ofstream(dir / "out" / "notes.txt") << "mine\n";
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 200 --no-optimize");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "hex_optimized.mesh"));
  EXPECT_FALSE(fs::exists(dir / "out" / "hex_padded.mesh"));
  EXPECT_TRUE(fs::exists(dir / "out" / "notes.txt"));
  // Every file of ours in the folder is one the report lists.
  const auto j = read_report(dir / "out");
  std::set<std::string> listed;
  for (const auto& f : j["files"]) listed.insert((dir / "out" / f.get<std::string>()).lexically_normal().string());
  for (const auto& e : fs::recursive_directory_iterator(dir / "out")) {
    const std::string name = e.path().filename().string();
    if (!e.is_regular_file() || name == "notes.txt" || name == "report.json") continue;
    EXPECT_TRUE(listed.count(e.path().lexically_normal().string())) << e.path();
  }
}

// The lattice of 2e9 hexes is beyond the gridding's bound (mesh/grid.h, max_lattice_points):
// the request cannot be met for this polycube, which only the hexmesh stage can tell. The file
// is fine, so not exit 2; the command line is well formed, so not exit 1: exit 3.
TEST(RunCli, ImpossibleHexCountStopsTheHexmeshStageWithExitThree) {
  const fs::path dir = temp_dir("hexmesh_fails");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 2000000000");
  expect_stopped_at(r, dir / "out", "hexmesh", 3, {"input", "construct", "simplify"});
  EXPECT_NE(r.err.find("too large"), std::string::npos) << r.err;
  const auto j = read_report(dir / "out");
  const core::PolycubeMap built = expect_valid_map(dir / "out" / "construct", j);
  const core::PolycubeMap simplified = expect_valid_map(dir / "out" / "simplify", j);
  EXPECT_EQ(simplified.tets, built.tets);
  EXPECT_TRUE(j["hexes"].is_null()) << j["hexes"];
  EXPECT_TRUE(j["grid_scale"].is_null()) << j["grid_scale"];
}

TEST(RunCli, ImpossibleHexCountWithoutSimplificationKeepsOnlyTheConstructedMap) {
  const fs::path dir = temp_dir("hexmesh_fails_nosimplify");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--no-simplify --hexes 2000000000");
  expect_stopped_at(r, dir / "out", "hexmesh", 3, {"input", "construct"});
  expect_valid_map(dir / "out" / "construct", read_report(dir / "out"));
}

TEST(RunCli, OptimizeFailureExitsThreeAndKeepsTheGriddedMeshes) {
  const fs::path dir = temp_dir("optimize_fails");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 100 --inject-failure optimize --no-labeling-fallback");
  expect_stopped_at(r, dir / "out", "optimize", 3, {"input", "construct", "simplify", "hexmesh"});
  const fs::path out = dir / "out";
  const auto j = read_report(out);
  expect_valid_map(out / "construct", j);
  expect_valid_map(out / "simplify", j);
  // The kept meshes read back with the report's counts and gridded quality.
  const core::HexMesh hex = core::hexes_of(io::read_mesh(out / "hex.mesh"));
  ASSERT_FALSE(hex.cells.empty());
  EXPECT_EQ(static_cast<int>(hex.cells.size()), j["hexes"].get<int>());
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(hex);
  EXPECT_EQ(sj.inverted + sj.invalid, j["gridded"]["inverted"].get<int>());
  EXPECT_NEAR(sj.min, j["gridded"]["msj"].get<double>(), 1e-12);
  const core::MeshData quads = io::read_mesh(out / "quad.vtk");
  EXPECT_EQ(static_cast<int>(quads.quads.size()), j["quads"].get<int>());
  EXPECT_EQ(quads.quads.size(), core::boundary(hex).surface.cells.size());
  EXPECT_EQ(cell_field(quads, "patch_id").size(), quads.quads.size());
  // The final figures stay "not computed".
  EXPECT_TRUE(j["final"]["inverted"].is_null()) << j["final"]["inverted"];
  EXPECT_TRUE(j["final"]["msj"].is_null()) << j["final"]["msj"];
}

TEST(RunCli, QualityFailureWithoutOptimizationKeepsTheGriddedMeshes) {
  const fs::path dir = temp_dir("quality_fails");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 2));
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 100 --no-optimize --inject-failure quality");
  expect_stopped_at(r, dir / "out", "quality", 3, {"input", "construct", "simplify", "hexmesh"});
  const auto j = read_report(dir / "out");
  EXPECT_EQ(static_cast<int>(core::hexes_of(io::read_mesh(dir / "out" / "hex.mesh")).cells.size()),
            j["hexes"].get<int>());
}

// --json on a failure: stdout holds one JSON document, the report (status "failed", the stage,
// nulls for what was not computed, every option's value); other commands print an error object.
TEST(RunCli, JsonOnFailureIsTheReportWithNullsAndTheOptions) {
  const fs::path dir = temp_dir("json_failure");
  const CliResult r = test::run_cli("--json run \"" + (dir / "missing.obj").string() + "\" -o \"" +
                                    (dir / "out").string() + "\" --hexes 1234 --padding none");
  EXPECT_EQ(r.exit_code, 2);
  const auto j = nlohmann::json::parse(r.out);  // throws (fails the test) unless exactly one document
  EXPECT_EQ(j, read_report(dir / "out"));
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["failure"]["stage"], "input");
  EXPECT_TRUE(j["hexes"].is_null());
  EXPECT_TRUE(j["final"]["msj"].is_null());
  EXPECT_EQ(j["options"]["hexes"], "1234");
  EXPECT_EQ(j["options"]["padding"], "none");
  EXPECT_EQ(j["options"]["sizing"], "uniform");  // not given: the default, by name
  EXPECT_EQ(j["options"]["no-simplify"], false);
  EXPECT_EQ(j["options"]["padding-lambda"], "auto");  // selective padding's λ: 1, and 0 where 1 pads everything
  EXPECT_TRUE(j["options"]["chamber"].is_null());
  EXPECT_FALSE(j["options"].contains("inject-failure"));  // hidden
  EXPECT_EQ(j["version"], "0.1.0");

  const CliResult info = test::run_cli("--json info \"" + (dir / "missing.obj").string() + "\"");
  EXPECT_EQ(info.exit_code, 2);
  const auto e = nlohmann::json::parse(info.out);
  EXPECT_EQ(e["status"], "failed");
  EXPECT_EQ(e["exit_code"], 2);
  EXPECT_NE(e["error"].get<std::string>().find("no such file"), std::string::npos) << info.out;
}

// A file that cannot be written is the user's to fix (exit 2, the file named), whichever stage
// writes it: here a folder stands where the hexmesh stage writes hex.mesh.
TEST(RunCli, AnOutputThatCannotBeWrittenIsExitTwoNamingTheFile) {
  const fs::path dir = temp_dir("unwritable");
  write_surface(dir / "box.obj", test::make_box(2.0, 1.0, 1.0, 2));
  fs::create_directories(dir / "out" / "hex.mesh" / "in_the_way");
  const CliResult r = run(dir / "box.obj", dir / "out", "--hexes 100 --no-optimize");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("stage hexmesh failed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("hex.mesh: is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(read_report(dir / "out")["status"], "failed");
}

// SIGTERM (or Ctrl-C) during a run: exit code 130, "interrupted" on stderr, and a report with
// status "interrupted" naming the stage that was running.
TEST(RunCli, AnInterruptedRunLeavesAReportSayingSo) {
  const fs::path dir = temp_dir("interrupted");
  write_surface(dir / "box.obj", test::make_box(2.0, 1.0, 1.0, 6));
  const fs::path out = dir / "out", err = dir / "stderr.txt";
  // Started in the background by a shell, stopped after 2 s (the construction takes longer).
  const std::string script = fmt::format(
      "'{}' run '{}' -o '{}' --hexes 20000 2>'{}' & pid=$!; sleep 2; kill -TERM $pid; wait $pid; exit $?", POLYCUBE_CLI,
      (dir / "box.obj").string(), out.string(), err.string());
  const int status = std::system(script.c_str());  // std::system runs it with sh -c
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 130) << slurp(err);
  EXPECT_NE(slurp(err).find("polycube: interrupted"), std::string::npos) << slurp(err);
  const auto j = read_report(out);
  EXPECT_EQ(j["status"], "interrupted");
  EXPECT_TRUE(j["interrupted_stage"].is_string()) << j.dump();
  EXPECT_EQ(j["options"]["hexes"], "20000");
}

TEST(RunCli, InjectingAFailureIntoAnUnknownStageIsAUsageError) {
  const fs::path dir = temp_dir("inject_unknown");
  write_surface(dir / "box.obj", test::make_box(1.0, 1.0, 1.0, 1));
  const CliResult r = run(dir / "box.obj", dir / "out", "--inject-failure gridding");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace
}  // namespace polycube
