//! Tests of the untangling engine (solve/untangle.h) and the sparse SPD solver
//! (solve/sparse_solver.h): element energy derivatives, Cholesky solves, untangling of a folded
//! grid with fixed and shared coordinates, attractions.
#include "core/errors.h"
#include "support/fixtures.h"
#include "solve/sparse_solver.h"
#include "solve/untangle.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <memory>
#include <random>
#include <thread>

namespace polycube {
namespace {

using core::Vec3;

// --- element energy and sparse solver ---------------------------------------------------------

TEST(EllipticEnergy, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.5, 1.5);
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::Matrix3d J;
    for (int i = 0; i < 9; ++i) J(i / 3, i % 3) = U(rng);
    if (trial == 0) J = Eigen::Matrix3d::Identity();
    const double eps = trial % 2 ? 0.3 : 1e-2;
    const auto e = solve::elliptic_energy(J, eps, 1.0);
    const double h = 1e-6;
    for (int i = 0; i < 9; ++i) {
      Eigen::Matrix3d Jp = J, Jm = J;
      Jp(i / 3, i % 3) += h;
      Jm(i / 3, i % 3) -= h;
      const auto ep = solve::elliptic_energy(Jp, eps, 1.0);
      const auto em = solve::elliptic_energy(Jm, eps, 1.0);
      const double scale = 1.0 + std::abs(e.gradient[i]);
      EXPECT_NEAR((ep.value - em.value) / (2 * h), e.gradient[i], 1e-5 * scale) << "trial " << trial;
      for (int j = 0; j < 9; ++j)
        EXPECT_NEAR((ep.gradient[j] - em.gradient[j]) / (2 * h), e.hessian(j, i), 1e-4 * (1.0 + e.hessian.norm()))
            << "trial " << trial << " (" << j << "," << i << ")";
    }
  }
  // At the identity the energy is minimal over the shape term: value = 1 + λ·2/χ(1,ε) ~ 3.
  const auto id = solve::elliptic_energy(Eigen::Matrix3d::Identity(), 1e-9, 1.0);
  EXPECT_NEAR(id.value, 3.0, 1e-9);
  EXPECT_LT(id.gradient.norm(), 1e-9);
}

// The projection from the analytic eigensystem against a numeric 9 × 9 eigensolver, on Jacobians
// that are well shaped, sheared, flat, inverted, and with repeated singular values.
TEST(EllipticEnergy, ProjectedHessianIsTheNumericPsdProjection) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-1.5, 1.5);
  int projected = 0;
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Matrix3d J;
    for (int i = 0; i < 9; ++i) J(i / 3, i % 3) = U(rng);
    if (trial == 0) J = Eigen::Matrix3d::Identity();
    if (trial == 1) J = Eigen::Vector3d(1.0, 1.0, -1.0).asDiagonal();  // inverted, repeated values
    if (trial == 2) J = Eigen::Vector3d(2.0, 0.5, 0.0).asDiagonal();   // flat
    if (trial == 3) J = Eigen::Vector3d(0.3, 0.3, 0.3).asDiagonal();   // small, repeated
    // Rotated: nearly a rotation (singular values 1e-7 apart), nearly flat and inverted, a
    // needle, and large.
    const Eigen::Matrix3d R = Eigen::Quaterniond(U(rng), U(rng), U(rng), U(rng)).normalized().toRotationMatrix();
    if (trial == 4) J = R * Eigen::Vector3d(1.0, 1.0 + 1e-7, 1.0 - 1e-7).asDiagonal();
    if (trial == 5) J = R * Eigen::Vector3d(1.0, 1e-6, -1e-8).asDiagonal() * R.transpose();
    if (trial == 6) J = R * Eigen::Vector3d(1.0, 1e-9, 1e-9).asDiagonal();
    if (trial == 7) J = 1e3 * R;
    if (trial == 8) J = R * Eigen::Vector3d(0.5, 0.5, -0.5 + 1e-8).asDiagonal();
    const double eps = trial % 3 == 0 ? 1e-3 : (trial % 3 == 1 ? 0.1 : 1.0);
    const double lambda = trial % 2 ? 1.0 : 0.25;
    const Eigen::Matrix<double, 9, 9> H = solve::elliptic_energy(J, eps, lambda).hessian;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> es(H);
    const Eigen::Matrix<double, 9, 1> ev = es.eigenvalues().cwiseMax(0.0);
    const Eigen::Matrix<double, 9, 9> expected = es.eigenvectors() * ev.asDiagonal() * es.eigenvectors().transpose();
    const Eigen::Matrix<double, 9, 9> P = solve::projected_elliptic_hessian(J, eps, lambda);
    EXPECT_LE((P - expected).norm(), 1e-9 * H.norm()) << "trial " << trial << "\nJ =\n" << J;
    const double least = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>>(P).eigenvalues().minCoeff();
    EXPECT_GE(least, -1e-9 * H.norm()) << "trial " << trial;
    projected += es.eigenvalues().minCoeff() < 0;
  }
  EXPECT_GT(projected, 50);  // most random Jacobians are indefinite: the projection is exercised
}

