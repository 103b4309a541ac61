//! The decomposition's steps and the chamber loop (see decompose.h).
#include "fabricate/decompose.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "fabricate/corners.h"

#include <fmt/format.h>

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

//! Lattice points per axis of a box's estimate: corners, quarters and middles of its edges.
constexpr int kLattice = 5;

int lattice_index(int i, int j, int k) { return i + kLattice * (j + kLattice * k); }

//! The box's lattice points in model space, index lattice_index(i, j, k).
std::vector<Vec3> mapped_lattice(const ToModel& to_model, const Extent& e) {
  std::vector<Vec3> out;
  for (int k = 0; k < kLattice; ++k)
    for (int j = 0; j < kLattice; ++j)
      for (int i = 0; i < kLattice; ++i) {
        const Vec3 t = Vec3(i, j, k) / (kLattice - 1);
        out.push_back(to_model(e.lo + t.cwiseProduct(e.hi - e.lo)));
      }
  return out;
}

//! Outward model-space normals of the box's six sides (low x, high x, low y, ...): from the
//! mapped middle of each side's opposite to it.
std::array<Vec3, 6> side_normals(const std::vector<Vec3>& lattice) {
  constexpr int m = kLattice / 2, l = kLattice - 1;
  const std::array<std::pair<int, int>, 3> faces{
      {{lattice_index(0, m, m), lattice_index(l, m, m)},
       {lattice_index(m, 0, m), lattice_index(m, l, m)},
       {lattice_index(m, m, 0), lattice_index(m, m, l)}}};
  std::array<Vec3, 6> out;
  for (int a = 0; a < 3; ++a) {
    const Vec3 axis = (lattice[faces[a].second] - lattice[faces[a].first]).normalized();
    out[2 * a] = -axis;
    out[2 * a + 1] = axis;
  }
  return out;
}

//! Whether side (axis, high) of the box has polycube across it, so that it will be a cut face,
//! flat, that the part can stand on (a side on the polycube's boundary is the solid's surface).
bool has_neighbour(const OccupancyGrid& g, const Box& b, int axis, bool high) {
  const int e1 = (axis + 1) % 3, e2 = (axis + 2) % 3;
  std::array<int, 3> c{};
  c[axis] = high ? b.hi[axis] : b.lo[axis] - 1;
  for (c[e1] = b.lo[e1]; c[e1] < b.hi[e1]; ++c[e1])
    for (c[e2] = b.lo[e2]; c[e2] < b.hi[e2]; ++c[e2])
      if (g.in(c)) return true;
  return false;
}

//! The estimated bases of the box's part: its sides that will be cut faces (all six when none
//! will, the solid in one piece).
std::vector<Vec3> estimated_bases(const OccupancyGrid& g, const Box& b,
                                  const std::vector<Vec3>& lattice) {
  const std::array<Vec3, 6> normals = side_normals(lattice);
  std::vector<Vec3> out;
  for (int s = 0; s < 6; ++s)
    if (has_neighbour(g, b, s / 2, s % 2 == 1)) out.push_back(normals[s]);
  if (out.empty()) out.assign(normals.begin(), normals.end());
  return out;
}

//! The estimate of whether the box's part fits the chamber: its mapped lattice standing on one
//! of its estimated bases.
bool estimate_fits(const ToModel& to_model, const OccupancyGrid& g, const Box& b,
                   const Chamber& chamber) {
  const std::vector<Vec3> lattice = mapped_lattice(to_model, extent_of(g, b));
  return fitting_base(lattice, estimated_bases(g, b, lattice), chamber) >= 0;
}

