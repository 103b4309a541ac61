//! Benchmark of hex-mesh optimization (issue 8): untangling + quality rounds with surface and
//! feature attraction, then the global fold-over check and the Hausdorff distance. Cases: the
//! box-cylinder sample through construction and gridding at about 50k hexes (the goal:
//! at most 60 s), a perturbed 37^3 grid of the unit cube (50,653 hexes) with the cube as target,
//! and the shared hex meshes (rockerarm, ellipsoid) with their own boundary as target. Prints
//! the median of 3 runs as a text table, or JSON with --json.
//!
//! usage: bench_optimize [--json] [--data DIR] [--runs N]
#include "construct/construct.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "mesh/grid.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "quality/surface_distance.h"
#include "samples/samples.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace polycube;
using Clock = std::chrono::steady_clock;

struct Case {
  std::string model;
  core::HexMesh hexes;
  core::TriMesh target;
};

struct Row {
  std::string model;
  int hexes = 0;
  double msj_before = 0, asj_before = 0, msj_after = 0, asj_after = 0;
  int inverted_before = 0, inverted_after = 0;
  double hausdorff = 0;
  bool check_ok = false;
  int iterations = 0;
  double untangle = 0, quality = 0, check = 0, total = 0;  // median seconds
};

core::HexMesh perturbed_cube(int n, double amplitude) {
  core::HexMesh m;
  auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-amplitude / n, amplitude / n);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.points.emplace_back(core::Vec3(double(i) / n, double(j) / n, double(k) / n) +
                                                         core::Vec3(u(rng), u(rng), u(rng)));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        m.cells.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                           id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return m;
}

core::TriMesh unit_cube() {
  core::TriMesh t;
  for (int c = 0; c < 8; ++c) t.points.emplace_back(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    t.cells.push_back({f[0], f[1], f[2]});
    t.cells.push_back({f[0], f[2], f[3]});
  }
  return t;
}

Row run(const Case& c, int runs) {
  Row r;
  r.model = c.model;
  r.hexes = c.hexes.num_cells();
  std::vector<double> tu, tq, tc, tt;
  for (int i = 0; i < runs; ++i) {
    core::HexMesh m = c.hexes;
    const auto t0 = Clock::now();
    const optimize::OptimizeResult res = optimize::optimize_hex_mesh(m, c.target);
    const auto t1 = Clock::now();
    const optimize::FoldoverReport check = optimize::check_foldover(m);
    const auto t2 = Clock::now();
    tu.push_back(res.untangle.seconds);
    tq.push_back(res.quality.seconds);
    tc.push_back(std::chrono::duration<double>(t2 - t1).count());
    tt.push_back(std::chrono::duration<double>(t2 - t0).count());
    if (i == 0) {
      r.msj_before = res.before.min;
      r.asj_before = res.before.average;
      r.inverted_before = res.before.inverted + res.before.invalid;
      r.msj_after = res.after.min;
      r.asj_after = res.after.average;
      r.inverted_after = res.after.inverted + res.after.invalid;
      r.iterations = res.untangle.iterations + res.quality.iterations;
      r.check_ok = check.ok();
      r.hausdorff = quality::hausdorff_distance(m, c.target).relative;
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  };
  r.untangle = median(tu);
  r.quality = median(tq);
  r.check = median(tc);
  r.total = median(tt);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  int runs = 3;
  std::filesystem::path data = POLYCUBE_DATA_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") json = true;
    else if (a == "--data" && i + 1 < argc) data = argv[++i];
    else if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else {
      std::cerr << "usage: bench_optimize [--json] [--data DIR] [--runs N]\n";
      return 1;
    }
  }
  std::vector<Case> cases;
  try {
    const core::TriMesh surface = samples::make_sample("box-cylinder");
    const construct::ConstructResult cr = construct::construct_polycube(surface);
    mesh::GridOptions go;
    go.target_hexes = 50000;
    cases.push_back({"box-cylinder (gridded)", mesh::grid_polycube(cr.map, go).hex_model, surface});
  } catch (const std::exception& e) {
    std::cerr << "box-cylinder skipped: " << e.what() << '\n';
  }
  cases.push_back({"perturbed cube 37^3", perturbed_cube(37, 0.25), unit_cube()});
  for (const char* name : {"rockerarm", "ellipsoid"}) {
    const auto file = data / "hex" / (std::string(name) + ".mesh");
    if (!std::filesystem::exists(file)) continue;
    core::HexMesh m = core::hexes_of(io::read_mesh(file));
    core::TriMesh target = quality::triangulate(core::boundary(m).surface);
    cases.push_back({name, std::move(m), std::move(target)});
  }
  nlohmann::json out = nlohmann::json::array();
  if (!json)
    std::printf("%-24s %7s %7s %7s %7s %7s %5s %5s %9s %5s %5s %8s %8s %7s %8s\n", "model", "#H", "mSJ in", "aSJ in",
                "mSJ out", "aSJ out", "inv", "inv'", "Hausdorff", "check", "it.", "untangle", "quality", "check",
                "total");
  for (const Case& c : cases) {
    const Row r = run(c, runs);
    if (json)
      out.push_back({{"model", r.model}, {"hexes", r.hexes}, {"msj_before", r.msj_before}, {"asj_before", r.asj_before},
                     {"msj_after", r.msj_after}, {"asj_after", r.asj_after}, {"inverted_before", r.inverted_before},
                     {"inverted_after", r.inverted_after}, {"hausdorff_relative", r.hausdorff},
                     {"check_ok", r.check_ok}, {"iterations", r.iterations}, {"untangle_s", r.untangle},
                     {"quality_s", r.quality}, {"check_s", r.check}, {"total_s", r.total}, {"runs", runs}});
    else
      std::printf("%-24s %7d %7.4f %7.4f %7.4f %7.4f %5d %5d %8.4f%% %5s %5d %7.2fs %7.2fs %6.2fs %7.2fs\n",
                  r.model.c_str(), r.hexes, r.msj_before, r.asj_before, r.msj_after, r.asj_after, r.inverted_before,
                  r.inverted_after, 100 * r.hausdorff, r.check_ok ? "ok" : "FAIL", r.iterations, r.untangle,
                  r.quality, r.check, r.total);
    std::fflush(stdout);
  }
  if (json) std::cout << out.dump(2) << '\n';
  else std::printf("(median of %d runs; Hausdorff relative to the target's bounding-box diagonal)\n", runs);
  return 0;
}