TEST(SparseSpdSolver, SolvesAndRejectsIndefinite) {
  const int n = 50;
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 4.0);
    if (i + 1 < n) {
      trip.emplace_back(i, i + 1, -1.0);
      trip.emplace_back(i + 1, i, -1.0);
    }
  }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  solve::SparseSpdSolver s;
  s.analyze(A);
  ASSERT_TRUE(s.factorize(A));
  const Eigen::VectorXd x = s.solve(b);
  EXPECT_LT((A * x - b).norm(), 1e-10 * b.norm());
  // Refactorize with new values on the same pattern.
  Eigen::SparseMatrix<double> A2 = A * 2.0;
  ASSERT_TRUE(s.factorize(A2));
  EXPECT_LT((A2 * s.solve(b) - b).norm(), 1e-10 * b.norm());
  // Indefinite: refused, and solving then throws.
  Eigen::SparseMatrix<double> B = A;
  B.coeffRef(3, 3) = -10.0;
  EXPECT_FALSE(s.factorize(B));
  EXPECT_THROW((void)s.solve(b), core::SolverError);
}

//! Upper triangle of a 7-point Laplacian on a k³ grid, shifted to be positive definite.
Eigen::SparseMatrix<double> grid_laplacian(int k) {
  const int n = k * k * k;
  std::vector<Eigen::Triplet<double>> trip;
  const auto id = [k](int x, int y, int z) { return (z * k + y) * k + x; };
  for (int z = 0; z < k; ++z)
    for (int y = 0; y < k; ++y)
      for (int x = 0; x < k; ++x) {
        trip.emplace_back(id(x, y, z), id(x, y, z), 6.1);
        if (x + 1 < k) trip.emplace_back(id(x, y, z), id(x + 1, y, z), -1.0);
        if (y + 1 < k) trip.emplace_back(id(x, y, z), id(x, y + 1, z), -1.0);
        if (z + 1 < k) trip.emplace_back(id(x, y, z), id(x, y, z + 1), -1.0);
      }
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  A.makeCompressed();
  return A;
}

