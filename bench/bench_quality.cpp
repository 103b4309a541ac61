//! Benchmark of the quality analyses (issue 3): scaled Jacobian, singularities and base-complex
//! domains of a ~50k-hex mesh (a perturbed 37^3 grid) and of the shared hex meshes when present,
//! plus the Hausdorff distance of a hex boundary to a surface. Prints the median of 3 runs per
//! stage as a text table, or JSON with --json.
//!
//! usage: bench_quality [--json] [--data DIR]   (DIR defaults to the configured shared data folder)
#include "core/topology.h"
#include "io/mesh_io.h"
#include "quality/domains.h"
#include "quality/scaled_jacobian.h"
#include "quality/singularities.h"
#include "quality/structure_topology.h"
#include "quality/surface_distance.h"
#include "support/fixtures.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace polycube;
using Clock = std::chrono::steady_clock;

constexpr int kRuns = 3;

//! Median wall time in seconds of kRuns calls of f.
double median_seconds(const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < kRuns; ++i) {
    const auto start = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[kRuns / 2];
}

//! n^3 grid of the unit cube, interior vertices moved randomly by up to `amplitude` cells.
core::HexMesh perturbed_grid(int n, double amplitude) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-amplitude / n, amplitude / n);
  return test::lattice_hexes(n, n, n, [&](int i, int j, int k) {
    core::Vec3 p(double(i) / n, double(j) / n, double(k) / n);
    if (i > 0 && j > 0 && k > 0 && i < n && j < n && k < n) p += core::Vec3(u(rng), u(rng), u(rng));
    return p;
  });
}

struct Row {
  std::string model;
  int hexes = 0;
  double sj = 0, topology = 0, singularities = 0, domains = 0, total = 0;
  double msj = 0, asj = 0;
  int sv = 0, se = 0, d = 0;
};

Row run(const std::string& model, const core::HexMesh& m) {
  Row r;
  r.model = model;
  r.hexes = m.num_cells();
  quality::ScaledJacobianSummary sj;
  quality::HexTopology topo;
  quality::HexSingularities sing;
  quality::HexDomains dom;
  r.sj = median_seconds([&] { sj = quality::scaled_jacobian(m); });
  r.topology = median_seconds([&] { topo = quality::hex_topology(m); });
  r.singularities = median_seconds([&] { sing = quality::hex_singularities(m, topo); });
  r.domains = median_seconds([&] { dom = quality::hex_domains(m, topo, sing); });
  r.total = median_seconds([&] {
    const auto s = quality::scaled_jacobian(m);
    const auto t = quality::hex_topology(m);
    const auto g = quality::hex_singularities(m, t);
    const auto d = quality::hex_domains(m, t, g);
    (void)s;
    (void)d;
  });
  r.msj = sj.min;
  r.asj = sj.average;
  r.sv = sing.singular_vertices;
  r.se = sing.singular_edges;
  r.d = dom.domains;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  std::filesystem::path data = POLYCUBE_DATA_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json")
      json = true;
    else if (a == "--data" && i + 1 < argc)
      data = argv[++i];
    else {
      std::cerr << "usage: bench_quality [--json] [--data DIR]\n";
      return 1;
    }
  }

  std::vector<Row> rows;
  rows.push_back(run("grid37 (perturbed)", perturbed_grid(37, 0.3)));
  for (const char* name : {"rockerarm.mesh", "ellipsoid.mesh"}) {
    const auto path = data / "hex" / name;
    if (std::filesystem::exists(path))
      rows.push_back(run(name, core::hexes_of(io::read_mesh(path))));
  }

  // Hausdorff distance of a hex mesh's boundary to a target: the boundary itself with every
  // vertex moved randomly by up to 0.2% of the bounding-box diagonal (rockerarm when present,
  // else the perturbed grid), default tolerance.
  double hausdorff_time = 0.0, hausdorff = 0.0, upper = 0.0;
  std::size_t samples = 0;
  std::string hausdorff_model = "grid37";
  {
    core::HexMesh hexes = perturbed_grid(37, 0.3);
    const auto rocker = data / "hex" / "rockerarm.mesh";
    if (std::filesystem::exists(rocker)) {
      hexes = core::hexes_of(io::read_mesh(rocker));
      hausdorff_model = "rockerarm.mesh";
    }
    core::TriMesh target = quality::triangulate(core::boundary(hexes).surface);
    const double amplitude = 0.002 * core::bounding_box(target.points).diagonal() / std::sqrt(3.0);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-amplitude, amplitude);
    for (auto& p : target.points) p += core::Vec3(u(rng), u(rng), u(rng));
    quality::SurfaceDistance d;
    hausdorff_time = median_seconds([&] { d = quality::hausdorff_distance(hexes, target); });
    hausdorff = d.hausdorff;
    samples = d.surface_to_reference.queries + d.reference_to_surface.queries;
    upper = d.hausdorff_upper;
  }

  if (json) {
    nlohmann::json j = nlohmann::json::array();
    for (const auto& r : rows)
      j.push_back({{"model", r.model},
                   {"hexes", r.hexes},
                   {"seconds",
                    {{"scaled_jacobian", r.sj},
                     {"topology", r.topology},
                     {"singularities", r.singularities},
                     {"domains", r.domains},
                     {"total", r.total}}},
                   {"mSJ", r.msj},
                   {"aSJ", r.asj},
                   {"Sv", r.sv},
                   {"Se", r.se},
                   {"D", r.d}});
    j.push_back({{"model", "hausdorff " + hausdorff_model + " boundary vs perturbed copy"},
                 {"seconds", hausdorff_time},
                 {"queries", samples},
                 {"hausdorff", hausdorff},
                 {"upper_bound", upper}});
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("quality analysis, median of %d runs (seconds)\n", kRuns);
  std::printf("%-20s %7s %8s %8s %8s %8s %8s | %6s %6s %5s %5s %5s\n", "model", "#H", "SJ",
              "topology", "singular", "domains", "total", "mSJ", "aSJ", "#Sv", "#Se", "#D");
  for (const auto& r : rows)
    std::printf("%-20s %7d %8.4f %8.4f %8.4f %8.4f %8.4f | %6.3f %6.3f %5d %5d %5d\n",
                r.model.c_str(), r.hexes, r.sj, r.topology, r.singularities, r.domains, r.total,
                r.msj, r.asj, r.sv, r.se, r.d);
  std::printf(
      "hausdorff (%s boundary vs perturbed copy, default tolerance): %.4f s, %zu queries, H in "
      "[%.4g, %.4g]\n",
      hausdorff_model.c_str(), hausdorff_time, samples, hausdorff, upper);
  return 0;
}
