// Tests of solve::with_derived_points (solve/untangle.h) against reductions written out by hand,
// and against the two explicit constructions it replaced (boundary-lift apexes, quad centres),
// which it claims to reproduce bit for bit.
#include "solve/untangle.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <array>
#include <random>

namespace polycube::solve {
namespace {

using core::Vec3;
using Triplet = Eigen::Triplet<double>;

//! Same sparsity, same stored values and same x0, bit for bit.
void expect_identical(const LinearReduction& a, const LinearReduction& b) {
  ASSERT_EQ(a.B.rows(), b.B.rows());
  ASSERT_EQ(a.B.cols(), b.B.cols());
  ASSERT_EQ(a.x0.size(), b.x0.size());
  EXPECT_EQ(a.B.nonZeros(), b.B.nonZeros());
  const Eigen::MatrixXd da(a.B), db(b.B);
  for (Eigen::Index i = 0; i < da.rows(); ++i)
    for (Eigen::Index j = 0; j < da.cols(); ++j) EXPECT_EQ(da(i, j), db(i, j)) << "B(" << i << "," << j << ")";
  for (Eigen::Index i = 0; i < a.x0.size(); ++i) EXPECT_EQ(a.x0[i], b.x0[i]) << "x0[" << i << "]";
}

LinearReduction from_triplets(Eigen::Index rows, Eigen::Index cols, const std::vector<Triplet>& t,
                              Eigen::VectorXd x0) {
  LinearReduction r;
  r.B.resize(rows, cols);
  r.B.setFromTriplets(t.begin(), t.end());
  r.x0 = std::move(x0);
  return r;
}

// Four base points over three variables v0, v1, v2 (coordinates x, y, z of each point):
//   p0 = (v0, 0.7, v1), p1 = (v2, v0, -1.3), p2 = (0.1, 0.2, 0.3) (all fixed), p3 = (v0, v1, v2).
const std::vector<int> kVar{0, -1, 1, 2, 0, -1, -1, -1, -1, 0, 1, 2};
const std::vector<double> kFixed{0, 0.7, 0, 0, 0, -1.3, 0.1, 0.2, 0.3, 0, 0, 0};

LinearReduction base() {
  return index_reduction(kVar, 3, Eigen::Map<const Eigen::VectorXd>(kFixed.data(), 12));
}

//! Rows 0..11 of the base, written out.
std::vector<Triplet> base_triplets() {
  return {{0, 0, 1.0}, {2, 1, 1.0}, {3, 2, 1.0}, {4, 0, 1.0}, {9, 0, 1.0}, {10, 1, 1.0}, {11, 2, 1.0}};
}

TEST(DerivedPoints, BaseReductionIsAsWrittenOut) {
  const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(kFixed.data(), 12);
  expect_identical(base(), from_triplets(12, 3, base_triplets(), x0));
}

TEST(DerivedPoints, ApexOfAFreeAndOfAFixedPointMatchTheHandReduction) {
  // An apex is point(base) + offset: rows of the base copied, x0 = offset + x0(base).
  std::vector<DerivedPoint> d(2);
  d[0].vertex[0] = 1;  // p1 = (v2, v0, -1.3)
  d[0].weight[0] = 1.0;
  d[0].offset = Vec3(0.5, -0.25, 2.0);
  d[1].vertex[0] = 2;  // p2, all fixed: no B entry, only x0
  d[1].weight[0] = 1.0;
  d[1].offset = Vec3(0.0, 0.0, 1.0);

  std::vector<Triplet> t = base_triplets();
  t.insert(t.end(), {{12, 2, 1.0}, {13, 0, 1.0}});
  Eigen::VectorXd x0(18);
  x0 << 0, 0.7, 0, 0, 0, -1.3, 0.1, 0.2, 0.3, 0, 0, 0,  //
      0.5, -0.25, 2.0 + -1.3,                           // apex of p1
      0.0 + 0.1, 0.0 + 0.2, 1.0 + 0.3;                  // apex of p2
  const LinearReduction got = with_derived_points(base(), d);
  expect_identical(got, from_triplets(18, 3, t, x0));
  EXPECT_EQ(got.num_points(), 6);
  // The apex of the fixed point is fixed: its rows are empty, whatever y.
  for (int r = 15; r < 18; ++r) EXPECT_EQ(got.B.row(r).nonZeros(), 0);
}

TEST(DerivedPoints, CombinationsSumSharedVariablesAndIgnoreUnusedEntries) {
  std::vector<DerivedPoint> d(2);
  // Centre of p0..p3: v0 enters x through p0 and p3 (0.25 + 0.25), fixed coordinates go to x0.
  d[0].vertex = {0, 1, 2, 3};
  d[0].weight = {0.25, 0.25, 0.25, 0.25};
  // Midpoint of p0 and p3 (entries with vertex -1 are unused even with a weight).
  d[1].vertex = {0, -1, 3, -1};
  d[1].weight = {0.5, 9.0, 0.5, 9.0};
  d[1].offset = Vec3(0.0, 0.0, 0.125);

  std::vector<Triplet> t = base_triplets();
  t.insert(t.end(), {{12, 0, 0.5}, {12, 2, 0.25},   // x: (v0 + v2 + 0.1 + v0) / 4
                     {13, 0, 0.25}, {13, 1, 0.25},  // y: (0.7 + v0 + 0.2 + v1) / 4
                     {14, 1, 0.25}, {14, 2, 0.25},  // z: (v1 - 1.3 + 0.3 + v2) / 4
                     {15, 0, 1.0},                  // x: (v0 + v0) / 2
                     {16, 1, 0.5},                  // y: (0.7 + v1) / 2
                     {17, 1, 0.5}, {17, 2, 0.5}});  // z: (v1 + v2) / 2 + 0.125
  Eigen::VectorXd x0(18);
  // Constants accumulate from the offset in vertex order (variable coordinates add 0).
  x0 << 0, 0.7, 0, 0, 0, -1.3, 0.1, 0.2, 0.3, 0, 0, 0,  //
      0.25 * 0.1, 0.25 * 0.7 + 0.25 * 0.2, 0.25 * -1.3 + 0.25 * 0.3,  //
      0.0, 0.5 * 0.7, 0.125;
  const LinearReduction got = with_derived_points(base(), d);
  expect_identical(got, from_triplets(18, 3, t, x0));

  // And the derived points are where they should be for some y.
  const Eigen::Vector3d y(0.3, -2.0, 5.0);
  const std::vector<Vec3> p = unflatten(got.apply(y));
  const std::array<Vec3, 4> q{Vec3(0.3, 0.7, -2.0), Vec3(5.0, 0.3, -1.3), Vec3(0.1, 0.2, 0.3),
                              Vec3(0.3, -2.0, 5.0)};
  for (int v = 0; v < 4; ++v) EXPECT_EQ(p[v], q[v]) << "point " << v;
  EXPECT_LT((p[4] - (q[0] + q[1] + q[2] + q[3]) / 4).norm(), 1e-14);
  EXPECT_LT((p[5] - ((q[0] + q[3]) / 2 + Vec3(0, 0, 0.125))).norm(), 1e-14);
}

TEST(DerivedPoints, NoDerivedPointsLeavesTheReduction) {
  expect_identical(with_derived_points(base(), {}), base());
}

// --- the explicit constructions it replaced (optimize/boundary_lift.cpp and face_attraction.cpp
// before with_derived_points), on a larger reduction with fixed, free and shared coordinates ---

LinearReduction explicit_apexes(const LinearReduction& r, const std::vector<int>& base_vertex,
                                const std::vector<Vec3>& offset) {
  const auto rows = static_cast<Eigen::Index>(r.B.rows());
  const auto extra = static_cast<Eigen::Index>(3 * base_vertex.size());
  std::vector<Triplet> trip;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (decltype(r.B)::InnerIterator it(r.B, i); it; ++it) trip.emplace_back(i, it.col(), it.value());
  LinearReduction out;
  out.x0.resize(rows + extra);
  out.x0.head(rows) = r.x0;
  for (std::size_t k = 0; k < base_vertex.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Index src = 3 * static_cast<Eigen::Index>(base_vertex[k]) + d;
      const Eigen::Index dst = rows + 3 * static_cast<Eigen::Index>(k) + d;
      for (decltype(r.B)::InnerIterator it(r.B, src); it; ++it) trip.emplace_back(dst, it.col(), it.value());
      out.x0[dst] = r.x0[src] + offset[k][d];
    }
  out.B.resize(rows + extra, r.B.cols());
  out.B.setFromTriplets(trip.begin(), trip.end());
  return out;
}

LinearReduction explicit_quad_centres(const LinearReduction& r, const std::vector<std::array<int, 4>>& quads) {
  const auto rows = static_cast<Eigen::Index>(r.B.rows());
  const auto extra = static_cast<Eigen::Index>(3 * quads.size());
  std::vector<Triplet> trip;
  for (Eigen::Index i = 0; i < rows; ++i)
    for (decltype(r.B)::InnerIterator it(r.B, i); it; ++it) trip.emplace_back(i, it.col(), it.value());
  LinearReduction out;
  out.x0 = Eigen::VectorXd::Zero(rows + extra);
  out.x0.head(rows) = r.x0;
  for (std::size_t k = 0; k < quads.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Index dst = rows + 3 * static_cast<Eigen::Index>(k) + d;
      for (int v : quads[k]) {
        const Eigen::Index src = 3 * static_cast<Eigen::Index>(v) + d;
        for (decltype(r.B)::InnerIterator it(r.B, src); it; ++it) trip.emplace_back(dst, it.col(), 0.25 * it.value());
        out.x0[dst] += 0.25 * r.x0[src];
      }
    }
  out.B.resize(rows + extra, r.B.cols());
  out.B.setFromTriplets(trip.begin(), trip.end());
  return out;
}

//! 40 points: each coordinate fixed at a random value (half of them, so that quad centres sum
//! three or four constants, where the order of the sum shows in the last bits), free, or sharing
//! a variable of a smaller index.
LinearReduction random_reduction(std::mt19937& rng) {
  const int n = 40;
  std::uniform_real_distribution<double> value(-3.0, 3.0);
  std::uniform_int_distribution<int> kind(0, 3);
  std::vector<int> var(3 * n, -1);
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(3 * n);
  int nvar = 0;
  for (int i = 0; i < 3 * n; ++i) {
    const int k = kind(rng);
    if (k <= 1) fixed[i] = value(rng);
    else if (k == 2 || nvar == 0) var[i] = nvar++;
    else var[i] = std::uniform_int_distribution<int>(0, nvar - 1)(rng);
  }
  return index_reduction(var, nvar, fixed);
}

TEST(DerivedPoints, ApexesAreBitForBitTheExplicitConstruction) {
  std::mt19937 rng(11);
  const LinearReduction r = random_reduction(rng);
  std::uniform_int_distribution<int> vertex(0, r.num_points() - 1);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<int> base_vertex;
  std::vector<Vec3> offset;
  std::vector<DerivedPoint> apexes;
  for (int k = 0; k < 30; ++k) {
    base_vertex.push_back(vertex(rng));
    offset.emplace_back(value(rng), value(rng), value(rng));
    DerivedPoint a;
    a.vertex[0] = base_vertex.back();
    a.weight[0] = 1.0;
    a.offset = offset.back();
    apexes.push_back(a);
  }
  expect_identical(with_derived_points(r, apexes), explicit_apexes(r, base_vertex, offset));
}

TEST(DerivedPoints, QuadCentresAreBitForBitTheExplicitConstruction) {
  std::mt19937 rng(12);
  const LinearReduction r = random_reduction(rng);
  std::uniform_int_distribution<int> vertex(0, r.num_points() - 1);
  std::vector<std::array<int, 4>> quads;
  std::vector<DerivedPoint> centres;
  for (int k = 0; k < 200; ++k) {
    quads.push_back({vertex(rng), vertex(rng), vertex(rng), vertex(rng)});
    DerivedPoint c;
    c.vertex = quads.back();
    c.weight = {0.25, 0.25, 0.25, 0.25};
    centres.push_back(c);
  }
  expect_identical(with_derived_points(r, centres), explicit_quad_centres(r, quads));
}

}  // namespace
}  // namespace polycube::solve