// The factorization's cost counted in solves (what the untangler weighs a factorization
// against): nothing before an analysis, about one where nothing fills in (a chain), and growing
// with the fill of a 3D grid.
TEST(SparseSpdSolver, CountsAFactorizationInSolves) {
  solve::SparseSpdSolver s;
  EXPECT_EQ(s.factorization_flops_per_solve(), 0.0);
  const int n = 1000;
  std::vector<Eigen::Triplet<double>> trip;
  for (int i = 0; i < n; ++i) {
    trip.emplace_back(i, i, 4.0);
    if (i + 1 < n) trip.emplace_back(i, i + 1, -1.0);
  }
  Eigen::SparseMatrix<double> chain(n, n);
  chain.setFromTriplets(trip.begin(), trip.end());
  chain.makeCompressed();
  s.analyze(chain);
  const double on_chain = s.factorization_flops_per_solve();
  EXPECT_GT(on_chain, 0.0);
  EXPECT_LT(on_chain, 2.0);
  s.analyze(grid_laplacian(10));
  const double on_small_grid = s.factorization_flops_per_solve();
  s.analyze(grid_laplacian(20));
  const double on_large_grid = s.factorization_flops_per_solve();
  EXPECT_GT(on_small_grid, 4.0 * on_chain);
  EXPECT_GT(on_large_grid, 1.5 * on_small_grid);
}

//! Threads of this process now (Linux: one entry per thread in /proc/self/task).
int process_threads() {
  const std::filesystem::path tasks("/proc/self/task");
  if (!std::filesystem::exists(tasks)) return -1;
  return static_cast<int>(std::distance(std::filesystem::directory_iterator(tasks), {}));
}

TEST(SparseSpdSolver, FactorizesOnTheCallingThreadAlone) {
  // A 7-point Laplacian on a 20^3 grid (plus a shift): large enough that CHOLMOD's supernodal
  // factorization opens its OpenMP loops (clearing its workspace and every large supernode),
  // which ask for four threads whatever omp_set_num_threads says. Run from a new thread, as
  // a solver may be, so that the setting has to be made there too.
  const int n = 20 * 20 * 20;
  const Eigen::SparseMatrix<double> A = grid_laplacian(20);  // upper triangle, as the solver reads it
  int before = 0, after = 0;
  double residual = 0;
  std::thread worker([&] {
    before = process_threads();
    solve::SparseSpdSolver s;
    s.analyze(A);
    ASSERT_TRUE(s.factorize(A));
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(n);
    const Eigen::SparseMatrix<double> full = A.selfadjointView<Eigen::Upper>();
    residual = (full * s.solve(b) - b).norm() / b.norm();
    after = process_threads();
  });
  worker.join();
  if (before < 0) GTEST_SKIP() << "no /proc/self/task to count threads";
  EXPECT_LT(residual, 1e-10);
  EXPECT_EQ(after, before) << "the factorization started threads of its own";
}

// CHOLMOD's OpenMP regions bind to the program's GOMP_parallel (sparse_solver.cpp), not to
// libgomp's, and that runs a region's body once on the calling thread, outside any team. Fails
// when a change of the link stops the program from exporting it (libgomp's would be bound).
TEST(SparseSpdSolver, OpenMpRegionsRunInline) {
  void* gomp = dlopen("libgomp.so.1", RTLD_LAZY | RTLD_NOLOAD);
  if (gomp == nullptr) GTEST_SKIP() << "libgomp is not loaded: CHOLMOD was built without OpenMP";
  void* bound = dlsym(RTLD_DEFAULT, "GOMP_parallel");
  void* libgomps = dlsym(gomp, "GOMP_parallel");
  using NumThreads = int (*)();
  const auto num_threads = reinterpret_cast<NumThreads>(dlsym(gomp, "omp_get_num_threads"));
  dlclose(gomp);
  ASSERT_NE(bound, nullptr);
  ASSERT_NE(num_threads, nullptr);
  EXPECT_NE(bound, libgomps) << "CHOLMOD's regions would go through libgomp's teams";
  struct Seen {
    int calls = 0;
    std::thread::id thread;
    int team = 0;
    NumThreads num_threads = nullptr;
  } seen;
  seen.num_threads = num_threads;
  using Parallel = void (*)(void (*)(void*), void*, unsigned, unsigned);
  reinterpret_cast<Parallel>(bound)(
      [](void* data) {
        auto* s = static_cast<Seen*>(data);
        ++s->calls;
        s->thread = std::this_thread::get_id();
        s->team = s->num_threads();
      },
      &seen, 4, 0);
  EXPECT_EQ(seen.calls, 1);
  EXPECT_EQ(seen.thread, std::this_thread::get_id());
  EXPECT_EQ(seen.team, 1);
}

