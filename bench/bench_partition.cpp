//! Benchmark of the box partition (issue 20): for each simplified map given as a directory
//! holding model.mesh and polycube.mesh (the `simplify/` folder of `polycube run`), the grid of
//! chart planes, concave edges, boxes of the partition (thesis §6.2) and after merging, the cuts of
//! the plan (and boxes a pinwheel split), corners not located in a tet, and the
//! time (median of 3). Prints a text table, or JSON with --json.
//!
//! usage: bench_partition [--json] DIR[=SOLID] ...
//!   With SOLID (a surface file, or "map" for the boundary of the map's model tets) the parts are
//!   cut too, once, and checked: closed, outward, no self-intersection, volumes adding up.
#include "core/log.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "core/types.h"
#include "fabricate/box_partition.h"
#include "fabricate/corners.h"
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"
#include "fabricate/parts.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;

constexpr int kRuns = 3;

struct Row {
  std::string model;
  std::array<int, 3> grid{};
  int inside = 0, concave = 0, regions = 0, boxes = 0, merged = 0, cuts = 0, splits = 0,
      not_located = 0;
  double plane_deviation = 0;                  // largest over the cuts, % of the model diagonal
  int parts = -1, bad_parts = 0, stray = 0;    // parts cut from the solid (-1: no solid given)
  double volume_error = 0, parts_seconds = 0;  // |sum - solid| / solid, %
  double seconds = 0;                          // median
};

Row run(const std::filesystem::path& dir, const std::string& solid_path) {
  const core::PolycubeMap map = io::read_polycube_map(dir / "model.mesh", dir / "polycube.mesh");
  Row r;
  r.model = dir.parent_path().filename().string();
  std::vector<double> times;
  fabricate::OccupancyGrid g;  // the last run's, for the exact cuts below
  fabricate::CutPlan plan;
  std::vector<fabricate::CutPlane> planes;
  for (int i = 0; i < kRuns; ++i) {
    const core::Stopwatch clock;
    g = fabricate::occupancy_grid(map);
    fabricate::BoxPartition p = fabricate::partition_boxes(g);
    const int boxes = static_cast<int>(p.boxes.size());
    r.regions = p.cut_regions;
    fabricate::merge_boxes(g, p);
    plan = fabricate::plan_cuts(g, p);
    const fabricate::BoxCorners corners = fabricate::map_corners(map, g, plan.partition);
    planes = fabricate::fit_cut_planes(map, g, plan);
    times.push_back(clock.seconds());
    r.cuts = static_cast<int>(plan.cuts.size());
    r.splits = plan.split_boxes;
    r.not_located = corners.not_located;
    const double diagonal = core::bounding_box(map.model).extent().norm();
    for (const auto& q : planes)
      r.plane_deviation = std::max(r.plane_deviation, 100.0 * q.max_deviation / diagonal);
    r.grid = {g.cells(0), g.cells(1), g.cells(2)};
    r.inside = static_cast<int>(std::count(g.inside.begin(), g.inside.end(), 1));
    r.concave = p.concave_edges;
    r.boxes = boxes;
    r.merged = static_cast<int>(p.boxes.size());
  }
  if (!solid_path.empty()) {  // the exact cuts, once (they take seconds, not milliseconds)
    const fabricate::Parts parts =
        fabricate::cut_parts((solid_path == "map" ? core::boundary(map.model_mesh()).surface
                                                  : io::read_surface(solid_path)),
                             plan, planes, fabricate::box_lookup(map, g, plan.partition));
    r.parts = static_cast<int>(parts.parts.size());
    for (const auto& q : parts.parts) {
      r.bad_parts += (!q.closed || !q.outward || q.self_intersecting) ? 1 : 0;
      r.stray += q.components - 1;
    }
    r.volume_error = 100.0 * std::abs(parts.volume_sum - parts.solid_volume) / parts.solid_volume;
    r.parts_seconds = parts.seconds;
  }
  std::sort(times.begin(), times.end());
  r.seconds = times[kRuns / 2];
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  std::vector<std::string> dirs;  // DIR or DIR=SOLID (the solid's surface: also cut the parts)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json")
      json = true;
    else
      dirs.emplace_back(a);
  }
  if (dirs.empty()) {
    std::cerr
        << "usage: bench_partition [--json] DIR ... (each with model.mesh and polycube.mesh)\n";
    return 2;
  }
  core::logger().set_level(spdlog::level::err);
  nlohmann::json out = nlohmann::json::array();
  if (!json)
    std::printf("%-28s %12s %7s %8s %8s %6s %7s %5s %7s %8s %12s %9s\n", "model", "grid", "inside",
                "concave", "regions", "boxes", "merged", "cuts", "splits", "outside", "plane dev %",
                "s");
  for (const auto& d : dirs) {
    try {
      const auto eq = d.find('=');
      const Row r =
          run(d.substr(0, eq), eq == std::string::npos ? std::string() : d.substr(eq + 1));
      if (json) {
        out.push_back({{"model", r.model},
                       {"grid", r.grid},
                       {"inside_cells", r.inside},
                       {"concave_edges", r.concave},
                       {"cut_regions", r.regions},
                       {"boxes", r.boxes},
                       {"merged", r.merged},
                       {"cuts", r.cuts},
                       {"pinwheel_splits", r.splits},
                       {"corners_not_located", r.not_located},
                       {"plane_max_deviation_percent", r.plane_deviation},
                       {"parts", r.parts},
                       {"parts_failing_checks", r.bad_parts},
                       {"stray_components", r.stray},
                       {"volume_error_percent", r.volume_error},
                       {"parts_seconds", r.parts_seconds},
                       {"seconds", r.seconds}});
      } else {
        std::printf("%-28s %4dx%3dx%3d %7d %8d %8d %6d %7d %5d %7d %8d %12.3f %9.3f\n",
                    r.model.c_str(), r.grid[0], r.grid[1], r.grid[2], r.inside, r.concave,
                    r.regions, r.boxes, r.merged, r.cuts, r.splits, r.not_located,
                    r.plane_deviation, r.seconds);
        if (r.parts >= 0)
          std::printf(
              "    parts %d, failing checks %d, stray components %d, volume error %.2e %%, %.1f "
              "s\n",
              r.parts, r.bad_parts, r.stray, r.volume_error, r.parts_seconds);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", d.c_str(), e.what());
    }
  }
  if (json) std::cout << out.dump(2) << "\n";
  return 0;
}
