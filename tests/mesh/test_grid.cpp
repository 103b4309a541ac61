// Gridding analytic polycube maps: exact positions, one hex per inside cell, closed quad
// surfaces, snapping defects, determinism.
#include "core/elements.h"
#include "core/errors.h"
#include "core/topology.h"
#include "mesh/grid.h"
#include "mesh/tet_locator.h"
#include "structure/analytic_maps.h"
#include "structure/validate.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

namespace polycube::mesh {
namespace {

using test::GridMap;
using test::Vec3;

constexpr std::array<std::array<int, 3>, 8> kCorner{
    {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};

//! Number of unit lattice cells whose centre satisfies `inside` (lattice coordinates), counted
//! by brute force over a box.
long long count_cells(const std::function<bool(const Vec3&)>& inside, int lo, int hi) {
  long long n = 0;
  for (int k = lo; k < hi; ++k)
    for (int j = lo; j < hi; ++j)
      for (int i = lo; i < hi; ++i) n += inside(Vec3(i + 0.5, j + 0.5, k + 0.5)) ? 1 : 0;
  return n;
}

//! The lattice structure of the result: every hex is a positively oriented unit cube of the
//! lattice, inside according to `inside` (lattice coordinates), no cell twice, and the count
//! equals the brute-force count of inside cells.
void expect_lattice(const GridResult& r, const std::function<bool(const Vec3&)>& inside, int lo,
                    int hi) {
  const auto& hp = r.hex_polycube;
  std::set<std::array<long long, 3>> seen;
  for (const auto& h : hp.cells) {
    const Vec3& p0 = hp.points[h[0]];
    for (int v = 0; v < 8; ++v) {
      const Vec3 expected = p0 + Vec3(kCorner[v][0], kCorner[v][1], kCorner[v][2]);
      ASSERT_EQ(hp.points[h[v]], expected) << "hex is not a lattice unit cube in elements.h order";
    }
    // positive orientation in polycube space (det(p1-p0, p3-p0, p4-p0) > 0, every corner)
    for (int i = 0; i < 8; ++i) {
      const auto& nb = core::kHexCornerNeighbors[i];
      const Vec3& p = hp.points[h[i]];
      EXPECT_GT(
          (hp.points[h[nb[0]]] - p).dot((hp.points[h[nb[1]]] - p).cross(hp.points[h[nb[2]]] - p)),
          0.0);
    }
    EXPECT_TRUE(inside(p0 + Vec3(0.5, 0.5, 0.5)));
    EXPECT_TRUE(
        seen.insert({std::llround(p0.x()), std::llround(p0.y()), std::llround(p0.z())}).second)
        << "duplicate hex";
  }
  EXPECT_EQ(static_cast<long long>(hp.cells.size()), count_cells(inside, lo, hi));
  EXPECT_EQ(r.hex_model.cells, hp.cells);
  EXPECT_EQ(r.hex_model.points.size(), hp.points.size());
}

//! Closed, manifold quad surface with the expected number of faces.
void expect_quads(const GridResult& r, long long expected) {
  const core::SurfaceReport rep = core::analyze_surface(r.quad_polycube);
  EXPECT_TRUE(rep.closed);
  EXPECT_EQ(rep.boundary_edges, 0);
  EXPECT_EQ(static_cast<long long>(r.quad_polycube.cells.size()), expected);
  EXPECT_EQ(r.quad_model.cells, r.quad_polycube.cells);
  EXPECT_GT(core::signed_volume(r.quad_polycube), 0.0);  // outward
}

//! Max distance between the model positions and f(lattice point).
double max_error(const GridResult& r, const std::function<Vec3(const Vec3&)>& f) {
  double e = 0.0;
  for (std::size_t v = 0; v < r.hex_polycube.points.size(); ++v)
    e = std::max(e, (r.hex_model.points[v] - f(r.hex_polycube.points[v])).norm());
  return e;
}

//! The L shape (kLVolume, kLArea) in lattice coordinates at integer scale s.
std::function<bool(const Vec3&)> l_inside(double s) {
  return [s](const Vec3& c) {
    const Vec3 p = c / s;
    return p.x() > 0 && p.y() > 0 && p.z() > 0 && p.x() < 2 && p.y() < 2 && p.z() < 1 &&
           (p.x() < 1 || p.y() < 1);
  };
}

TEST(Grid, IdentityLShape) {
  const GridMap g = test::l_shape(2);
  GridOptions o;
  o.scale = 4;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_EQ(r.scale, 4.0);
  EXPECT_EQ(r.hex_polycube.cells.size(), static_cast<std::size_t>(test::kLVolume * 64));
  expect_lattice(r, l_inside(4), -1, 10);
  expect_quads(r, static_cast<long long>(test::kLArea * 16));
  EXPECT_LT(max_error(r, [](const Vec3& q) { return Vec3(q / 4.0); }), 1e-9);
  EXPECT_EQ(r.points_failed, 0);
  EXPECT_EQ(r.points_located, static_cast<int>(r.hex_polycube.points.size()));
  EXPECT_FALSE(r.snapping.needed);
  EXPECT_TRUE(r.snapping.ok());
  EXPECT_EQ(r.inverted_model_hexes, 0);
}

TEST(Grid, GlobalShearIsExact) {
  auto affine = [](const Vec3& p) {
    return Vec3(p.x() + 0.3 * p.z() + 1.0, 0.8 * p.y() + 0.2 * p.x(), 1.5 * p.z() - 2.0);
  };
  const GridMap g = test::l_shape(1, affine);
  ASSERT_TRUE(structure::diagnose_map(g.map).valid());
  for (double s : {1.0, 3.0, 5.0}) {
    GridOptions o;
    o.scale = s;
    const GridResult r = grid_polycube(g.map, o);
    EXPECT_EQ(r.hex_polycube.cells.size(),
              static_cast<std::size_t>(std::llround(test::kLVolume * s * s * s)));
    expect_lattice(r, l_inside(s), -1, static_cast<int>(2 * s) + 2);
    expect_quads(r, std::llround(test::kLArea * s * s));
    EXPECT_LT(max_error(r, [&](const Vec3& q) { return affine(q / s); }), 1e-9) << "scale " << s;
    EXPECT_EQ(r.inverted_model_hexes, 0);
  }
}

TEST(Grid, PiecewiseAffineShearIsExact) {
  // shear only above z = 0.5, a plane made of tet faces of the r = 2 grid: affine on every tet
  auto shear = [](const Vec3& p) {
    return p.z() > 0.5 ? Vec3(p.x() + 0.6 * (p.z() - 0.5), p.y(), p.z()) : p;
  };
  const GridMap g = test::l_shape(2, shear);
  ASSERT_TRUE(structure::diagnose_map(g.map).valid());
  GridOptions o;
  o.scale = 6;
  const GridResult r = grid_polycube(g.map, o);
  expect_lattice(r, l_inside(6), -1, 14);
  expect_quads(r, std::llround(test::kLArea * 36));
  EXPECT_LT(max_error(r, [&](const Vec3& q) { return shear(q / 6.0); }), 1e-9);
}

Vec3 bend(const Vec3& p) {
  constexpr double R = 3.0;  // bend the L around the y axis: x becomes an arc of radius R + z
  return {(R + p.z()) * std::sin(p.x() / R), p.y(), (R + p.z()) * std::cos(p.x() / R) - R};
}

TEST(Grid, BendMatchesTheInterpolantAndConverges) {
  GridOptions o;
  o.scale = 4;
  double previous = 0.0;
  for (int res : {2, 4, 8}) {
    const GridMap g = test::l_shape(res, bend);
    ASSERT_TRUE(structure::diagnose_map(g.map).valid());
    const GridResult r = grid_polycube(g.map, o);
    expect_lattice(r, l_inside(4), -1, 10);
    // exact: the piecewise-linear map of the tets, evaluated independently
    const double pl = max_error(r, [&](const Vec3& q) {
      Vec3 out;
      EXPECT_TRUE(g.pl_image(q / 4.0, out));
      return out;
    });
    EXPECT_LT(pl, 1e-9) << "resolution " << res;
    // convergent: second order in the tet size
    const double err = max_error(r, [](const Vec3& q) { return bend(q / 4.0); });
    if (previous > 0.0) {
      EXPECT_LT(err, previous / 3.0) << "resolution " << res;
    }
    EXPECT_LT(err, 0.05);
    previous = err;
  }
}

TEST(Grid, BoxToCylinder) {
  // the square cross-section [-1,1]^2 is mapped onto the unit disc radially, z kept
  auto disc = [](const Vec3& p) {
    const double r2 = std::hypot(p.x(), p.y());
    const double f = r2 > 0 ? std::max(std::abs(p.x()), std::abs(p.y())) / r2 : 1.0;
    return Vec3(f * p.x(), f * p.y(), p.z());
  };
  const GridMap g = test::make_grid_map(
      test::uniform(-1, 1, 8), test::uniform(-1, 1, 8), test::uniform(0, 1, 4),
      [](const Vec3&) { return true; }, disc);
  ASSERT_TRUE(structure::diagnose_map(g.map).valid());
  GridOptions o;
  o.scale = 3;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_EQ(r.hex_polycube.cells.size(), 6u * 6u * 3u);
  expect_lattice(
      r,
      [](const Vec3& c) {
        return std::abs(c.x()) < 3 && std::abs(c.y()) < 3 && c.z() > 0 && c.z() < 3;
      },
      -4, 4);
  expect_quads(r, 2 * 36 + 4 * 18);
  EXPECT_LT(max_error(r,
                      [&](const Vec3& q) {
                        Vec3 out;
                        EXPECT_TRUE(g.pl_image(q / 3.0, out));
                        return out;
                      }),
            1e-9);
  // the side of the box lands on the cylinder's side up to the chord error of the tet grid
  for (std::size_t v = 0; v < r.quad_polycube.points.size(); ++v) {
    const Vec3& q = r.quad_polycube.points[v];
    if (std::max(std::abs(q.x()), std::abs(q.y())) == 3.0) {
      const double rad = std::hypot(r.quad_model.points[v].x(), r.quad_model.points[v].y());
      EXPECT_LE(rad, 1.0 + 1e-12);
      EXPECT_GT(rad,
                std::cos(M_PI / 16));  // chord of a grid step (1/8 of a quarter circle at worst)
    }
  }
}

TEST(Grid, NonIntegerScaleWithoutCollapseIsExact) {
  // levels 0, 1, 2 at scale 2.5 -> 0, 2.5, 5 -> rounded 0, 3, 5: distinct, so the snapping map is
  // the per-axis piecewise-linear map and the model positions follow it exactly
  const GridMap g = test::l_shape(2);
  GridOptions o;
  o.scale = 2.5;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_TRUE(r.snapping.needed);
  EXPECT_TRUE(r.snapping.ok());
  EXPECT_FALSE(r.snapping.deformed);
  EXPECT_GT(r.snapping.corners_moved, 0);
  EXPECT_NEAR(r.snapping.max_displacement, 0.5, 1e-12);
  auto snapped_l = [](const Vec3& c) {
    return c.x() > 0 && c.y() > 0 && c.z() > 0 && c.x() < 5 && c.y() < 5 && c.z() < 3 &&
           (c.x() < 3 || c.y() < 3);
  };
  expect_lattice(r, snapped_l, -1, 7);
  EXPECT_EQ(r.hex_polycube.cells.size(), 63u);
  auto finv = [](double n) {
    return n <= 3 ? n / 3.0 : 1.0 + (n - 3.0) / 2.0;
  };                                               // 0->0, 3->1, 5->2
  auto finv_z = [](double n) { return n / 3.0; };  // 0->0, 3->1
  EXPECT_LT(
      max_error(r, [&](const Vec3& q) { return Vec3(finv(q.x()), finv(q.y()), finv_z(q.z())); }),
      1e-9);
}

TEST(Grid, TargetHexCount) {
  const GridMap g = test::l_shape(2);
  for (int target : {200, 1000, 5000}) {
    GridOptions o;
    o.target_hexes = target;
    const GridResult r = grid_polycube(g.map, o);
    const double n = static_cast<double>(r.hex_polycube.cells.size());
    EXPECT_LT(std::abs(n - target) / target, 0.25)
        << "target " << target << " got " << n << " at scale " << r.scale;
    // the count is the lattice's at the chosen scale
    const double s = r.scale;
    const double a = std::round(s), b = std::round(2 * s);
    auto inside = [&](const Vec3& c) {
      return c.x() > 0 && c.y() > 0 && c.z() > 0 && c.x() < b && c.y() < b && c.z() < a &&
             (c.x() < a || c.y() < a);
    };
    EXPECT_EQ(static_cast<long long>(n), count_cells(inside, -1, static_cast<int>(b) + 1));
  }
  GridOptions q;
  q.target_quads = 600;
  const GridResult rq = grid_polycube(g.map, q);
  EXPECT_LT(std::abs(static_cast<double>(rq.quad_polycube.cells.size()) - 600) / 600, 0.25);
}

//! [0,2]x[0,1]x[0,1] with a step [0,1]x[0,1]x[1,1.3] on its left half.
GridMap step_03() {
  return test::make_grid_map(
      test::uniform(0, 2, 4), test::uniform(0, 1, 2), {0, 0.5, 1, 1.3},
      [](const Vec3& c) { return c.z() < 1 || c.x() < 1; }, [](const Vec3& p) { return p; });
}

TEST(Grid, IntegerPolycubeIsNeverScaledBelowOne) {
  // the L's planes are at integers (a simplified polycube): a target below its 3 unit cells
  // would merge planes at a scale < 1, so the scale stays 1 and the structure is kept
  const GridMap g = test::l_shape(2);
  for (int target : {1, 2}) {
    GridOptions o;
    o.target_hexes = target;
    const GridResult r = grid_polycube(g.map, o);
    EXPECT_EQ(r.scale, 1.0);
    EXPECT_TRUE(r.snapping.ok());
    EXPECT_EQ(r.snapping.collapsed_levels, 0);
    EXPECT_EQ(r.hex_polycube.cells.size(), static_cast<std::size_t>(test::kLVolume));
  }
  // a polycube with a plane off the integers may go below 1 (and is reported when it breaks)
  GridOptions o;
  o.target_hexes = 1;
  const GridResult r = grid_polycube(step_03().map, o);
  EXPECT_LT(r.scale, 1.0);
}

TEST(Grid, MapSizingFollowsTheStretch) {
  // model = polycube stretched 3x along x: with Map sizing each unit interval along x gets three
  // times the cells of one along y or z, so the model hexes are cubes; the per-axis map is
  // piecewise linear, so the positions are exact and the L's planes land on integers.
  auto stretch = [](const Vec3& p) { return Vec3(3.0 * p.x(), p.y(), p.z()); };
  const GridMap g = test::l_shape(2, stretch);
  for (int target : {1200, 5000}) {
    GridOptions o;
    o.sizing = GridSizing::Map;
    o.target_hexes = target;
    const GridResult r = grid_polycube(g.map, o);
    EXPECT_TRUE(r.snapping.ok());
    EXPECT_EQ(r.snapping.collapsed_levels, 0);
    const int nx = (r.lattice_max[0] - r.lattice_min[0]) / 2;  // cells per unit interval
    const int ny = (r.lattice_max[1] - r.lattice_min[1]) / 2;
    const int nz = r.lattice_max[2] - r.lattice_min[2];
    EXPECT_EQ(nx, std::lround(3.0 * r.scale)) << "target " << target;
    EXPECT_EQ(ny, std::lround(r.scale));
    EXPECT_EQ(nz, ny);
    EXPECT_LE(std::abs(nx - 3 * ny), 1);
    const double n = static_cast<double>(r.hex_polycube.cells.size());
    EXPECT_EQ(r.hex_polycube.cells.size(), static_cast<std::size_t>(3 * nx * ny * nz));
    EXPECT_LT(std::abs(n - target) / target, 0.25) << "target " << target << " got " << n;
    auto to_model = [&](const Vec3& q) {
      return stretch(Vec3((q.x() - r.lattice_min[0]) / nx, (q.y() - r.lattice_min[1]) / ny,
                          (q.z() - r.lattice_min[2]) / nz));
    };
    EXPECT_LT(max_error(r, to_model), 1e-9);
    EXPECT_EQ(r.inverted_model_hexes, 0);
    // model hexes: edges along x and along y within one rounding step of each other
    EXPECT_LT(std::abs(3.0 / nx - 1.0 / ny), 1.0 / ny / ny + 1e-12);
  }
}

// refine_near doubles the cells of the intervals between chart planes that hold the point, on
// each axis, and no others: on the L at scale 4, a point in the corner cube gives its x, y and z
// intervals 8 cells instead of 4; the per-axis map stays piecewise linear, so the positions are
// exact. A point on a chart plane refines the intervals on both sides.
TEST(Grid, RefineNearDoublesTheCellsOfTheIntervalsThatHoldThePoint) {
  auto affine = [](const Vec3& p) { return Vec3(p.x() + 0.3 * p.z() + 1.0, 0.8 * p.y(), 1.5 * p.z()); };
  const GridMap g = test::l_shape(2, affine);
  GridOptions o;
  o.scale = 4;
  const std::vector<Vec3> near = polycube_points(g.map, {affine(Vec3(0.5, 0.25, 0.5))});
  ASSERT_EQ(near.size(), 1u);
  EXPECT_LT((near[0] - Vec3(0.5, 0.25, 0.5)).norm(), 1e-9);
  o.refine_near = near;
  const GridResult r = grid_polycube(g.map, o);
  // x and y: [0, 1] 8 cells, [1, 2] 4; z: [0, 1] 8. Boxes (0,0), (1,0), (0,1) of the L.
  EXPECT_EQ(r.hex_polycube.cells.size(), static_cast<std::size_t>(8 * 8 * 8 + 4 * 8 * 8 + 8 * 4 * 8));
  EXPECT_EQ(r.lattice_max[0] - r.lattice_min[0], 12);
  EXPECT_EQ(r.lattice_max[1] - r.lattice_min[1], 12);
  EXPECT_EQ(r.lattice_max[2] - r.lattice_min[2], 8);
  auto axis = [](double c) { return c <= 8 ? c / 8 : 1 + (c - 8) / 4; };  // lattice -> polycube
  EXPECT_LT(max_error(r, [&](const Vec3& q) { return affine(Vec3(axis(q.x()), axis(q.y()), q.z() / 8)); }), 1e-9);
  EXPECT_EQ(r.inverted_model_hexes, 0);
  EXPECT_TRUE(r.snapping.ok());
  EXPECT_FALSE(r.snapping.needed);
  const core::SurfaceReport rep = core::analyze_surface(r.quad_polycube);
  EXPECT_TRUE(rep.closed);
  EXPECT_EQ(rep.boundary_edges, 0);

  // On the plane x = 1: both x intervals doubled; y and z as before.
  o.refine_near = {Vec3(1.0, 0.25, 0.5)};
  EXPECT_EQ(grid_polycube(g.map, o).hex_polycube.cells.size(), static_cast<std::size_t>(8 * 8 * 8 + 8 * 8 * 8 + 8 * 4 * 8));
  // Factor 1, or no point: the plain grid.
  o.refine_factor = 1;
  EXPECT_EQ(grid_polycube(g.map, o).hex_polycube.cells.size(), static_cast<std::size_t>(3 * 64));
  o.refine_factor = 0;
  EXPECT_THROW((void)grid_polycube(g.map, o), core::InputError);
}

// On an integer polycube the refined cells fill the unit slab around the point, not the whole
// interval between chart planes: a 4 x 3 x 2 box at scale 1 and a point at (1.5, 0.5, 1.2) get
// 5 x 4 x 3 cells (x: [0,1] 1, [1,2] 2, [2,4] 2; y: [0,1] 2, [1,3] 2; z: [0,1] 1, [1,2] 2) instead
// of 4 x 3 x 2, with the positions still exact.
TEST(Grid, RefineNearFillsTheUnitSlabOfAnIntegerPolycube) {
  auto shear = [](const Vec3& p) { return Vec3(p.x() + 0.2 * p.y(), p.y(), 0.5 * p.z() + 0.1 * p.x()); };
  const GridMap g = test::make_grid_map(
      test::uniform(0, 4, 4), test::uniform(0, 3, 3), test::uniform(0, 2, 2), [](const Vec3&) { return true; },
      shear);
  GridOptions o;
  o.scale = 1;
  ASSERT_EQ(grid_polycube(g.map, o).hex_polycube.cells.size(), 24u);
  o.refine_near = {Vec3(1.5, 0.5, 1.2)};
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_EQ(r.hex_polycube.cells.size(), 60u);
  auto piecewise = [](double c, const std::vector<double>& lattice, const std::vector<double>& poly) {
    std::size_t i = 0;
    while (i + 2 < lattice.size() && c > lattice[i + 1]) ++i;
    return poly[i] + (c - lattice[i]) / (lattice[i + 1] - lattice[i]) * (poly[i + 1] - poly[i]);
  };
  auto to_model = [&](const Vec3& q) {
    return shear(Vec3(piecewise(q.x() - r.lattice_min[0], {0, 1, 3, 5}, {0, 1, 2, 4}),
                      piecewise(q.y() - r.lattice_min[1], {0, 2, 4}, {0, 1, 3}),
                      piecewise(q.z() - r.lattice_min[2], {0, 1, 3}, {0, 1, 2})));
  };
  EXPECT_LT(max_error(r, to_model), 1e-9);
  EXPECT_EQ(r.inverted_model_hexes, 0);
  EXPECT_TRUE(r.snapping.ok());
}

TEST(Grid, MapSizingNeverSnaps) {
  // step_03 has a plane at z = 1.3 (model = polycube): uniform sizing at scale 0.8 merges levels
  // 1 and 1.3; Map sizing gives every interval at least one cell, so nothing collapses
  GridOptions u;
  u.scale = 0.8;
  const GridResult ru = grid_polycube(step_03().map, u);
  EXPECT_GT(ru.snapping.collapsed_levels, 0);
  GridOptions m = u;
  m.sizing = GridSizing::Map;
  const GridResult rm = grid_polycube(step_03().map, m);
  EXPECT_EQ(rm.snapping.collapsed_levels, 0);
  EXPECT_TRUE(rm.snapping.ok());
  EXPECT_EQ(rm.inverted_model_hexes, 0);
  // one cell per unit interval in x and y, one per z interval: 2 x 1 below z = 1, 1 in the step
  EXPECT_EQ(rm.hex_polycube.cells.size(), 3u);
  const core::SurfaceReport rep = core::analyze_surface(rm.quad_polycube);
  EXPECT_TRUE(rep.closed);
  EXPECT_EQ(rep.boundary_edges, 0);
}

int count_kind(const SnapReport& r, DefectKind k) {
  return static_cast<int>(std::count_if(r.defects.begin(), r.defects.end(),
                                        [&](const SnapDefect& d) { return d.kind == k; }));
}

TEST(Grid, NaiveSnappingMergesCorners) {
  const GridMap g = step_03();
  ASSERT_TRUE(structure::diagnose_map(g.map).valid());
  GridOptions o;
  o.scale = 1;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_TRUE(r.snapping.deformed);
  EXPECT_EQ(r.snapping.collapsed_levels, 1);
  ASSERT_FALSE(r.snapping.ok());
  // the step's two corners at x = 1 on top (z = 1.3) merge with the two below them (z = 1)
  EXPECT_EQ(count_kind(r.snapping, DefectKind::CornersMerged), 2);
  for (const SnapDefect& d : r.snapping.defects)
    if (d.kind == DefectKind::CornersMerged) {
      ASSERT_EQ(d.positions.size(), 2u);
      EXPECT_DOUBLE_EQ(d.lattice.x(), 1.0);
      EXPECT_DOUBLE_EQ(d.lattice.z(), 1.0);
      std::set<double> zs{d.positions[0].z(), d.positions[1].z()};
      EXPECT_EQ(zs, (std::set<double>{1.0, 1.3}));
    }
  EXPECT_EQ(count_kind(r.snapping, DefectKind::EdgeCollapsed), 2);   // the step's vertical edges
  EXPECT_EQ(count_kind(r.snapping, DefectKind::ChartCollapsed), 1);  // the step's +X face
  EXPECT_NE(r.snapping.summary().find("corners merged"), std::string::npos);
  // the (broken) result is still a well-formed lattice: the snapped solid is the 2 x 1 x 1 box
  EXPECT_EQ(r.hex_polycube.cells.size(), 2u);
}

TEST(Grid, NaiveSnappingPushesACornerOntoAFacet) {
  // a C shape: base [0,3]x[0,1]x[0,1], pillar [0,1]x[0,1]x[1,1.4], overhang
  // [0,2.4]x[0,1]x[1.4,2.4]; at scale 1 the overhang's far bottom corners (2.4, *, 1.4) round onto
  // the base's top (z = 1)
  const GridMap g = test::make_grid_map(
      test::merged(test::uniform(0, 3, 6), {2.4}), test::uniform(0, 1, 2),
      test::merged(test::uniform(0, 1, 2), {1.4, 1.9, 2.4}),
      [](const Vec3& c) {
        return c.z() < 1 || (c.z() < 1.4 && c.x() < 1) ||
               (c.z() > 1.4 && c.z() < 2.4 && c.x() < 2.4);
      },
      [](const Vec3& p) { return p; });
  ASSERT_TRUE(structure::diagnose_map(g.map).valid());
  GridOptions o;
  o.scale = 1;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_EQ(count_kind(r.snapping, DefectKind::CornerOnFacet), 2);
  for (const SnapDefect& d : r.snapping.defects)
    if (d.kind == DefectKind::CornerOnFacet) {
      EXPECT_NEAR(d.positions[0].x(), 2.4, 1e-12);
      EXPECT_NEAR(d.positions[0].z(), 1.4, 1e-12);
      EXPECT_EQ(d.lattice, Vec3(2, d.lattice.y(), 1));
    }
  EXPECT_NE(r.snapping.summary().find("pushed onto chart"), std::string::npos)
      << r.snapping.summary();
}

TEST(Grid, BenignCollapseIsNotADefect) {
  // two separate towers on a base, 2.0 and 2.2 high: at scale 1 both tops round to z = 2, which
  // aligns them (what simplification aims for) without breaking anything
  const GridMap g = test::make_grid_map(
      test::uniform(0, 3, 6), test::uniform(0, 1, 2), test::merged(test::uniform(0, 2, 4), {2.2}),
      [](const Vec3& c) {
        return c.z() < 1 || (c.z() < 2 && c.x() < 1) || (c.z() < 2.2 && c.x() > 2);
      },
      [](const Vec3& p) { return p; });
  GridOptions o;
  o.scale = 1;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_TRUE(r.snapping.deformed);
  EXPECT_EQ(r.snapping.collapsed_levels, 1);
  EXPECT_TRUE(r.snapping.ok()) << r.snapping.summary();
  EXPECT_EQ(r.points_failed, 0);
  EXPECT_EQ(r.hex_polycube.cells.size(), 5u);
  EXPECT_EQ(r.inverted_model_hexes, 0);
  // the lattice tops (z = 2) map back onto the model's tops: z = 2 on the left, 2.2 on the right
  int tops = 0;
  for (std::size_t v = 0; v < r.hex_polycube.points.size(); ++v) {
    const Vec3& q = r.hex_polycube.points[v];
    if (q.z() != 2.0) continue;
    ++tops;
    EXPECT_NEAR(r.hex_model.points[v].z(), q.x() <= 1 ? 2.0 : 2.2, 1e-9) << q.transpose();
  }
  EXPECT_EQ(tops, 8);
}

TEST(TetLocator, SharedFacesResolveDeterministically) {
  const GridMap g = test::l_shape(1);
  const TetLocator loc(g.map.tets, g.map.polycube, 1e-9);
  // a grid vertex is shared by many tets: the answer is the same tet every time, and it holds the
  // point
  const auto a = loc.locate(Vec3(1, 1, 0.5));
  const auto b = loc.locate(Vec3(1, 1, 0.5));
  ASSERT_GE(a.tet, 0);
  EXPECT_EQ(a.tet, b.tet);
  EXPECT_GE(a.score, -1e-12);
  EXPECT_NEAR(a.bary[0] + a.bary[1] + a.bary[2] + a.bary[3], 1.0, 1e-12);
  // outside the L (in its notch) and outside the box: nothing
  EXPECT_EQ(loc.locate(Vec3(1.5, 1.5, 0.5)).tet, -1);
  EXPECT_EQ(loc.locate(Vec3(5, 5, 5)).tet, -1);
  // on the boundary, within the tolerance: found
  EXPECT_GE(loc.locate(Vec3(0.3, 0.2, 1.0 + 1e-10)).tet, 0);
  EXPECT_EQ(loc.locate(Vec3(0.3, 0.2, 1.0 + 1e-6)).tet, -1);
  // nearest: the closest tet even outside
  EXPECT_GE(loc.nearest(Vec3(0.3, 0.2, 1.1), 2).tet, 0);
}

TEST(Grid, CoarserScaleOfTheStepIsClean) {
  // the same step at scale 10: 10, 13 are distinct integers, no defect, exact
  const GridMap g = step_03();
  GridOptions o;
  o.scale = 10;
  const GridResult r = grid_polycube(g.map, o);
  EXPECT_TRUE(r.snapping.ok());
  EXPECT_FALSE(r.snapping.needed);
  EXPECT_EQ(r.hex_polycube.cells.size(), 20u * 10u * 10u + 10u * 10u * 3u);
  EXPECT_LT(max_error(r, [](const Vec3& q) { return Vec3(q / 10.0); }), 1e-9);
}

TEST(Grid, Deterministic) {
  const GridMap g = test::l_shape(3, bend);
  GridOptions o;
  o.scale = 3.7;
  const GridResult a = grid_polycube(g.map, o);
  const GridResult b = grid_polycube(g.map, o);
  EXPECT_EQ(a.hex_model.cells, b.hex_model.cells);
  EXPECT_EQ(a.hex_model.points, b.hex_model.points);
  EXPECT_EQ(a.quad_model.cells, b.quad_model.cells);
  EXPECT_EQ(a.quad_model.points, b.quad_model.points);
}

TEST(Grid, SurfaceOnlyGivesTheSameQuads) {
  const GridMap g = test::l_shape(2, bend);
  GridOptions o;
  o.scale = 5;
  const GridResult full = grid_polycube(g.map, o);
  o.volume = false;
  const GridResult surf = grid_polycube(g.map, o);
  EXPECT_TRUE(surf.hex_model.cells.empty());
  EXPECT_EQ(surf.quad_model.cells, full.quad_model.cells);
  EXPECT_EQ(surf.quad_model.points, full.quad_model.points);
  EXPECT_LT(surf.points_located, full.points_located);
}

TEST(Grid, BadOptions) {
  const GridMap g = test::l_shape(1);
  GridOptions o;
  o.scale = -1;
  EXPECT_THROW(grid_polycube(g.map, o), core::InputError);
  o.scale = 0.1;  // every level rounds to 0: no cell
  EXPECT_THROW(grid_polycube(g.map, o), core::GeometryError);
  o.scale = 1e5;
  EXPECT_THROW(grid_polycube(g.map, o), core::InputError);  // lattice too large
}

}  // namespace
}  // namespace polycube::mesh