// --- untangling -------------------------------------------------------------------------------

struct FoldedGrid {
  core::TetMesh mesh;
  std::vector<int> var;  // 3#V
  int nvar = 0;
};

//! 3x3x3 grid split into tets; boundary vertices fixed; the interior vertex (1,1,1) pushed
//! through the far side of its neighbourhood so that tets around it are inverted.
FoldedGrid folded_grid() {
  FoldedGrid g;
  g.mesh = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const int nv = g.mesh.num_points();
  g.var.assign(3 * nv, -1);
  for (int v = 0; v < nv; ++v) {
    const Vec3& p = g.mesh.points[v];
    const bool bnd = (p.array() == 0.0).any() || (p.array() == 3.0).any();
    if (!bnd)
      for (int d = 0; d < 3; ++d) g.var[3 * v + d] = g.nvar++;
  }
  g.mesh.points[1 + 4 * (1 + 4 * 1)] = Vec3(2.7, 2.6, 2.8);  // vertex (1,1,1) beyond (2,2,2)
  return g;
}

int inverted_count(const core::TetMesh& m, const std::vector<Vec3>& p) {
  int n = 0;
  for (const auto& t : m.cells)
    n += (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) <= 0;
  return n;
}

TEST(Untangle, FoldedVertexBecomesValidAndFixedCoordinatesStay) {
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  ASSERT_GT(inverted_count(g.mesh, g.mesh.points), 0);
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  const solve::LinearReduction R = solve::index_reduction(g.var, g.nvar, x_init);
  Eigen::VectorXd y(g.nvar);
  for (int i = 0; i < 3 * g.mesh.num_points(); ++i)
    if (g.var[i] >= 0) y[g.var[i]] = x_init[i];
  const solve::TetElements el = solve::reference_elements(ref.points, ref.cells);
  const solve::UntangleResult r = solve::untangle(el, R, y, {});
  EXPECT_GT(r.inverted_before, 0);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(r.inverted_after, 0);
  EXPECT_GT(r.min_det, 0.0);
  const Eigen::VectorXd x = R.apply(y);
  const std::vector<Vec3> p = solve::unflatten(x);
  EXPECT_EQ(inverted_count(g.mesh, p), 0);
  for (int i = 0; i < x.size(); ++i) {
    if (g.var[i] < 0) {
      EXPECT_EQ(x[i], x_init[i]) << "fixed coordinate " << i << " moved";
    }
  }
  // The optimum of this fixture is the undistorted grid: the vertices come back close to it.
  double err = 0;
  for (int v = 0; v < ref.num_points(); ++v) err = std::max(err, (p[v] - ref.points[v]).norm());
  EXPECT_LT(err, 0.05);
}

// The pattern cache (UntangleOptions::pattern_cache) gives the same result bit for bit as a
// call without it, and a call on another reduction of the same size (the variables numbered
// the other way round) rebuilds it instead of taking the last one.
TEST(Untangle, APatternCacheChangesNothingAndFollowsTheReduction) {
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  std::vector<int> reversed = g.var;
  for (int& v : reversed)
    if (v >= 0) v = g.nvar - 1 - v;
  const solve::TetElements el = solve::reference_elements(ref.points, ref.cells);
  const auto solve_with = [&](const std::vector<int>& var, const std::shared_ptr<solve::PatternCache>& cache) {
    const solve::LinearReduction R = solve::index_reduction(var, g.nvar, x_init);
    Eigen::VectorXd y(g.nvar);
    for (int i = 0; i < 3 * g.mesh.num_points(); ++i)
      if (var[i] >= 0) y[var[i]] = x_init[i];
    solve::UntangleOptions o;
    o.pattern_cache = cache;
    const solve::UntangleResult r = solve::untangle(el, R, y, o);
    EXPECT_TRUE(r.untangled);
    return R.apply(y);
  };
  const Eigen::VectorXd plain = solve_with(g.var, nullptr);
  const Eigen::VectorXd plain_reversed = solve_with(reversed, nullptr);
  const std::shared_ptr<solve::PatternCache> cache = solve::make_pattern_cache();
  EXPECT_EQ(solve_with(g.var, cache), plain);  // built
  EXPECT_EQ(solve_with(g.var, cache), plain);  // reused
  EXPECT_EQ(solve_with(reversed, cache), plain_reversed);  // another reduction: built again
  EXPECT_EQ(solve_with(g.var, cache), plain);
}

