//! Benchmark of the gridding (issue 4): locating and mapping lattice points of analytic polycube
//! maps (a bent L-shaped polycube and a box mapped onto a cylinder, ~50k tets each) at a ~50k-hex
//! and a ~1M-hex resolution. Prints the median of 3 runs as a text table, or JSON with --json.
//!
//! usage: bench_grid [--json]
#include "mesh/grid.h"
#include "structure/analytic_maps.h"
#include "structure/validate.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;
using Clock = std::chrono::steady_clock;
using test::Vec3;

constexpr int kRuns = 3;

Vec3 bend(const Vec3& p) {
  constexpr double R = 3.0;
  return {(R + p.z()) * std::sin(p.x() / R), p.y(), (R + p.z()) * std::cos(p.x() / R) - R};
}

Vec3 disc(const Vec3& p) {
  const double r = std::hypot(p.x(), p.y());
  const double f = r > 0 ? std::max(std::abs(p.x()), std::abs(p.y())) / r : 1.0;
  return {f * p.x(), f * p.y(), p.z()};
}

struct Row {
  std::string model;
  int tets = 0;
  int target = 0;
  double scale = 0;
  int hexes = 0;
  int points = 0;
  double locate = 0;  // median seconds
  double total = 0;   // median seconds
  double points_per_second = 0;
  int failed = 0;
  int inverted = 0;
};

Row run(const std::string& name, const core::PolycubeMap& map, int target) {
  Row r;
  r.model = name;
  r.tets = map.num_tets();
  r.target = target;
  mesh::GridOptions o;
  o.target_hexes = target;
  std::vector<double> loc, tot;
  for (int i = 0; i < kRuns; ++i) {
    const mesh::GridResult g = mesh::grid_polycube(map, o);
    loc.push_back(g.seconds_locate);
    tot.push_back(g.seconds_total);
    r.scale = g.scale;
    r.hexes = g.hex_model.num_cells();
    r.points = g.hex_model.num_points();
    r.failed = g.points_failed;
    r.inverted = g.inverted_model_hexes;
  }
  std::sort(loc.begin(), loc.end());
  std::sort(tot.begin(), tot.end());
  r.locate = loc[kRuns / 2];
  r.total = tot[kRuns / 2];
  r.points_per_second = r.points / r.locate;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const bool json = argc > 1 && std::string(argv[1]) == "--json";
  // ~50k tets each: the L has 3 r^3 cubes of 6 tets, the box 2r x 2r x r cubes
  const auto l = test::l_shape(14, bend);
  const auto box = test::make_grid_map(
      test::uniform(-1, 1, 30), test::uniform(-1, 1, 30), test::uniform(0, 1, 10),
      [](const Vec3&) { return true; }, disc);
  for (const auto* m : {&l.map, &box.map}) structure::validate_map(*m);
  std::vector<Row> rows;
  for (int target : {50'000, 1'000'000}) {
    rows.push_back(run("bent L", l.map, target));
    rows.push_back(run("box -> cylinder", box.map, target));
  }
  if (json) {
    nlohmann::json j = nlohmann::json::array();
    for (const Row& r : rows)
      j.push_back({{"model", r.model},
                   {"tets", r.tets},
                   {"target_hexes", r.target},
                   {"scale", r.scale},
                   {"hexes", r.hexes},
                   {"lattice_points", r.points},
                   {"seconds_locate", r.locate},
                   {"seconds_total", r.total},
                   {"points_per_second", r.points_per_second},
                   {"points_failed", r.failed},
                   {"inverted_model_hexes", r.inverted}});
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("gridding, median of %d runs (locate = locate + map every lattice point)\n", kRuns);
  std::printf("%-16s %7s %8s %9s %9s %10s %10s %12s %7s %9s\n", "model", "tets", "scale", "hexes",
              "points", "locate s", "total s", "points/s", "failed", "inverted");
  for (const Row& r : rows)
    std::printf("%-16s %7d %8.3f %9d %9d %10.3f %10.3f %12.3g %7d %9d\n", r.model.c_str(), r.tets,
                r.scale, r.hexes, r.points, r.locate, r.total, r.points_per_second, r.failed,
                r.inverted);
  return 0;
}
