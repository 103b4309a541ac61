// Hausdorff distance on pairs whose distance is known analytically.
#include "quality/surface_distance.h"

#include "core/errors.h"
#include "core/topology.h"
#include "quality_fixtures.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace polycube::quality {
namespace {

using core::Vec3;

//! Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5); an
//! implementation independent of the one under test (CGAL's).
Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double brute_distance(const Vec3& p, const core::TriMesh& m) {
  double best = std::numeric_limits<double>::max();
  for (const auto& t : m.cells)
    best = std::min(
        best, (p - closest_on_triangle(p, m.points[t[0]], m.points[t[1]], m.points[t[2]])).norm());
  return best;
}

double bbox_diagonal(const core::TriMesh& m) { return core::bounding_box(m.points).diagonal(); }

TEST(HausdorffDistance, ConcentricAlignedSpheresIsExactlyATenth) {
  // A = icosphere of radius 1, B = the same mesh scaled by 1.1 (same vertex directions).
  // h(B -> A) = 0.1: the distance to the convex polytope A is a convex function, so its maximum
  // over a triangle of B is at a vertex 1.1 u, whose closest point on A is A's vertex u (u is
  // A's farthest point in direction u), at distance 0.1. h(A -> B) <= 0.1: a point p = sum l_i u_i
  // of a triangle of A is at distance |p - 1.1 p| = 0.1 |p| <= 0.1 of the point sum l_i 1.1 u_i
  // of B. So H = 0.1 exactly, and the sampled estimate (a lower bound that includes B's
  // vertices) equals it up to rounding.
  const auto a = test::icosphere(4, 1.0);
  const auto b = test::icosphere(4, 1.1);
  const auto d = hausdorff_distance(a, b, SurfaceDistanceOptions{0.005});
  EXPECT_NEAR(d.hausdorff, 0.1, 1e-9);
  EXPECT_NEAR(d.reference_to_surface.max, 0.1, 1e-9);
  EXPECT_LE(d.surface_to_reference.max, 0.1 + 1e-12);
  EXPECT_GT(d.surface_to_reference.max, 0.09);
  EXPECT_NEAR(d.relative, 0.1 / bbox_diagonal(b), 1e-12);
  EXPECT_NEAR(d.reference_diagonal, bbox_diagonal(b), 1e-12);
  // The worst point of B is one of its vertices, on the sphere of radius 1.1.
  EXPECT_NEAR(d.reference_to_surface.worst_point.norm(), 1.1, 1e-12);
  EXPECT_GE(d.surface_to_reference.queries, a.points.size() + a.cells.size());
  // The guaranteed bracket contains 0.1 and is at most the tolerance wide.
  EXPECT_GE(d.hausdorff_upper, 0.1 - 1e-12);
  EXPECT_LE(d.hausdorff_upper - d.hausdorff, 0.005 * d.reference_diagonal + 1e-12);
}

TEST(HausdorffDistance, ConcentricMisalignedSpheres) {
  // A = fine icosphere of radius 1 (level 5), B = coarse icosphere of radius 1.1 (level 3),
  // rotated so no vertex directions coincide. B contains A (its inscribed radius 1.1 cos(rho)
  // exceeds 1). Then:
  // - h(B -> A) = L := max over B's vertices of their distance to A (convexity, as above),
  //   computed here by brute force with an independent point-triangle distance;
  // - h(A -> B) <= 1.1 - r_in(A): for p on A, the point of B in direction p has radius at
  //   most 1.1, and |p| >= r_in(A) (A's inscribed radius: its smallest face-plane distance).
  // So H lies in [L, U] with U = max(L, 1.1 - r_in(A)), and both are within (1 - r_in(A)) of
  // 0.1: the discretization error of the fine sphere. The sampled estimate lies in [L, H].
  const auto a = test::icosphere(5, 1.0);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const auto b = test::icosphere(3, 1.1, rot);

  double lower = 0.0;
  for (const auto& v : b.points) lower = std::max(lower, brute_distance(v, a));
  double r_in = std::numeric_limits<double>::max();
  for (const auto& t : a.cells) {
    const Vec3 n =
        (a.points[t[1]] - a.points[t[0]]).cross(a.points[t[2]] - a.points[t[0]]).normalized();
    r_in = std::min(r_in, std::fabs(n.dot(a.points[t[0]])));
  }
  const double upper = std::max(lower, 1.1 - r_in);
  ASSERT_LT(upper - lower, 1e-3 * 0.1 * 5);  // the pair pins H to 5e-4 relative

  const SurfaceDistanceOptions options{0.005};
  const auto d = hausdorff_distance(a, b, options);
  EXPECT_GE(d.hausdorff, lower - 1e-12);
  EXPECT_LE(d.hausdorff, upper + 1e-12);
  EXPECT_NEAR(d.reference_to_surface.max, lower, 1e-12);  // B's vertices are sampled
  EXPECT_NEAR(d.hausdorff, 0.1, 1e-3 * 0.1 + (1.0 - r_in));
  EXPECT_GE(d.hausdorff_upper, lower - 1e-12);  // the true H is in both brackets
  EXPECT_LE(d.hausdorff_upper - d.hausdorff, 0.005 * d.reference_diagonal + 1e-12);
  // Symmetric: swapping the roles gives the same distance (other relative normalization).
  const auto s = hausdorff_distance(b, a, options);
  EXPECT_NEAR(s.hausdorff, d.hausdorff, 1e-4);
}

core::TriMesh box_surface(double lo, double hi, int n, const Vec3& shift = Vec3::Zero()) {
  auto hexes = test::gridded_box(1, 1, 1, n);
  for (auto& p : hexes.points) p = Vec3::Constant(lo) + (hi - lo) * p + shift;
  return triangulate(core::boundary(hexes).surface);
}

TEST(HausdorffDistance, HexBoundaryAgainstShiftedAndScaledBoxes) {
  const auto hexes = test::gridded_box(1, 1, 1, 3);  // [0,1]^3
  // Every maximum here is at a vertex (distances to boxes from planar faces are convex or
  // attained at corners), so a coarse sampling suffices.
  const SurfaceDistanceOptions coarse{0.02};
  // Shifted up by 0.05: every point is within 0.05 of the other box, the bottom and top faces
  // are exactly 0.05 away.
  auto d = hausdorff_distance(hexes, box_surface(0, 1, 2, Vec3(0, 0, 0.05)), coarse);
  EXPECT_NEAR(d.hausdorff, 0.05, 1e-12);
  EXPECT_NEAR(d.surface_to_reference.max, 0.05, 1e-12);
  // Box [-0.05, 1.05]^3: its corners are 0.05 sqrt(3) from the unit box; the unit box's points
  // are at most 0.05 from the big box's faces.
  d = hausdorff_distance(hexes, box_surface(-0.05, 1.05, 4), coarse);
  EXPECT_NEAR(d.hausdorff, 0.05 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(d.surface_to_reference.max, 0.05, 1e-12);
  EXPECT_NEAR(d.relative, d.hausdorff / (1.1 * std::sqrt(3.0)), 1e-12);
  // Identical surfaces (different triangulations): 0.
  d = hausdorff_distance(hexes, box_surface(0, 1, 5), coarse);
  EXPECT_NEAR(d.hausdorff, 0.0, 1e-12);
}

TEST(RememberedDistance, GivesTheMeasurementOfExactlyTheSameMeshOnly) {
  auto hexes = test::gridded_box(1, 1, 1, 3);
  const core::TriMesh target = box_surface(0, 1, 2, Vec3(0, 0, 0.05));
  RememberedDistance memo;
  EXPECT_EQ(memo.find(hexes), nullptr);
  const SurfaceDistance measured = memo.measure(hexes, target);
  const SurfaceDistance direct = hausdorff_distance(hexes, target);
  EXPECT_EQ(measured.hausdorff, direct.hausdorff);
  EXPECT_EQ(measured.hausdorff_upper, direct.hausdorff_upper);
  EXPECT_EQ(measured.surface_to_reference.queries, direct.surface_to_reference.queries);
  ASSERT_NE(memo.find(hexes), nullptr);
  EXPECT_EQ(memo.find(hexes)->hausdorff, direct.hausdorff);

  // One coordinate moved by its last bit: another mesh, measured again.
  auto moved = hexes;
  moved.points[0].z() = std::nextafter(moved.points[0].z(), 1.0);
  EXPECT_EQ(memo.find(moved), nullptr);
  // The same points with another hex's vertex order: another mesh too.
  auto reordered = hexes;
  std::swap(reordered.cells[0][0], reordered.cells[0][1]);
  EXPECT_EQ(memo.find(reordered), nullptr);

  // Remembering another measurement replaces the first.
  moved.points[0].z() -= 0.5;  // a corner pulled out below the box: farther from the target
  const SurfaceDistance far = hausdorff_distance(moved, target);
  memo.remember(moved, far);
  EXPECT_EQ(memo.find(hexes), nullptr);
  ASSERT_NE(memo.find(moved), nullptr);
  EXPECT_EQ(memo.measure(moved, target).hausdorff, far.hausdorff);
  EXPECT_GT(far.hausdorff, direct.hausdorff);
}

TEST(HausdorffDistance, DenserSamplingFindsInteriorMaxima) {
  // A single triangle against an open pyramid over it whose apex lies below the triangle: both
  // share the vertices and edges, so vertex and edge sampling alone would report 0; the
  // maximum is inside the triangle. Reference value: brute force on a 200 x 200 grid (the
  // distance is 1-Lipschitz, so the grid is within its spacing of the true maximum).
  core::TriMesh s;
  s.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  s.cells = {{0, 1, 2}};
  core::TriMesh r;
  r.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1.0 / 3, 1.0 / 3, -0.2)};
  r.cells = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  double truth = 0.0;
  constexpr int kGrid = 200;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; i + j <= kGrid; ++j)
      truth = std::max(truth, brute_distance(Vec3(double(i) / kGrid, double(j) / kGrid, 0), r));
  const double grid_error = std::sqrt(2.0) / kGrid;

  // For every tolerance, [max, upper_bound] brackets the true maximum and is tolerance wide.
  for (const double tol : {0.05, 0.01, 1e-3}) {
    const auto d = hausdorff_distance(s, r, SurfaceDistanceOptions{tol});
    const double abs_tol = tol * core::bounding_box(r.points).diagonal();
    EXPECT_GT(d.surface_to_reference.max, 0.05) << tol;
    EXPECT_LE(d.surface_to_reference.max, truth + grid_error) << tol;
    EXPECT_GE(d.surface_to_reference.upper_bound, truth) << tol;
    EXPECT_LE(d.surface_to_reference.upper_bound - d.surface_to_reference.max, abs_tol + 1e-12)
        << tol;
  }
}