// A caller's budget (UntangleOptions::expired) ends the untangling after the iteration that
// polls it, with the best state so far; the same run without it goes on.
TEST(Untangle, AnExpiredBudgetStopsAfterOneIteration) {
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  const solve::LinearReduction R = solve::index_reduction(g.var, g.nvar, x_init);
  Eigen::VectorXd y0(g.nvar);
  for (int i = 0; i < 3 * g.mesh.num_points(); ++i)
    if (g.var[i] >= 0) y0[g.var[i]] = x_init[i];
  const solve::TetElements el = solve::reference_elements(ref.points, ref.cells);
  Eigen::VectorXd y = y0;
  const solve::UntangleResult full = solve::untangle(el, R, y, {});
  ASSERT_GT(full.iterations, 1);
  int polls = 0;
  solve::UntangleOptions o;
  o.expired = [&polls] { return ++polls >= 1; };
  y = y0;
  const solve::UntangleResult cut = solve::untangle(el, R, y, o);
  EXPECT_EQ(cut.iterations, 1);
  EXPECT_EQ(polls, 1);
  EXPECT_LE(cut.inverted_after, cut.inverted_before);
}

// Steps solved by conjugate gradients preconditioned with an earlier factorization
// (UntangleOptions::stale_factor_iterations) reach the minimum the exact steps reach. A grid of
// 12³ cells with one interior vertex pushed through its neighbours: the barrier tightens around
// the few inverted tets while the rest of the system hardly changes, the case those steps are for.
TEST(Untangle, StepsOnAnEarlierFactorizationReachTheSameMinimum) {
  constexpr int kCells = 12;
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(kCells, kCells, kCells));
  const int nv = ref.num_points();
  std::vector<int> var(3 * static_cast<std::size_t>(nv), -1);
  int nvar = 0;
  for (int v = 0; v < nv; ++v) {
    const Vec3& p = ref.points[v];
    if (!((p.array() == 0.0).any() || (p.array() == kCells).any()))
      for (int d = 0; d < 3; ++d) var[3 * v + d] = nvar++;
  }
  std::vector<Vec3> start = ref.points;
  const int pushed = 6 + (kCells + 1) * (6 + (kCells + 1) * 6);  // vertex (6,6,6)
  start[pushed] += Vec3(1.7, 1.6, 1.8);
  ASSERT_GT(inverted_count(ref, start), 0);
  const Eigen::VectorXd x_init = solve::flatten(start);
  const solve::LinearReduction R = solve::index_reduction(var, nvar, x_init);
  const solve::TetElements el = solve::reference_elements(ref.points, ref.cells);
  const auto run = [&](int stale_iterations) {
    Eigen::VectorXd y(nvar);
    for (int i = 0; i < 3 * nv; ++i)
      if (var[i] >= 0) y[var[i]] = x_init[i];
    solve::UntangleOptions o;
    o.stale_factor_iterations = stale_iterations;
    const solve::UntangleResult r = solve::untangle(el, R, y, o);
    EXPECT_TRUE(r.untangled);
    EXPECT_EQ(r.factorizations + r.stale_factor_steps, r.newton_steps);
    return std::pair{r, R.apply(y)};
  };
  const auto [exact, x_exact] = run(0);
  const auto [stale, x_stale] = run(10);
  EXPECT_EQ(exact.stale_factor_steps, 0);
  EXPECT_GT(stale.stale_factor_steps, 0) << "no step used the earlier factorization";
  EXPECT_LT(stale.factorizations, exact.factorizations);
  EXPECT_NEAR(stale.energy, exact.energy, 1e-6 * std::abs(exact.energy));
  EXPECT_LT((x_stale - x_exact).cwiseAbs().maxCoeff(), 1e-4);  // cells of size 1
  EXPECT_EQ(inverted_count(ref, solve::unflatten(x_stale)), 0);
}

