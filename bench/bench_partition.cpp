//! Benchmark of the decomposition into parts (issue 20): for each simplified map given as a
//! directory holding model.mesh and polycube.mesh (the `simplify/` folder of `polycube run`), the
//! grid of chart planes, concave edges, boxes of the partition (thesis §6.2) and after merging,
//! the cuts of the plan (and boxes a pinwheel split), corners not located in a tet, the planes'
//! deviation from their points and the planes tilted to keep boxes on their sides; the time of
//! partition, merging, plan and planes (median of 3). Prints a text table, or JSON with --json.
//!
//! usage: bench_partition [--json] [--no-merge] [--chamber X Y Z | --chamber-fraction F]
//!                        DIR[=SOLID] ...
//!   --chamber-fraction F: a cubic chamber whose side is F times each model's diagonal.
//!   With SOLID (a surface file, or "map" for the boundary of the map's model tets) the whole
//!   decomposition runs (exact cuts included; median of 3) and its parts are checked: closed,
//!   outward, no self-intersection, volumes adding up, overlap and gap by sampling, the parts'
//!   own triangles on the solid's surface (fabricate/partition_check.h).
#include "core/log.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "core/types.h"
#include "fabricate/box_partition.h"
#include "fabricate/corners.h"
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"
#include "fabricate/decompose.h"
#include "fabricate/partition_check.h"
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
      not_located = 0, constrained = 0, unkept = 0;
  double plane_deviation = 0;  // largest over the cuts, % of the model diagonal
  double seconds = 0;          // median: partition, merging, plan, planes
  // With a solid: the whole decomposition (-1: no solid given).
  int parts = -1, bad_parts = 0, stray = 0, rounds = 0, unfit = 0;
  double volume_error = 0;                             // |sum - solid| / solid, %
  double overlap = 0, gap = 0, surface_deviation = 0;  // %, %, fraction of the diagonal
  double decompose_seconds = 0;                        // median
};

template <class F>
double median_seconds(F&& f) {
  std::vector<double> t;
  for (int i = 0; i < kRuns; ++i) {
    const core::Stopwatch clock;
    f();
    t.push_back(clock.seconds());
  }
  std::sort(t.begin(), t.end());
  return t[kRuns / 2];
}

void partition_figures(const core::PolycubeMap& map, bool merge, Row& r) {
  fabricate::OccupancyGrid g;
  fabricate::BoxPartition p;
  fabricate::CutPlan plan;
  std::vector<fabricate::CutPlane> planes;
  r.seconds = median_seconds([&] {
    g = fabricate::occupancy_grid(map);
    p = fabricate::partition_boxes(g);
    r.boxes = static_cast<int>(p.boxes.size());
    if (merge) fabricate::merge_boxes(g, p);
    plan = fabricate::plan_cuts(g, p);
    planes = fabricate::fit_cut_planes(map, g, plan);
  });
  r.regions = p.cut_regions;
  r.cuts = static_cast<int>(plan.cuts.size());
  r.splits = plan.split_boxes;
  r.not_located = fabricate::map_corners(map, g, plan.partition).not_located;
  const double diagonal = core::bounding_box(map.model).extent().norm();
  for (const auto& q : planes) {
    r.plane_deviation = std::max(r.plane_deviation, 100.0 * q.max_deviation / diagonal);
    r.constrained += q.constrained > 0 ? 1 : 0;
    r.unkept += q.unkept_boxes;
  }
  r.grid = {g.cells(0), g.cells(1), g.cells(2)};
  r.inside = static_cast<int>(std::count(g.inside.begin(), g.inside.end(), 1));
  r.concave = p.concave_edges;
  r.merged = static_cast<int>(p.boxes.size());
}

void decomposition_figures(const core::PolycubeMap& map, const core::TriMesh& solid,
                           const fabricate::DecomposeOptions& o, Row& r) {
  fabricate::Decomposition d;
  r.decompose_seconds = median_seconds([&] { d = fabricate::decompose(map, solid, o); });
  r.parts = static_cast<int>(d.parts.parts.size());
  r.rounds = d.rounds;
  r.unfit = d.unfit_parts;
  for (const auto& q : d.parts.parts) {
    r.bad_parts += (q.mesh.cells.empty() || !q.closed || !q.outward || q.self_intersecting) ? 1 : 0;
    r.stray += std::max(0, q.components - 1);
  }
  r.volume_error =
      100.0 * std::abs(d.parts.volume_sum - d.parts.solid_volume) / d.parts.solid_volume;
  const fabricate::PartitionCheck c = fabricate::check_partition(d.parts, solid);
  r.overlap = 100.0 * c.overlap;
  r.gap = 100.0 * c.gap;
  r.surface_deviation = c.surface_deviation;
}

