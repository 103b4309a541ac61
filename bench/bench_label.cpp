//! Benchmark of polycube labeling (issue 5): graph-cut labeling + repair to validity on the
//! boundary of the tetrahedralized shared models (bunny, max-planck, and the others when
//! present). Tetrahedralization is timed once, labeling and repair as the median of 3 runs.
//!
//! usage: bench_label [--json] [--data DIR] [--all]   (default models: bunny, max-planck)
#include "construct/labeling.h"
#include "construct/labeling_repair.h"
#include "construct/tetrahedralize.h"
#include "core/topology.h"
#include "io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;
using Clock = std::chrono::steady_clock;
constexpr int kRuns = 3;

double seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double median_seconds(const std::function<void()>& f) {
  std::vector<double> t;
  for (int i = 0; i < kRuns; ++i) {
    const auto start = Clock::now();
    f();
    t.push_back(seconds(start));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  bool all = false;
  std::filesystem::path data = POLYCUBE_DATA_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") json = true;
    else if (a == "--all") all = true;
    else if (a == "--data" && i + 1 < argc) data = argv[++i];
    else {
      std::cerr << "usage: bench_label [--json] [--data DIR] [--all]\n";
      return 1;
    }
  }
  std::vector<std::string> models = {"surface/bunny.obj", "surface/max-planck.obj"};
  if (all)
    models = {"surface/torus.obj", "surface/3holes.obj", "surface/cube_minus_sphere.obj",
              "surface/fandisk.obj", "surface/rocker-arm.obj", "surface/B0.obj", "surface/bunny.obj",
              "surface/moai.obj", "surface/max-planck.obj", "tet/B0.mesh", "tet/sphere.mesh",
              "tet/cup.mesh", "tet/S3.mesh"};
  nlohmann::json rows = nlohmann::json::array();
  if (!json)
    std::printf("%-26s %8s %8s %8s %7s %7s %8s %8s %6s %6s %6s\n", "model", "tris", "tets", "tet_s",
                "label_s", "total_s", "charts", "corners", "defect0", "defect", "valid");
  for (const auto& name : models) {
    const auto path = data / name;
    if (!std::filesystem::exists(path)) {
      if (!json) std::printf("%-26s (missing, skipped)\n", name.c_str());
      continue;
    }
    try {
      const auto t0 = Clock::now();
      core::TetMesh mesh;
      if (path.extension() == ".mesh") {
        mesh = core::tets_of(io::read_mesh(path));
        mesh.labels.clear();
        construct::prepare_tet_mesh(mesh);
        construct::refine_boundary(mesh);
      } else {
        mesh = construct::tetrahedralize(io::read_surface(path)).mesh;
      }
      const double tet_s = seconds(t0);
      const core::TriMesh surface = core::boundary(mesh).surface;
      construct::RepairResult rep;
      double label_part = 0.0;
      const double total = median_seconds([&] {
        const auto t1 = Clock::now();
        const auto lab = construct::graph_cut_labeling(surface);
        label_part = seconds(t1);
        rep = construct::repair_labeling(surface, lab.labels);
      });
      const auto& L = rep.check.layout;
      rows.push_back({{"model", name},
                      {"boundary_triangles", surface.num_cells()},
                      {"tets", mesh.num_cells()},
                      {"tetrahedralize_s", tet_s},
                      {"graph_cut_s", label_part},
                      {"label_and_repair_s", total},
                      {"charts", L.num_charts()},
                      {"corners", L.corners.size()},
                      {"defects_before_repair", rep.initial_defects},
                      {"defects", rep.check.defects.size()},
                      {"valid", rep.valid()}});
      if (!json)
        std::printf("%-26s %8d %8d %8.2f %7.2f %7.2f %8d %8zu %6d %6zu %6s\n", name.c_str(),
                    surface.num_cells(), mesh.num_cells(), tet_s, label_part, total, L.num_charts(),
                    L.corners.size(), rep.initial_defects, rep.check.defects.size(),
                    rep.valid() ? "yes" : "NO");
    } catch (const std::exception& e) {
      if (!json) std::printf("%-26s error: %s\n", name.c_str(), e.what());
      rows.push_back({{"model", name}, {"error", e.what()}});
    }
  }
  if (json) std::cout << nlohmann::json{{"benchmark", "label"}, {"runs", kRuns}, {"rows", rows}}.dump(2) << '\n';
  return 0;
}