TEST(Untangle, SharedVariableConstraintIsExact) {
  // All interior vertices of the grid with z = 1 share one z variable (a "chart" constraint),
  // and they start tangled.
  FoldedGrid g = folded_grid();
  const core::TetMesh ref = test::tetrahedralize(test::hex_grid(3, 3, 3));
  const int nv = g.mesh.num_points();
  const int shared = g.nvar++;
  std::vector<int> members;
  for (int v = 0; v < nv; ++v)
    if (g.var[3 * v + 2] >= 0 && ref.points[v].z() == 1.0) {
      g.var[3 * v + 2] = shared;
      members.push_back(v);
    }
  ASSERT_GE(members.size(), 4u);
  // Renumber variables densely.
  std::vector<int> remap(g.nvar, -1);
  int n = 0;
  for (int& v : g.var)
    if (v >= 0) {
      if (remap[v] < 0) remap[v] = n++;
      v = remap[v];
    }
  const Eigen::VectorXd x_init = solve::flatten(g.mesh.points);
  const solve::LinearReduction R = solve::index_reduction(g.var, n, x_init);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < 3 * nv; ++i)
    if (g.var[i] >= 0) y[g.var[i]] = x_init[i];
  y[remap[shared]] = 1.3;
  solve::UntangleOptions o;
  o.attractions.push_back({0, Vec3(0, 0, 0), 1.0});  // a fixed vertex: attraction has no effect
  const solve::UntangleResult r = solve::untangle(solve::reference_elements(ref.points, ref.cells), R, y, o);
  EXPECT_TRUE(r.untangled);
  const std::vector<Vec3> p = solve::unflatten(R.apply(y));
  EXPECT_EQ(inverted_count(g.mesh, p), 0);
  for (int v : members) EXPECT_EQ(p[v].z(), p[members.front()].z());
  EXPECT_NEAR(p[members.front()].z(), 1.0, 0.05);
}