//! Triangulated height field z = f(x, y) over the unit square, n × n cells.
template <class F>
core::TriMesh height_field(int n, const F& f) {
  core::TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, y = double(j) / n;
      m.points.emplace_back(x, y, f(x, y));
    }
  auto id = [n](int i, int j) { return j * (n + 1) + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

TEST(HausdorffDistance, TrianglesCloseToTheReferenceAreAcceptedAgainstTheFarthestCentroid) {
  // A flat square of 16 × 16 × 2 triangles against a fine height field that ripples 0.001 around
  // it and drops by 0.02 in a small well under one triangle's centroid, away from every vertex,
  // as a fitted mesh's boundary lies on its target but for one place inside a triangle. The
  // vertices alone see the ripples only: against that floor each rippled triangle would be
  // refined until its pieces are within the tolerance of its own samples.
  // The centroids find the well, and against it a rippled triangle is accepted at once.
  const auto flat = height_field(16, [](double, double) { return 0.0; });
  const auto& w = flat.cells[2 * (7 * 16 + 7)];
  const Vec3 well = (flat.points[w[0]] + flat.points[w[1]] + flat.points[w[2]]) / 3.0;
  const auto rippled = height_field(256, [&](double x, double y) {
    const double ripple = 0.001 * std::abs(std::remainder(x * 128.0, 1.0)) * 2.0;
    return (Vec3(x, y, 0) - well).norm() < 0.02 ? -0.02 : ripple;
  });
  const auto d = hausdorff_distance(flat, rippled, SurfaceDistanceOptions{1e-3});
  const double tol = 1e-3 * d.reference_diagonal;
  EXPECT_GT(d.surface_to_reference.max, 0.01);
  EXPECT_LE(d.surface_to_reference.upper_bound - d.surface_to_reference.max, tol + 1e-12);
  EXPECT_LE((d.surface_to_reference.worst_point - well).norm(), 0.03);
  // Two splits bring a rippled triangle's pieces within the well's depth of their centroids
  // (1 + 7 + 28 queries with its centroid); refined down to the tolerance it takes hundreds.
  EXPECT_LE(d.surface_to_reference.queries, 40 * flat.cells.size());
}

TEST(HausdorffDistance, QueryBudgetIsRespected) {
  // Two differently rotated spheres with a tolerance of 1e-7 of the diagonal: the refinement
  // cannot reach it within 20000 queries and stops at the depth cap; the bounds stay valid,
  // only wider than the tolerance.
  const auto a = test::icosphere(2, 1.0);
  const auto b = test::icosphere(2, 1.0, Eigen::AngleAxisd(0.3, Vec3(0, 0, 1)).toRotationMatrix());
  const auto d = hausdorff_distance(a, b, SurfaceDistanceOptions{1e-7, 20000});
  EXPECT_LE(d.surface_to_reference.queries, 20000u);
  EXPECT_LE(d.reference_to_surface.queries, 20000u);
  EXPECT_GT(d.hausdorff, 0.01);
  EXPECT_GT(d.hausdorff_upper - d.hausdorff, 1e-7 * d.reference_diagonal);
  EXPECT_LT(d.hausdorff_upper - d.hausdorff, 0.1);
  // Without the cap the bracket closes to the tolerance.
  const auto full = hausdorff_distance(a, b, SurfaceDistanceOptions{1e-4});
  EXPECT_LE(full.hausdorff_upper - full.hausdorff, 1e-4 * full.reference_diagonal + 1e-12);
  EXPECT_GE(full.hausdorff_upper, d.hausdorff - 1e-12);
  EXPECT_LE(full.hausdorff, d.hausdorff_upper + 1e-12);
}

TEST(HausdorffDistance, BadInputThrows) {
  core::TriMesh empty;
  const auto a = test::icosphere(1, 1.0);
  EXPECT_THROW(hausdorff_distance(empty, a), core::InputError);
  EXPECT_THROW(hausdorff_distance(a, empty), core::InputError);
  auto bad = a;
  bad.cells[0][0] = 1000;
  EXPECT_THROW(hausdorff_distance(bad, a), core::InputError);
  auto nan = a;
  nan.points[0].x() = std::nan("");
  EXPECT_THROW(hausdorff_distance(nan, a), core::InputError);
  core::TriMesh flat;
  flat.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)};
  flat.cells = {{0, 1, 2}};
  EXPECT_THROW(hausdorff_distance(flat, a), core::GeometryError);
  EXPECT_THROW(hausdorff_distance(a, a, SurfaceDistanceOptions{-1.0}), core::InputError);
  EXPECT_THROW(hausdorff_distance(a, a, SurfaceDistanceOptions{0.0}), core::InputError);
}

}  // namespace
}  // namespace polycube::quality
