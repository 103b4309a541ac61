//! Benchmark of polycube simplification (issue 7): pairing + alignment + finalization of the
//! structure (the goal: under 0.25 s per model, median of 3), and separately the tet
//! fitting/untangling, with #D and #dom before/after. Models: polycubes built in code (the
//! tests' comb and C-with-bump, and "cities" of n x n towers with perturbed heights)
//! and every map folder given on the command line (holding model.mesh and polycube.mesh, e.g.
//! `polycube construct` outputs).
//!
//! usage: bench_simplify [--json] [--no-fit] [--no-exterior-rule] [MAP_DIR...]
#include "io/polycube_map_io.h"
#include "simplify/simplify.h"
#include "structure/structure.h"
#include "simplify/polycube_fixtures.h"

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
constexpr int kRuns = 3;

//! n x n towers over a base, top of tower (i, j) = 1 + min(a_i, b_j) with integer a, b in 1..4
//! perturbed by up to ±0.15 (a min of per-row and per-column heights never makes two towers
//! touch along an edge only, so the polycube is manifold); tower widths perturbed too.
core::PolycubeMap city(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> h(1, 4);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  std::vector<double> gx, gy, a(n), b(n);
  for (int i = 0; i <= n; ++i) {
    gx.push_back(i + (i > 0 && i < n ? 0.5 * jitter(rng) : 0.0));
    gy.push_back(i + (i > 0 && i < n ? 0.5 * jitter(rng) : 0.0));
  }
  for (int i = 0; i < n; ++i) {
    a[i] = h(rng) + jitter(rng);
    b[i] = h(rng) + jitter(rng);
  }
  std::vector<double> gz{0.0, 1.0};
  for (int i = 0; i < n; ++i) {
    gz.push_back(1.0 + a[i]);
    gz.push_back(1.0 + b[i]);
  }
  std::sort(gz.begin(), gz.end());
  gz.erase(std::unique(gz.begin(), gz.end()), gz.end());
  return test::grid_polycube(gx, gy, gz, [&, n](int i, int j, int k) {
    return gz[k + 1] <= 1.0 + std::min(a[i], b[j]) + 1e-12;
  });
}

struct Model {
  std::string name;
  core::PolycubeMap map;
  double scale = 0.0;  // 0: automatic
};

}  // namespace

int main(int argc, char** argv) {
  bool json = false, fit = true, exterior = true;
  std::vector<Model> models;
  models.push_back({"comb", test::comb(0.1), 10.0});
  models.push_back({"c-with-bump", test::c_with_bump(0.1), 10.0});
  models.push_back({"city-8x8", city(8, 11), 0.0});
  models.push_back({"city-16x16", city(16, 12), 0.0});
  models.push_back({"city-24x24", city(24, 13), 0.0});
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") { json = true; continue; }
    if (a == "--no-fit") { fit = false; continue; }
    if (a == "--no-exterior-rule") { exterior = false; continue; }
    const std::filesystem::path dir = std::filesystem::path(a).lexically_normal();
    // `polycube run` and `construct` folders: name the model by the folder above "construct".
    std::string name = dir.filename().string();
    if (name.empty()) name = dir.parent_path().filename().string();
    if (name == "construct" || name == "simplify") name = dir.parent_path().filename().string();
    try {
      models.push_back({name, io::read_polycube_map(dir / "model.mesh", dir / "polycube.mesh"), 0.0});
    } catch (const std::exception& e) {
      std::cerr << "skipping " << a << ": " << e.what() << "\n";
    }
  }
  nlohmann::json out = nlohmann::json::array();
  if (!json)
    std::printf("%-14s %7s %8s %5s %7s %7s %6s %8s %8s %8s %6s %5s %9s %9s %5s\n", "model", "tets", "corners", "iters",
                "planes0", "planes1", "#D0", "#D1", "#dom0", "#dom1", "gainD", "cert", "struct_s", "fit_s", "LPs");
  for (const auto& m : models) {
    const auto s = structure::extract_structure(m.map);
    simplify::AlignOptions ao;
    ao.scale = m.scale;
    ao.exterior_rule = exterior;
    std::vector<double> times;
    simplify::AlignResult r;
    for (int k = 0; k < kRuns; ++k) {
      const auto t0 = Clock::now();
      r = simplify::align_corners(s, ao);
      times.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::sort(times.begin(), times.end());
    const double median = times[kRuns / 2];
    simplify::SimplifyOptions so;
    so.align = ao;
    so.fit_map = fit;
    const auto full = simplify::simplify_map(m.map, so);
    const int p0 = r.planes_before[0] + r.planes_before[1] + r.planes_before[2];
    const int p1 = r.planes_after[0] + r.planes_after[1] + r.planes_after[2];
    const double gain = full.before.hex_domains > 0 ? 100.0 * (full.before.hex_domains - full.after.hex_domains) / full.before.hex_domains : 0.0;
    const double fit_s = full.fit.seconds_place + full.fit.seconds_untangle + full.fit.seconds_certify;
    out.push_back({{"model", m.name}, {"tets", m.map.num_tets()}, {"corners", s.corners.size()},
                   {"iterations", r.iterations.size()}, {"planes_before", r.planes_before},
                   {"planes_after", r.planes_after}, {"hex_domains_before", full.before.hex_domains},
                   {"hex_domains_after", full.after.hex_domains}, {"quad_domains_before", full.before.quad_domains},
                   {"quad_domains_after", full.after.quad_domains}, {"certified", full.fit.certified},
                   {"structure_seconds_median", median},
                   {"seconds_constraints", r.seconds_system}, {"seconds_pairing", r.seconds_pairing},
                   {"seconds_alignment", r.seconds_solve}, {"seconds_finalization", r.seconds_finalize},
                   {"iteration_candidates", [&] { std::vector<int> c; for (const auto& it : r.iterations) c.push_back(it.candidates); return c; }()},
                   {"iteration_aligned", [&] { std::vector<int> c; for (const auto& it : r.iterations) c.push_back(it.aligned); return c; }()},
                   {"infeasible_first", r.iterations.empty() ? 0 : r.iterations[0].pairing.infeasible},
                   {"exterior_first", r.iterations.empty() ? 0 : r.iterations[0].pairing.exterior},
                   {"delaunay_first", r.iterations.empty() ? 0 : r.iterations[0].pairing.delaunay}, {"fit_seconds", fit_s}, {"lp_solves", r.lp_solves},
                   {"scale", r.scale}});
    if (!json)
      std::printf("%-14s %7d %8zu %5zu %7d %7d %6d %8d %8d %8d %5.0f%% %5s %9.4f %9.3f %5d\n", m.name.c_str(),
                  m.map.num_tets(), s.corners.size(), r.iterations.size(), p0, p1, full.before.hex_domains,
                  full.after.hex_domains, full.before.quad_domains, full.after.quad_domains, gain,
                  fit ? (full.fit.certified ? "yes" : "NO") : "-", median, fit_s, r.lp_solves);
  }
  if (json) std::cout << out.dump(2) << "\n";
  return 0;
}
