// Hex-mesh optimization: untangling, feature preservation, determinism, the rockerarm.
#include "core/errors.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "optimize/features.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "optimize_fixtures.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <filesystem>

namespace polycube {
namespace {

bool on_wall(double x) { return x == 0.0 || x == 1.0; }
bool interior(const core::Vec3& p) { return !on_wall(p.x()) && !on_wall(p.y()) && !on_wall(p.z()); }

TEST(HexOptimize, TangledGridUntangles) {
  core::HexMesh m = test::box_grid(5, 5, 5);
  // Fold the interior: mirror a block of interior vertices through the centre and push two
  // more across their neighbours, so several hexes are inverted.
  for (auto& p : m.points)
    if (interior(p) && p.x() < 0.5) p.x() = 1.0 - p.x() - 0.05;
  ASSERT_GT(quality::scaled_jacobian(m).inverted, 0);
  const auto r = optimize::optimize_hex_mesh(m, test::box_surface());
  EXPECT_GT(r.before.inverted, 0);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(r.after.inverted + r.after.invalid, 0);
  EXPECT_GT(r.after.min, 0.0);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
}

// One interior vertex of a 10 x 10 x 10 grid pushed through its neighbour: with
// local_untangle_rings the untangling moves only the vertices of the hexes within that many rings
// of the inverted ones, and still leaves none inverted; the whole-mesh untangling moves vertices
// far from the tangle too (so the test tells the two apart).
TEST(HexOptimize, LocalUntanglingMovesOnlyTheRegionAroundTheTangle) {
  const core::Vec3 pushed(0.3, 0.5, 0.5);
  const auto tangled = [&] {
    core::HexMesh m = test::box_grid(10, 10, 10);
    for (auto& p : m.points)
      if ((p - pushed).norm() < 1e-9) p.x() += 0.17;  // past its neighbour at 0.4
    return m;
  };
  const core::HexMesh start = tangled();
  ASSERT_GT(quality::scaled_jacobian(start).inverted, 0);
  // The inverted hexes are those around the pushed vertex and the one it crossed (x from 0.2 to
  // 0.5, y and z from 0.4 to 0.6); one ring more: x from 0.1 to 0.6, y and z from 0.3 to 0.7.
  const auto far = [&](const core::Vec3& p) {
    return p.x() < 0.1 - 1e-9 || p.x() > 0.6 + 1e-9 || std::abs(p.y() - 0.5) > 0.2 + 1e-9 ||
           std::abs(p.z() - 0.5) > 0.2 + 1e-9;
  };
  const auto moved_far = [&](const core::HexMesh& m) {
    int n = 0;
    for (std::size_t v = 0; v < m.points.size(); ++v)
      n += far(start.points[v]) && m.points[v] != start.points[v] ? 1 : 0;
    return n;
  };
  optimize::OptimizeOptions o;
  o.quality_rounds = 0;
  o.drift_retries = 0;
  o.polish = false;  // the untangling alone: the polish moves the worst hexes' vertices anywhere
  o.local_untangle_rings = 1;
  core::HexMesh local = tangled();
  const auto r = optimize::optimize_hex_mesh(local, test::box_surface(), o);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(r.after.inverted + r.after.invalid, 0);
  EXPECT_EQ(moved_far(local), 0);
  EXPECT_NE(local.points, start.points);

  o.local_untangle_rings = 0;
  core::HexMesh whole = tangled();
  EXPECT_TRUE(optimize::optimize_hex_mesh(whole, test::box_surface(), o).untangled);
  EXPECT_GT(moved_far(whole), 100);
}

// The untangling's σ floor sets how fast ε falls: two vertices of a box's top face swapped (the
// quads between them folded over) unfold with the optimizer's default floor (0.2) in fewer outer
// iterations than with the paper's 0.1 (19 against 30 when written).
TEST(HexOptimize, AHigherSigmaFloorUntanglesInFewerIterations) {
  const auto iterations = [](double sigma) {
    core::HexMesh m = test::box_grid(6, 6, 6);
    int a = -1, b = -1;
    for (int v = 0; v < m.num_points(); ++v) {
      if ((m.points[v] - core::Vec3(1.0 / 6, 0.5, 1)).norm() < 1e-9) a = v;
      if ((m.points[v] - core::Vec3(4.0 / 6, 0.5, 1)).norm() < 1e-9) b = v;
    }
    std::swap(m.points[a], m.points[b]);
    optimize::OptimizeOptions o;
    o.untangle_min_sigma = sigma;
    o.quality_rounds = 0;
    const auto r = optimize::optimize_hex_mesh(m, test::box_surface(), o);
    EXPECT_TRUE(r.untangled) << sigma;
    return r.untangle.iterations;
  };
  EXPECT_EQ(optimize::OptimizeOptions{}.untangle_min_sigma, 0.2);
  const int fast = iterations(0.2), paper = iterations(0.1);
  EXPECT_LT(fast, paper) << fast << " " << paper;
}

TEST(HexOptimize, TangledBoundaryUntanglesOnTheSurface) {
  core::HexMesh m = test::box_grid(4, 4, 4);
  // Swap two boundary vertices of the top face: the quads around them fold.
  auto find = [&](const core::Vec3& q) {
    return static_cast<int>(std::find_if(m.points.begin(), m.points.end(),
                                         [&](const core::Vec3& p) { return (p - q).norm() < 1e-12; }) -
                            m.points.begin());
  };
  std::swap(m.points[find({0.25, 0.5, 1})], m.points[find({0.5, 0.5, 1})]);
  ASSERT_GT(quality::scaled_jacobian(m).inverted, 0);
  const core::TriMesh box = test::box_surface();
  optimize::optimize_hex_mesh(m, box);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
  const auto d = quality::hausdorff_distance(m, box);
  EXPECT_LT(d.relative, 0.01);
}

// A grid of perfect cubes on its box: no quality round can raise the minimum (1), so none is
// kept or climbs; the rounds stop after round 0 (which never counts) and `patience` more (the
// default: one), and the mesh is the one all six rounds give.
TEST(HexOptimize, QualityRoundsStopAfterPatienceRoundsInARowNotKept) {
  core::HexMesh stopped = test::box_grid(4, 4, 4);
  core::HexMesh two = stopped;
  core::HexMesh all = stopped;
  const core::TriMesh box = test::box_surface();
  EXPECT_EQ(optimize::OptimizeOptions{}.quality_patience, 1);
  const auto r = optimize::optimize_hex_mesh(stopped, box);
  EXPECT_EQ(r.rounds_accepted, 0);
  EXPECT_EQ(r.rounds_run, 2);
  optimize::OptimizeOptions p;
  p.quality_patience = 2;
  const auto r_two = optimize::optimize_hex_mesh(two, box, p);
  EXPECT_EQ(r_two.rounds_run, 3);
  EXPECT_EQ(two.points, stopped.points);
  optimize::OptimizeOptions o;
  o.quality_patience = 0;
  const auto r_all = optimize::optimize_hex_mesh(all, box, o);
  EXPECT_EQ(r_all.rounds_accepted, 0);
  EXPECT_EQ(r_all.rounds_run, o.quality_rounds);
  EXPECT_EQ(stopped.points, all.points);
  EXPECT_DOUBLE_EQ(r.after.min, 1.0);
}

TEST(HexOptimize, PerturbedBoxKeepsCornersAndEdges) {
  const int n = 6;
  const double h = 1.0 / n;
  core::HexMesh m = test::box_grid(n, n, n);
  const core::HexMesh grid = m;
  test::perturb(m, 0.2 * h, 11, [](const core::Vec3&) { return true; });
  const auto before = quality::scaled_jacobian(m);
  const auto r = optimize::optimize_hex_mesh(m, test::box_surface());
  EXPECT_EQ(r.corner_vertices, 8);
  EXPECT_EQ(r.feature_vertices, 12 * (n - 1));
  EXPECT_TRUE(r.untangled);
  EXPECT_GT(r.after.min, before.min);
  EXPECT_GE(r.after.average, before.average);
  for (int v = 0; v < m.num_points(); ++v) {
    const core::Vec3& g = grid.points[v];
    const core::Vec3& p = m.points[v];
    const int walls = (g.array() == 0 || g.array() == 1).count();
    // distance to the walls the grid vertex lies on (its face, edge or corner)
    double off = 0;
    for (int d = 0; d < 3; ++d)
      if (on_wall(g[d])) off = std::max(off, std::abs(p[d] - g[d]));
    if (walls == 3) {
      EXPECT_LT((p - g).norm(), 1e-9) << "corner " << v;
    } else if (walls == 2) {
      EXPECT_LT(off, 0.02 * h) << "edge vertex " << v;
    } else if (walls == 1) {
      EXPECT_LT(off, 0.02 * h) << "face vertex " << v;
    }
    // and inside the box
    EXPECT_TRUE((p.array() > -0.02 * h).all() && (p.array() < 1 + 0.02 * h).all()) << v;
  }
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
}

//! The ball grid of n cells a side with its boundary vertices on `sphere`: every boundary quad a
//! chord.
core::HexMesh ball_on(const core::TriMesh& sphere, int n) {
  const optimize::TargetSurface target(sphere, {});
  core::HexMesh ball = test::ball_grid(n);
  for (const int v : core::boundary(ball).vertex_map) ball.points[v] = target.closest_point(ball.points[v]);
  return ball;
}

// Issue 8, cube_minus_sphere: the quality rounds raise the weights of the worst hexes, whose
// shape energy then pulls some boundary vertices off the surface (there, by a third of an edge
// length), and the final snap, which keeps the minimum reached, leaves them there. With drift
// retries, those vertices' attraction is stiffened until they stay on the surface (without,
// the worst vertex here ends 0.4 edge lengths off). The ball's corner hexes have three faces
// on the sphere: the worst hexes, all with boundary vertices.
TEST(HexOptimize, WorstHexesKeepTheirBoundaryOnACurvedSurface) {
  const int n = 6;
  core::HexMesh m = test::ball_grid(n);
  const core::TriMesh sphere = test::sphere_surface(4);
  const optimize::TargetSurface target(sphere, {});
  for (const int v : core::boundary(m).vertex_map) m.points[v] = target.closest_point(m.points[v]);
  // retries while the Hausdorff distance is above 0.5 % (tighter than the default 0.9 %): the
  // stiffened vertices come back within 5 % of an edge
  optimize::OptimizeOptions o;
  o.drift_retries = 6;
  o.hausdorff_bound = 0.005;
  const auto r = optimize::optimize_hex_mesh(m, sphere, o);
  EXPECT_TRUE(r.untangled);
  EXPECT_GT(r.after.min, r.before.min);
  EXPECT_GT(r.rounds_accepted, 1);  // the reweighting rounds ran and were kept
  const double h = 2.0 / n;
  double worst = 0;
  for (const int v : core::boundary(m).vertex_map)
    worst = std::max(worst, (target.closest_point(m.points[v]) - m.points[v]).norm());
  EXPECT_LT(worst, 0.05 * h) << "retries " << r.drift_retries << " mSJ " << r.after.min;
  EXPECT_LE(quality::hausdorff_distance(m, sphere).relative, 0.009);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
}

// The same ball with no retry and a bound of 3 %: the best round's boundary, put on the sphere,
// ends 3.8 % from it (its worst hexes pulled their vertices off), and the last round kept before
// it whose boundary is within the bound is the result (the retries, off here, start over from
// the rounds' start and may end lower; with them, the higher of the two in mSJ is kept).
TEST(HexOptimize, WithoutRetriesTheLastRoundWithinTheBoundIsKept) {
  const core::TriMesh sphere = test::sphere_surface(4);
  core::HexMesh m = ball_on(sphere, 6);
  optimize::OptimizeOptions o;
  o.drift_retries = 0;
  o.fit_retry = 0;
  o.hausdorff_bound = 0.03;
  const core::HexMesh start = m;
  const auto r = optimize::optimize_hex_mesh(m, sphere, o);
  EXPECT_TRUE(r.untangled);
  EXPECT_GT(r.after.min, r.before.min);
  EXPECT_LE(quality::hausdorff_distance(m, sphere).relative, o.hausdorff_bound);
  EXPECT_EQ(r.rounds_accepted, 6);
  // With a bound nothing exceeds, the rounds' best: higher in mSJ, beyond the 3 %.
  core::HexMesh best = start;
  optimize::OptimizeOptions all = o;
  all.hausdorff_bound = 1.0;
  const auto rb = optimize::optimize_hex_mesh(best, sphere, all);
  EXPECT_GT(quality::hausdorff_distance(best, sphere).relative, o.hausdorff_bound) << "mSJ " << rb.after.min;
  EXPECT_GT(rb.after.min, r.after.min);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
}

// The same ball with every option at its default: the defaults promise a mesh within
// hausdorff_bound (0.9 % of the target's diagonal, the thesis's bound) whenever it is valid, so
// no boundary vertex may end farther from the sphere than that bound, measured here by the
// sphere's own equation (independent of the optimizer's projection) and by the Hausdorff distance.
TEST(HexOptimize, DefaultsKeepACurvedBoundaryWithinTheHausdorffBound) {
  const int n = 6;
  core::HexMesh m = test::ball_grid(n);
  const core::TriMesh sphere = test::sphere_surface(4);
  const optimize::TargetSurface target(sphere, {});
  for (const int v : core::boundary(m).vertex_map) m.points[v] = target.closest_point(m.points[v]);
  const optimize::OptimizeOptions defaults;
  ASSERT_EQ(defaults.hausdorff_bound, 0.009);  // the bound this test holds the defaults to
  const auto r = optimize::optimize_hex_mesh(m, sphere);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(r.after.inverted + r.after.invalid, 0);
  EXPECT_GT(r.after.min, r.before.min);
  const double diagonal = core::bounding_box(sphere.points).extent().norm();
  const double bound = defaults.hausdorff_bound * diagonal;
  // The polyhedral sphere lies between radius 1 and its inscribed radius: a vertex off the
  // polyhedron by d is off the unit sphere by at most d + (1 - inscribed radius).
  double inscribed = 1.0;
  for (const auto& t : sphere.cells) {
    const core::Vec3 &a = sphere.points[t[0]], &b = sphere.points[t[1]], &c = sphere.points[t[2]];
    inscribed = std::min(inscribed, std::abs((b - a).cross(c - a).normalized().dot(a)));
  }
  double worst = 0;
  for (const int v : core::boundary(m).vertex_map)
    worst = std::max(worst, std::abs(m.points[v].norm() - 1.0));
  EXPECT_LE(worst, bound + (1.0 - inscribed)) << "mSJ " << r.after.min << ", drift retries " << r.drift_retries;
  EXPECT_LE(quality::hausdorff_distance(m, sphere).relative, defaults.hausdorff_bound);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
}

// A block 4 x 2 x 2 with a pocket 0.2 wide and 1 deep cut into its top, meshed with the pocket's
// walls as hex faces; then one vertex of each wall pushed 0.3 across the pocket, so that the
// walls cross. Each pushed vertex is now closer to the opposite wall (0.1) than to its own
// (0.3): the closest point would hold the crossing, the closest point facing the vertex's own
// way (TargetSurface::closest_point_facing) takes each wall back.
TEST(HexOptimize, WallsPushedAcrossANarrowPocketGoBackToTheirOwnSides) {
  const std::array<double, 10> xs{0, 0.5, 1, 1.5, 1.9, 2.1, 2.5, 3, 3.5, 4};
  const int nx = 9, ny = 4, nz = 4;
  core::HexMesh full = test::lattice_hexes(nx, ny, nz, [&](int i, int j, int k) {
    return core::Vec3(xs[static_cast<std::size_t>(i)], 0.5 * j, 0.5 * k);
  });
  core::HexMesh m;
  m.points = full.points;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (!(i == 4 && k >= 2 && (j == 1 || j == 2)))
          m.cells.push_back(full.cells[static_cast<std::size_t>(i + nx * (j + ny * k))]);
  const core::TriMesh target = quality::triangulate(core::boundary(m).surface);
  ASSERT_TRUE(optimize::check_foldover(m).ok());
  const auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  const int left = id(4, 2, 3), right = id(5, 2, 3);  // (1.9, 1, 1.5) and (2.1, 1, 1.5)
  m.points[left].x() = 2.2;
  m.points[right].x() = 1.8;
  ASSERT_EQ(quality::scaled_jacobian(m).inverted, 0);
  ASSERT_GT(optimize::check_foldover(m).boundary_self_intersections, 0);
  optimize::optimize_hex_mesh(m, target);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
  EXPECT_NEAR(m.points[left].x(), 1.9, 0.02);
  EXPECT_NEAR(m.points[right].x(), 2.1, 0.02);
}

TEST(HexOptimize, Deterministic) {
  core::HexMesh a = test::box_grid(6, 5, 4, 1.2, 1, 0.8);
  test::perturb(a, 0.05, 5, [](const core::Vec3&) { return true; });
  core::HexMesh b = a;
  const core::TriMesh box = test::box_surface(1.2, 1, 0.8);
  optimize::optimize_hex_mesh(a, box);
  optimize::optimize_hex_mesh(b, box);
  EXPECT_EQ(io::write_mesh_to_string(core::to_mesh_data(a), io::Format::Medit),
            io::write_mesh_to_string(core::to_mesh_data(b), io::Format::Medit));
}

double sphere_diagonal(const core::TriMesh& t) { return core::bounding_box(t.points).extent().norm(); }

//! Largest over smallest hex volume (of the box spanned by corners 0 and 6: about it for
//! near-boxes).
double volume_ratio(const core::HexMesh& m) {
  double lo = 1e300, hi = 0;
  for (const auto& h : m.cells) {
    const core::Vec3 d = m.points[h[6]] - m.points[h[0]];
    const double v = std::abs(d.x() * d.y() * d.z());
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  return hi / lo;
}

TEST(HexOptimize, SizeUniformityEvensOutAGradedMesh) {
  // the unit cube with its x layers graded as x^2 (largest over smallest hex volume 11): the
  // input's reference keeps the grading, a uniform one moves the layers towards equal sizes;
  // the boundary stays on the cube either way
  // (interior vertices jittered by 0.005: a perfect grid has nothing a quality round may raise)
  core::HexMesh graded = test::box_grid(6, 4, 4);
  for (auto& p : graded.points) p.x() = p.x() * p.x();
  test::perturb(graded, 0.005, 3, interior);
  const double before = volume_ratio(graded);
  ASSERT_GT(before, 9.0);
  const core::TriMesh box = test::box_surface();
  core::HexMesh kept = graded;
  optimize::optimize_hex_mesh(kept, box);
  EXPECT_GT(volume_ratio(kept), 0.8 * before);
  core::HexMesh even = graded;
  optimize::OptimizeOptions o;
  o.size_uniformity = 1.0;
  const auto r = optimize::optimize_hex_mesh(even, box, o);
  EXPECT_TRUE(r.untangled);
  EXPECT_GT(r.after.min, 0.9);
  EXPECT_LT(volume_ratio(even), 0.5 * before);
  EXPECT_LT(quality::hausdorff_distance(even, box).relative, 1e-3);
  const auto check = optimize::check_foldover(even);
  EXPECT_TRUE(check.ok()) << check.reason();
}

TEST(HexOptimize, FaceAttractionFitsInsteadOfInterpolating) {
  // a coarse ball: with every boundary vertex on the sphere each quad is a chord; attracting the
  // quad centres too lets the boundary straddle the sphere, and the Hausdorff distance drops
  const core::TriMesh sphere = test::sphere_surface(4);
  const core::HexMesh start = ball_on(sphere, 6);
  // one quality round without reweighting (the ball's corner hexes would otherwise pull their
  // vertices off the sphere, which is another test's subject)
  optimize::OptimizeOptions o;
  o.quality_rounds = 1;
  o.drift_retries = 0;
  core::HexMesh chords = start;
  optimize::optimize_hex_mesh(chords, sphere, o);
  core::HexMesh fitted = start;
  o.face_attraction = 1.0;
  const auto r = optimize::optimize_hex_mesh(fitted, sphere, o);
  EXPECT_TRUE(r.untangled);
  EXPECT_GT(r.after.min, 0.0);
  const double d_chords = quality::hausdorff_distance(chords, sphere).relative;
  const double d_fitted = quality::hausdorff_distance(fitted, sphere).relative;
  EXPECT_LT(d_fitted, 0.75 * d_chords) << "chords " << d_chords << ", fitted " << d_fitted;
  // vertices leave the sphere, outwards, by a fraction of the chord's sag
  double outside = 0;
  for (const int v : core::boundary(fitted).vertex_map) outside = std::max(outside, fitted.points[v].norm() - 1.0);
  EXPECT_GT(outside, 0.0);
  EXPECT_LT(outside, d_chords * sphere_diagonal(sphere));
  const auto check = optimize::check_foldover(fitted);
  EXPECT_TRUE(check.ok()) << check.reason();
}

// A coarse ball whose boundary, on the sphere, is beyond the Hausdorff bound by its chords: the
// fit retry runs after the plain rounds and is kept. Attracting the quad centres from the start
// gives the same mesh, bit for bit, without the plain rounds.
TEST(HexOptimize, FitFromTheStartGivesTheFitRetrysMeshWithoutThePlainRounds) {
  const core::TriMesh sphere = test::sphere_surface(4);
  const core::HexMesh start = ball_on(sphere, 4);
  optimize::OptimizeOptions o;
  o.quality_rounds = 2;
  o.drift_retries = 0;
  ASSERT_GT(quality::hausdorff_distance(start, sphere).relative, o.hausdorff_bound);
  o.fit_first_margin = 0;  // the plain rounds first, then the fit retry
  core::HexMesh retried = start;
  const auto r0 = optimize::optimize_hex_mesh(retried, sphere, o);
  ASSERT_TRUE(r0.fit_retry);
  o.fit_first_margin = 1;
  core::HexMesh fitted = start;
  const auto r1 = optimize::optimize_hex_mesh(fitted, sphere, o);
  EXPECT_TRUE(r1.fit_retry);
  EXPECT_EQ(fitted.points, retried.points);
  EXPECT_EQ(r1.rounds_run, r0.rounds_run - 2);
  EXPECT_LE(quality::hausdorff_distance(fitted, sphere).relative, o.hausdorff_bound);
  EXPECT_GT(r1.after.min, 0.0);
}

// The distance the optimizer reports is a measurement of the mesh it returns, figure for figure
// (callers take it instead of measuring again); nothing is reported when it measured nothing.
TEST(HexOptimize, TheDistanceItReportsIsThatOfTheMeshItReturns) {
  const core::TriMesh sphere = test::sphere_surface(4);
  const core::HexMesh start = ball_on(sphere, 4);
  for (const double margin : {0.0, 1.0}) {  // plain rounds, retries and fit retry; fit from the start
    optimize::OptimizeOptions o;
    o.quality_rounds = 2;
    o.fit_first_margin = margin;
    core::HexMesh mesh = start;
    const auto r = optimize::optimize_hex_mesh(mesh, sphere, o);
    ASSERT_TRUE(r.distance.has_value()) << "margin " << margin;
    const quality::SurfaceDistance d = quality::hausdorff_distance(mesh, sphere);
    EXPECT_EQ(r.distance->hausdorff, d.hausdorff);
    EXPECT_EQ(r.distance->hausdorff_upper, d.hausdorff_upper);
    EXPECT_EQ(r.distance->relative, d.relative);
    EXPECT_EQ(r.distance->reference_to_surface.mean, d.reference_to_surface.mean);
  }
  optimize::OptimizeOptions none;
  none.quality_rounds = 1;
  none.drift_retries = 0;
  none.fit_retry = 0;
  none.polish = false;  // its boundary moves are measured when they raise the mSJ
  core::HexMesh mesh = start;
  EXPECT_FALSE(optimize::optimize_hex_mesh(mesh, sphere, none).distance.has_value());
}

// A bar of positive hexes bent by more than a turn has a boundary that crosses itself; the
// quality rounds move the boundary along the target and keep the crossing. With
// stop_when_untangled_crosses the optimizer stops before them (for a caller that then tries a
// stiffer barrier) and says so; without it the rounds run.
TEST(HexOptimize, StopsBeforeTheRoundsWhenTheUntangledBoundaryCrossesItself) {
  const core::HexMesh bar = test::bent_bar(1.1);
  const core::TriMesh target = test::boundary_surface(bar);
  optimize::OptimizeOptions o;
  o.quality_rounds = 1;
  o.stop_when_untangled_crosses = true;
  core::HexMesh stopped = bar;
  const auto r = optimize::optimize_hex_mesh(stopped, target, o);
  EXPECT_TRUE(r.stopped_crossing);
  EXPECT_EQ(r.rounds_run, 0);
  EXPECT_EQ(r.quality.iterations, 0);
  EXPECT_GT(optimize::check_foldover(stopped).boundary_self_intersections, 0);
  o.stop_when_untangled_crosses = false;
  core::HexMesh rounds = bar;
  const auto full = optimize::optimize_hex_mesh(rounds, target, o);
  EXPECT_FALSE(full.stopped_crossing);
  EXPECT_EQ(full.rounds_run, 1);
  EXPECT_GT(optimize::check_foldover(rounds).boundary_self_intersections, 0);
  // A boundary that does not cross itself goes through the rounds either way.
  core::HexMesh open_bar = test::bent_bar(0.9);
  o.stop_when_untangled_crosses = true;
  const auto passing = optimize::optimize_hex_mesh(open_bar, test::boundary_surface(open_bar), o);
  EXPECT_FALSE(passing.stopped_crossing);
  EXPECT_EQ(passing.rounds_run, 1);
}

TEST(HexOptimize, BadInput) {
  core::HexMesh empty;
  EXPECT_THROW(optimize::optimize_hex_mesh(empty, test::box_surface()), core::InputError);
  core::HexMesh m = test::box_grid(2, 2, 2);
  m.cells[0][3] = 1000;
  EXPECT_THROW(optimize::optimize_hex_mesh(m, test::box_surface()), core::InputError);
  core::HexMesh g = test::box_grid(2, 2, 2);
  optimize::OptimizeOptions o;
  o.feature_angle = 0;
  EXPECT_THROW(optimize::optimize_hex_mesh(g, test::box_surface(), o), core::InputError);
  optimize::OptimizeOptions u;
  u.size_uniformity = 1.5;
  EXPECT_THROW(optimize::optimize_hex_mesh(g, test::box_surface(), u), core::InputError);
  optimize::OptimizeOptions f;
  f.face_attraction = -1;
  EXPECT_THROW(optimize::optimize_hex_mesh(g, test::box_surface(), f), core::InputError);
  optimize::OptimizeOptions p;
  p.quality_patience = -1;
  EXPECT_THROW(optimize::optimize_hex_mesh(g, test::box_surface(), p), core::InputError);
  for (double sigma : {0.0, 1.0}) {
    optimize::OptimizeOptions s;
    s.untangle_min_sigma = sigma;
    EXPECT_THROW(optimize::optimize_hex_mesh(g, test::box_surface(), s), core::InputError) << sigma;
  }
}

// Done-when line of issue 8: the rockerarm optimized with its own boundary as target keeps
// (at least) its mSJ and aSJ, passes the fold-over check and stays on its surface.
TEST(HexOptimize, RockerarmOwnBoundary) {
  const std::filesystem::path file = std::filesystem::path(POLYCUBE_DATA_DIR) / "hex" / "rockerarm.mesh";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not found";
  core::HexMesh m = core::hexes_of(io::read_mesh(file));
  const core::TriMesh target = quality::triangulate(core::boundary(m).surface);
  const auto r = optimize::optimize_hex_mesh(m, target);
  EXPECT_GE(r.after.min, r.before.min);
  EXPECT_GE(r.after.average, r.before.average);
  EXPECT_EQ(r.after.inverted + r.after.invalid, 0);
  const auto check = optimize::check_foldover(m);
  EXPECT_TRUE(check.ok()) << check.reason();
  EXPECT_LE(quality::hausdorff_distance(m, target).relative, 0.009);
}

}  // namespace
}  // namespace polycube
