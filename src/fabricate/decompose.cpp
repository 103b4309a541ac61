//! The decomposition's steps and the chamber loop (see decompose.h).
#include "fabricate/decompose.h"

#include "core/stopwatch.h"
#include "fabricate/corners.h"

#include <algorithm>
#include <utility>

namespace polycube::fabricate {

namespace {

using core::Vec3;

//! A box in polycube coordinates (grids of different rounds index the same box differently).
struct Extent {
  Vec3 lo, hi;
};

Extent extent_of(const OccupancyGrid& g, const Box& b) {
  return {box_corner(g, b, 0, 0, 0), box_corner(g, b, 1, 1, 1)};
}

bool contains(const Extent& outer, const Extent& inner, double tolerance) {
  for (int a = 0; a < 3; ++a)
    if (inner.lo[a] < outer.lo[a] - tolerance || inner.hi[a] > outer.hi[a] + tolerance)
      return false;
  return true;
}

//! The box's 27 lattice points (corners, edge and face middles, centre) in model space.
std::vector<Vec3> mapped_lattice(const ToModel& to_model, const Extent& e) {
  std::vector<Vec3> out;
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 3; ++i) {
        const Vec3 t(0.5 * i, 0.5 * j, 0.5 * k);
        out.push_back(to_model(e.lo + t.cwiseProduct(e.hi - e.lo)));
      }
  return out;
}

//! Model-space directions of the box's axes: from the mapped middle of its low face to that of
//! its high face. Lattice index i + 3 j + 9 k.
std::array<Vec3, 3> mapped_axes(const std::vector<Vec3>& lattice) {
  const std::array<std::pair<int, int>, 3> faces{{{12, 14}, {10, 16}, {4, 22}}};
  std::array<Vec3, 3> out;
  for (int a = 0; a < 3; ++a) out[a] = lattice[faces[a].second] - lattice[faces[a].first];
  return out;
}

//! The six sides of the box as bases: outward normals ± each mapped axis.
std::vector<Vec3> box_bases(const std::array<Vec3, 3>& axes) {
  std::vector<Vec3> out;
  for (const Vec3& a : axes) {
    out.push_back(-a.normalized());
    out.push_back(a.normalized());
  }
  return out;
}

//! One decomposition of the grid: partition, forced splits, merging, plan, planes, cuts.
struct Round {
  CutPlan plan;
  std::vector<CutPlane> planes;
  Parts parts;
  double partition_seconds = 0.0, cut_seconds = 0.0;
};

Round decompose_grid(const core::PolycubeMap& map, const core::TriMesh& solid,
                     const OccupancyGrid& grid, const std::vector<std::pair<int, double>>& forced,
                     bool merge, const std::function<bool(const Box&)>& fits) {
  const core::Stopwatch clock;
  BoxPartition partition = partition_boxes(grid);
  for (const auto& [axis, coordinate] : forced) {
    const auto& pl = grid.planes[axis];
    const int k =
        static_cast<int>(std::lower_bound(pl.begin(), pl.end(), coordinate - 1e-9) - pl.begin());
    split_boxes(grid, partition, axis, k);
  }
  if (merge) merge_boxes(grid, partition, fits);
  Round r;
  r.plan = plan_cuts(grid, partition);
  r.planes = fit_cut_planes(map, grid, r.plan);
  r.partition_seconds = clock.seconds();
  r.parts = cut_parts(solid, r.plan, r.planes, box_lookup(map, grid, r.plan.partition),
                      map_centres(ToModel(map), grid, r.plan.partition));
  r.cut_seconds = r.parts.seconds;
  return r;
}

//! Per part, the side it stands on: its largest side that fits the chamber (sides come largest
//! first); a part without flat sides (the solid in one piece) tries its box's mapped sides and
//! gets 0 when one fits.
std::vector<int> choose_bases(const Round& r, const OccupancyGrid& grid, const ToModel& to_model,
                              const Chamber& chamber) {
  std::vector<int> out;
  for (const Part& p : r.parts.parts) {
    if (p.sides.empty()) {
      const Box& b = r.plan.partition.boxes[static_cast<std::size_t>(std::max(p.box, 0))];
      const auto bases = box_bases(mapped_axes(mapped_lattice(to_model, extent_of(grid, b))));
      out.push_back(fitting_base(p.mesh.points, bases, chamber) >= 0 ? 0 : -1);
      continue;
    }
    std::vector<Vec3> normals;
    for (const FlatSide& s : p.sides) normals.push_back(s.normal);
    out.push_back(fitting_base(p.mesh.points, normals, chamber));
  }
  return out;
}

}  // namespace

Decomposition decompose(const core::PolycubeMap& map, const core::TriMesh& solid,
                        const DecomposeOptions& options) {
  const core::Stopwatch clock;
  const ToModel to_model(map);
  Decomposition d;
  const OccupancyGrid base = occupancy_grid(map);
  d.boxes = static_cast<int>(partition_boxes(base).boxes.size());
  std::vector<std::pair<int, double>> forced;  // (axis, polycube coordinate) split planes
  std::vector<Extent> refused;                 // boxes whose part was too large
  const double tolerance = 1e-9;
  for (int round = 1;; ++round) {
    d.grid = base;
    for (const auto& [axis, coordinate] : forced) insert_plane(d.grid, axis, coordinate);
    const auto fits = [&](const Box& b) {
      const Extent e = extent_of(d.grid, b);
      for (const Extent& r : refused)
        if (contains(e, r, tolerance)) return false;
      const std::vector<Vec3> lattice = mapped_lattice(to_model, e);
      return fitting_base(lattice, box_bases(mapped_axes(lattice)), options.chamber) >= 0;
    };
    Round r =
        decompose_grid(map, solid, d.grid, forced, options.merge,
                       options.chamber.limited() ? std::function<bool(const Box&)>(fits) : nullptr);
    d.base = choose_bases(r, d.grid, to_model, options.chamber);
    d.plan = std::move(r.plan);
    d.planes = std::move(r.planes);
    d.parts = std::move(r.parts);
    d.partition_seconds = r.partition_seconds;
    d.cut_seconds = r.cut_seconds;
    d.rounds = round;
    d.unfit_parts = static_cast<int>(std::count(d.base.begin(), d.base.end(), -1));
    if (!options.chamber.limited() || d.unfit_parts == 0 || round >= options.max_rounds) break;
    // Split each part that does not fit across its box's longest mapped axis.
    for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
      if (d.base[i] >= 0 || d.parts.parts[i].box < 0) continue;
      const Extent e =
          extent_of(d.grid, d.plan.partition.boxes[static_cast<std::size_t>(d.parts.parts[i].box)]);
      refused.push_back(e);
      const auto axes = mapped_axes(mapped_lattice(to_model, e));
      int longest = 0;
      for (int a = 1; a < 3; ++a)
        if (axes[a].norm() > axes[longest].norm()) longest = a;
      forced.emplace_back(longest, 0.5 * (e.lo[longest] + e.hi[longest]));
      ++d.chamber_planes;
    }
  }
  d.seconds = clock.seconds();
  return d;
}

}  // namespace polycube::fabricate
