//! Benchmark of the polycube construction (issue 6): tetrahedralize, label, repair, deform,
//! untangle, certify, on the shared models. Each model is constructed 3 times; the table shows
//! the run with the median total time (per-stage times of that run) and its figures.
//!
//! usage: bench_construct [--json] [--data DIR] [--runs N] [model ...]
//!        (default models: every file of DATA/tet and DATA/surface)
#include "construct/construct.h"
#include "io/mesh_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;

construct::ConstructResult run(const std::filesystem::path& path) {
  const core::MeshData d = io::read_mesh(path);
  if (!d.tets.empty()) {
    core::TetMesh m = core::tets_of(d);
    m.labels.clear();
    return construct::construct_polycube(std::move(m));
  }
  core::TriMesh s = core::triangles_of(d);
  s.labels.clear();
  return construct::construct_polycube(s);
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  int runs = 3;
  std::filesystem::path data = POLYCUBE_DATA_DIR;
  std::vector<std::string> models;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") json = true;
    else if (a == "--data" && i + 1 < argc) data = argv[++i];
    else if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::stoi(argv[++i]));
    else if (!a.empty() && a[0] != '-') models.push_back(a);
    else {
      std::cerr << "usage: bench_construct [--json] [--data DIR] [--runs N] [model ...]\n";
      return 1;
    }
  }
  if (models.empty())
    for (const char* sub : {"tet", "surface"}) {
      std::vector<std::string> found;
      std::error_code ec;
      for (const auto& e : std::filesystem::directory_iterator(data / sub, ec))
        if (e.path().extension() == ".mesh" || e.path().extension() == ".obj")
          found.push_back(std::string(sub) + "/" + e.path().filename().string());
      std::sort(found.begin(), found.end());
      models.insert(models.end(), found.begin(), found.end());
    }
  nlohmann::json rows = nlohmann::json::array();
  if (!json)
    std::printf("%-26s %7s %6s %7s %6s %7s %7s | %6s %6s %6s %6s %6s %6s %7s\n", "model", "tets", "charts",
                "corners", "fidel", "iso_avg", "iso_max", "tet_s", "label", "repair", "deform", "untang", "cert",
                "total_s");
  for (const auto& name : models) {
    std::filesystem::path path = name;
    if (!std::filesystem::exists(path)) path = data / name;
    if (!std::filesystem::exists(path)) {
      if (!json) std::printf("%-26s (missing, skipped)\n", name.c_str());
      continue;
    }
    try {
      std::vector<construct::ConstructResult> rs;
      for (int r = 0; r < runs; ++r) rs.push_back(run(path));
      std::sort(rs.begin(), rs.end(), [](const auto& a, const auto& b) { return a.seconds.total < b.seconds.total; });
      const construct::ConstructResult& r = rs[rs.size() / 2];
      const auto& s = r.seconds;
      rows.push_back({{"model", name},
                      {"tets", r.map.num_tets()},
                      {"charts", r.charts},
                      {"corners", r.corners},
                      {"fidelity", r.fidelity},
                      {"isometric_average", r.isometric_average},
                      {"isometric_max", r.isometric_max},
                      {"certified", r.certificate.certified()},
                      {"seconds",
                       {{"tetrahedralize", s.tetrahedralize},
                        {"label", s.label},
                        {"repair", s.repair},
                        {"deform", s.deform},
                        {"untangle", s.untangle},
                        {"certify", s.certify},
                        {"total", s.total}}}});
      if (!json)
        std::printf("%-26s %7d %6d %7d %6.3f %7.3f %7.2f | %6.2f %6.2f %6.2f %6.2f %6.2f %6.2f %7.2f\n", name.c_str(),
                    r.map.num_tets(), r.charts, r.corners, r.fidelity, r.isometric_average, r.isometric_max,
                    s.tetrahedralize, s.label, s.repair, s.deform, s.untangle, s.certify, s.total);
    } catch (const std::exception& e) {
      if (!json) std::printf("%-26s FAILED: %s\n", name.c_str(), e.what());
      rows.push_back({{"model", name}, {"error", e.what()}});
    }
  }
  if (json) std::cout << nlohmann::json{{"benchmark", "construct"}, {"runs", runs}, {"rows", rows}}.dump(2) << '\n';
  return 0;
}