//! The polycube plane through the middle of the box, across its longest mapped axis.
std::pair<int, double> middle_plane(const ToModel& to_model, const Extent& e) {
  const std::vector<Vec3> lattice = mapped_lattice(to_model, e);
  constexpr int m = kLattice / 2, l = kLattice - 1;
  const std::array<double, 3> length{
      (lattice[lattice_index(l, m, m)] - lattice[lattice_index(0, m, m)]).norm(),
      (lattice[lattice_index(m, l, m)] - lattice[lattice_index(m, 0, m)]).norm(),
      (lattice[lattice_index(m, m, l)] - lattice[lattice_index(m, m, 0)]).norm()};
  const int axis =
      static_cast<int>(std::max_element(length.begin(), length.end()) - length.begin());
  return {axis, 0.5 * (e.lo[axis] + e.hi[axis])};
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
        static_cast<int>(std::lower_bound(pl.begin(), pl.end(), coordinate - 1e-9 * grid_diagonal(grid)) -
                         pl.begin());
    split_boxes(grid, partition, axis, k);
  }
  if (merge) merge_boxes(grid, partition, fits);
  Round r;
  // Prefer the cuts whose model-space plane keeps every box of the group on its side.
  const ToModel to_model(map);
  r.plan = plan_cuts(grid, partition, [&](const BoxPartition& p, const Cut& cut) {
    return fit_cut_plane(to_model, grid, p, cut).unkept_boxes == 0;
  });
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
      const std::array<Vec3, 6> sides = side_normals(mapped_lattice(to_model, extent_of(grid, b)));
      const std::vector<Vec3> bases(sides.begin(), sides.end());
      out.push_back(fitting_base(p.mesh.points, bases, chamber) >= 0 ? 0 : -1);
      continue;
    }
    std::vector<Vec3> normals;
    for (const FlatSide& s : p.sides) normals.push_back(s.normal);
    out.push_back(fitting_base(p.mesh.points, normals, chamber));
  }
  return out;
}

//! The grid with the forced planes, and the partition with its boxes split at them.
std::pair<OccupancyGrid, BoxPartition> forced_partition(
    const OccupancyGrid& base, const std::vector<std::pair<int, double>>& forced) {
  OccupancyGrid grid = base;
  for (const auto& [axis, coordinate] : forced) insert_plane(grid, axis, coordinate);
  BoxPartition partition = partition_boxes(grid);
  for (const auto& [axis, coordinate] : forced)
    split_boxes(grid, partition, axis, insert_plane(grid, axis, coordinate));
  return {std::move(grid), std::move(partition)};
}

//! Force middle planes until every box of the partition fits the chamber by the estimate.
//! \throw core::GeometryError when that takes more than kMaxBoxes boxes: the chamber is too
//!        small for this shape
void split_until_boxes_fit(const OccupancyGrid& base, const ToModel& to_model,
                           const Chamber& chamber, std::vector<std::pair<int, double>>& forced) {
  constexpr std::size_t kMaxBoxes = 400;
  for (;;) {
    const auto [grid, partition] = forced_partition(base, forced);
    const std::size_t before = forced.size();
    for (const Box& b : partition.boxes)
      if (!estimate_fits(to_model, grid, b, chamber))
        forced.push_back(middle_plane(to_model, extent_of(grid, b)));
    if (forced.size() == before) return;
    if (partition.boxes.size() > kMaxBoxes)
      throw core::GeometryError(fmt::format(
          "fabricate: the chamber {:g} x {:g} x {:g} is too small for this shape: {} boxes and "
          "some still do not fit; give a larger chamber",
          chamber.x, chamber.y, chamber.z, partition.boxes.size()));
  }
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
  std::vector<Extent> refused;                 // boxes whose real part did not fit
  const double tolerance = 1e-9 * grid_diagonal(base);  // relative: any unit cuts alike
  for (int round = 1;; ++round) {
    if (options.chamber.limited()) split_until_boxes_fit(base, to_model, options.chamber, forced);
    d.grid = base;
    for (const auto& [axis, coordinate] : forced) insert_plane(d.grid, axis, coordinate);
    const auto fits = [&](const Box& b) {
      const Extent e = extent_of(d.grid, b);
      for (const Extent& r : refused)
        if (contains(e, r, tolerance)) return false;
      return estimate_fits(to_model, d.grid, b, options.chamber);
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
    core::logger().info("fabricate: round {}: {} parts ({} do not fit the chamber), {:.1f} s",
                        round, d.parts.parts.size(), d.unfit_parts, clock.seconds());
    if (!options.chamber.limited() || d.unfit_parts == 0 || round >= options.max_rounds) break;
    // The estimate was wrong for these: never merge their boxes again, and split them.
    for (std::size_t i = 0; i < d.parts.parts.size(); ++i) {
      if (d.base[i] >= 0 || d.parts.parts[i].box < 0) continue;
      const Extent e =
          extent_of(d.grid, d.plan.partition.boxes[static_cast<std::size_t>(d.parts.parts[i].box)]);
      refused.push_back(e);
      forced.push_back(middle_plane(to_model, e));
    }
  }
  d.chamber_planes = static_cast<int>(forced.size());
  d.seconds = clock.seconds();
  return d;
}

}  // namespace polycube::fabricate