TEST(Untangle, AttractionPullsFreeVertex) {
  // One tet, all vertices free but vertex 0..2 attracted strongly to translated targets:
  // the tet follows while staying positive.
  const std::vector<Vec3> ref{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::array<int, 4>> tets{{0, 1, 2, 3}};
  const solve::LinearReduction R = solve::identity_reduction(4);
  Eigen::VectorXd y = solve::flatten(ref);
  solve::UntangleOptions o;
  for (int v = 0; v < 3; ++v) o.attractions.push_back({v, ref[v] + Vec3(5, 0, 0), 100.0});
  const auto r = solve::untangle(solve::reference_elements(ref, tets), R, y, o);
  EXPECT_TRUE(r.untangled);
  const auto p = solve::unflatten(y);
  for (int v = 0; v < 3; ++v) EXPECT_NEAR((p[v] - ref[v] - Vec3(5, 0, 0)).norm(), 0.0, 1e-2);
}


// A grid of kCells³ cells split into tets, the boundary fixed, and every interior vertex moved
// by up to `reach` cells along each axis (mt19937, fully specified by the standard): a tangle
// of many inverted tets all through the volume, harder the larger the reach.
struct ThrownGrid {
  core::TetMesh reference;
  solve::LinearReduction reduction;
  Eigen::VectorXd start;  // the free coordinates
};

ThrownGrid thrown_grid(int cells, double reach, unsigned seed) {
  ThrownGrid g;
  g.reference = test::tetrahedralize(test::hex_grid(cells, cells, cells));
  const int nv = g.reference.num_points();
  std::vector<int> var(3 * static_cast<std::size_t>(nv), -1);
  int nvar = 0;
  std::mt19937 rng(seed);
  std::vector<Vec3> moved = g.reference.points;
  for (int v = 0; v < nv; ++v) {
    const Vec3& p = g.reference.points[v];
    if ((p.array() == 0.0).any() || (p.array() == cells).any()) continue;
    for (int d = 0; d < 3; ++d) {
      var[3 * v + d] = nvar++;
      moved[v][d] += reach * (2.0 * static_cast<double>(rng()) / static_cast<double>(std::mt19937::max()) - 1.0);
    }
  }
  const Eigen::VectorXd x = solve::flatten(moved);
  g.reduction = solve::index_reduction(var, nvar, x);
  g.start.resize(nvar);
  for (int i = 0; i < 3 * nv; ++i)
    if (var[i] >= 0) g.start[var[i]] = x[i];
  return g;
}

constexpr double kFast = 0.2;

struct ScheduleRun {
  solve::UntangleResult result;
  Eigen::VectorXd y;
};

//! untangle() of the thrown grid with the floor `sigma`, or untangle_fast_first() with kFast
//! before it.
ScheduleRun run_schedule(const ThrownGrid& g, double sigma, bool fast_first) {
  const solve::TetElements el = solve::reference_elements(g.reference.points, g.reference.cells);
  solve::UntangleOptions o;
  o.min_sigma = sigma;
  ScheduleRun r{{}, g.start};
  r.result = fast_first ? solve::untangle_fast_first(el, g.reduction, r.y, o, kFast)
                        : solve::untangle(el, g.reduction, r.y, o);
  return r;
}

// untangle_fast_first: where ε falling by a fifth per iteration leaves a tet inverted (seed 9 of
// the thrown grid: one after 148 iterations), the paper's schedule runs from the same start,
// and the result is exactly untangle()'s with it.
TEST(Untangle, FastScheduleFirstFallsBackToTheOwnScheduleFromTheSameStart) {
  const ThrownGrid g = thrown_grid(6, 1.5, 9);
  const ScheduleRun fast = run_schedule(g, kFast, false);
  ASSERT_FALSE(fast.result.untangled) << "the fast schedule untangles this seed";
  const ScheduleRun paper = run_schedule(g, 0.1, false);
  ASSERT_TRUE(paper.result.untangled);
  const ScheduleRun r = run_schedule(g, 0.1, true);
  EXPECT_TRUE(r.result.untangled);
  EXPECT_TRUE(r.result.slower_schedule);
  EXPECT_EQ(r.result.iterations, paper.result.iterations);
  EXPECT_EQ(r.y, paper.y);
}

// Where the fast schedule untangles (seed 3), its result is kept as it is: no second run.
TEST(Untangle, FastScheduleFirstKeepsTheFastResultWhereItUntangles) {
  const ThrownGrid g = thrown_grid(6, 1.5, 3);
  const ScheduleRun fast = run_schedule(g, kFast, false);
  ASSERT_TRUE(fast.result.untangled);
  for (double own : {0.1, kFast}) {  // a caller whose own floor is already that high: untangle() itself
    const ScheduleRun r = run_schedule(g, own, true);
    EXPECT_TRUE(r.result.untangled);
    EXPECT_FALSE(r.result.slower_schedule);
    EXPECT_EQ(r.result.iterations, fast.result.iterations);
    EXPECT_EQ(r.y, fast.y);
  }
}

}  // namespace
}  // namespace polycube