Row run(const std::filesystem::path& dir, const std::string& solid_path,
        fabricate::DecomposeOptions o, double chamber_fraction) {
  const core::PolycubeMap map = io::read_polycube_map(dir / "model.mesh", dir / "polycube.mesh");
  if (chamber_fraction > 0) {
    const double side = chamber_fraction * core::bounding_box(map.model).extent().norm();
    o.chamber = {side, side, side};
  }
  Row r;
  r.model = dir.parent_path().filename().string();
  partition_figures(map, o.merge, r);
  if (!solid_path.empty())
    decomposition_figures(map,
                          solid_path == "map" ? core::boundary(map.model_mesh()).surface
                                              : io::read_surface(solid_path),
                          o, r);
  return r;
}

nlohmann::json to_json(const Row& r) {
  return {{"model", r.model},
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
          {"planes_constrained", r.constrained},
          {"boxes_unkept", r.unkept},
          {"seconds", r.seconds},
          {"parts", r.parts},
          {"parts_failing_checks", r.bad_parts},
          {"stray_components", r.stray},
          {"chamber_rounds", r.rounds},
          {"unfit_parts", r.unfit},
          {"volume_error_percent", r.volume_error},
          {"overlap_percent", r.overlap},
          {"gap_percent", r.gap},
          {"surface_deviation", r.surface_deviation},
          {"decompose_seconds", r.decompose_seconds}};
}

void print(const Row& r) {
  std::printf("%-22s %3dx%2dx%2d %6d %7d %7d %5d %6d %4d %6d %7d %9.3f %5d/%d %7.3f\n",
              r.model.c_str(), r.grid[0], r.grid[1], r.grid[2], r.inside, r.concave, r.regions,
              r.boxes, r.merged, r.cuts, r.splits, r.not_located, r.plane_deviation, r.constrained,
              r.unkept, r.seconds);
  if (r.parts >= 0)
    std::printf(
        "    parts %d (rounds %d, unfit %d), failing checks %d, stray components %d, volume "
        "error %.2e %%, overlap %.4f %%, gap %.4f %%, surface deviation %.2e, decomposition "
        "%.2f s\n",
        r.parts, r.rounds, r.unfit, r.bad_parts, r.stray, r.volume_error, r.overlap, r.gap,
        r.surface_deviation, r.decompose_seconds);
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  double chamber_fraction = 0;  // > 0: a cubic chamber of this fraction of each model's diagonal
  fabricate::DecomposeOptions options;
  std::vector<std::string> dirs;  // DIR or DIR=SOLID (the solid's surface: also cut the parts)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") {
      json = true;
    } else if (a == "--no-merge") {
      options.merge = false;
    } else if (a == "--chamber-fraction" && i + 1 < argc) {
      chamber_fraction = std::stod(argv[++i]);
    } else if (a == "--chamber" && i + 3 < argc) {
      options.chamber = {std::stod(argv[i + 1]), std::stod(argv[i + 2]), std::stod(argv[i + 3])};
      i += 3;
    } else {
      dirs.emplace_back(a);
    }
  }
  if (dirs.empty()) {
    std::cerr
        << "usage: bench_partition [--json] [--no-merge] [--chamber X Y Z | --chamber-fraction "
           "F] DIR[=SOLID] ... "
           "(each DIR with model.mesh and polycube.mesh)\n";
    return 2;
  }
  core::logger().set_level(spdlog::level::err);
  nlohmann::json out = nlohmann::json::array();
  if (!json)
    std::printf("%-22s %9s %6s %7s %7s %5s %6s %4s %6s %7s %9s %7s %7s\n", "model", "grid",
                "inside", "concave", "regions", "boxes", "merged", "cuts", "splits", "outside",
                "plane dev %", "tilted/unkept", "s");
  for (const auto& d : dirs) {
    try {
      const auto eq = d.find('=');
      const Row r = run(d.substr(0, eq), eq == std::string::npos ? std::string() : d.substr(eq + 1),
                        options, chamber_fraction);
      if (json)
        out.push_back(to_json(r));
      else
        print(r);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", d.c_str(), e.what());
    }
  }
  if (json) std::cout << out.dump(2) << "\n";
  return 0;
}
