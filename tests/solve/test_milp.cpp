// Tests of the LP / MILP adapter (solve/milp.h): hand-solved programs through both paths (CLP for
// LPs, CBC for MILPs), infeasible and unbounded programs, the time limit and the error paths.
#include "solve/milp.h"

#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace polycube::solve {
namespace {

constexpr double kTol = 1e-7;

//! Violation of bounds, rows and integrality of x in p (0 when x is feasible).
double infeasibility(const LinearProgram& p, const std::vector<double>& x) {
  double worst = 0;
  for (int j = 0; j < p.num_variables(); ++j) {
    worst = std::max({worst, p.lower[j] - x[j], x[j] - p.upper[j]});
    if (!p.integer.empty() && p.integer[j]) worst = std::max(worst, std::abs(x[j] - std::round(x[j])));
  }
  for (const auto& r : p.rows) {
    double a = 0;
    for (std::size_t k = 0; k < r.columns.size(); ++k) a += r.coefficients[k] * x[r.columns[k]];
    worst = std::max({worst, r.lower - a, a - r.upper});
  }
  return worst;
}

double cost_of(const LinearProgram& p, const std::vector<double>& x) {
  double c = 0;
  for (int j = 0; j < p.num_variables(); ++j) c += p.cost[j] * x[j];
  return c;
}

//! Optimal status, x and objective as expected (and the objective is c·x).
void expect_optimum(const LinearProgram& p, const MilpResult& r, const std::vector<double>& x,
                    double objective) {
  ASSERT_EQ(r.status, MilpStatus::Optimal) << status_name(r.status);
  ASSERT_EQ(r.x.size(), x.size());
  for (std::size_t j = 0; j < x.size(); ++j) EXPECT_NEAR(r.x[j], x[j], kTol) << "x[" << j << "]";
  EXPECT_NEAR(r.objective, objective, kTol);
  EXPECT_NEAR(cost_of(p, r.x), objective, kTol);
  EXPECT_LE(infeasibility(p, r.x), kTol);
}

// --- linear programs (CLP) ----------------------------------------------------------------------

TEST(Milp, WyndorLpHasItsTextbookOptimum) {
  // Hillier & Lieberman's Wyndor: max 3x + 5y, x <= 4, 2y <= 12, 3x + 2y <= 18, x, y >= 0.
  // Vertex y = 6 (2y = 12), 3x = 18 - 12 -> x = 2: z = 6 + 30 = 36 (next vertex (4, 3): 27).
  LinearProgram p;
  const int x = p.add_variable(-3.0, 0.0);
  const int y = p.add_variable(-5.0, 0.0);
  p.add_row({x}, {1.0}, -kInfinity, 4.0);
  p.add_row({y}, {2.0}, -kInfinity, 12.0);
  p.add_row({x, y}, {3.0, 2.0}, -kInfinity, 18.0);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.solver, "CLP dual simplex");
  expect_optimum(p, r, {2.0, 6.0}, -36.0);
}

TEST(Milp, EqualityRowFreeVariableAndUpperBound) {
  // min x + 2y, x + y = 3, x <= 2 (x >= 0), y free: y = 3 - x gives 6 - x, least at x = 2, y = 1: 4.
  LinearProgram p;
  p.add_variable(1.0, 0.0, 2.0);
  p.add_variable(2.0);  // free
  p.add_row({0, 1}, {1.0, 1.0}, 3.0, 3.0);
  expect_optimum(p, solve_program(p), {2.0, 1.0}, 4.0);
}

TEST(Milp, RangedRowIsActiveOnEitherSide) {
  // Row 1 <= x + 2y <= 4, x in [0, 2], y >= 0.
  LinearProgram p;
  p.add_variable(0.0, 0.0, 2.0);
  p.add_variable(0.0, 0.0);
  p.add_row({0, 1}, {1.0, 2.0}, 1.0, 4.0);
  // min x + y: y costs 1/2 per unit of row (x costs 1), so x = 0, y = 1/2 on the lower side: 1/2.
  p.cost = {1.0, 1.0};
  expect_optimum(p, solve_program(p), {0.0, 0.5}, 0.5);
  // min -x - y: x gives 1 per unit of row (y 1/2), so x = 2, then 2y = 4 - 2 on the upper side: -3.
  p.cost = {-1.0, -1.0};
  expect_optimum(p, solve_program(p), {2.0, 1.0}, -3.0);
}

TEST(Milp, InfeasibleLp) {
  // x + y <= 1 and x + y >= 2.
  LinearProgram p;
  p.add_variable(1.0, 0.0);
  p.add_variable(1.0, 0.0);
  p.add_row({0, 1}, {1.0, 1.0}, -kInfinity, 1.0);
  p.add_row({0, 1}, {1.0, 1.0}, 2.0);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.status, MilpStatus::Infeasible) << status_name(r.status);
  EXPECT_TRUE(r.x.empty());
}

TEST(Milp, UnboundedLp) {
  // min -x - y, x - y <= 1, x, y >= 0: (t, t) is feasible for every t >= 0, cost -2t.
  LinearProgram p;
  p.add_variable(-1.0, 0.0);
  p.add_variable(-1.0, 0.0);
  p.add_row({0, 1}, {1.0, -1.0}, -kInfinity, 1.0);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.status, MilpStatus::Unbounded) << status_name(r.status);
  EXPECT_TRUE(r.x.empty());
}

// --- mixed-integer programs (CBC) ---------------------------------------------------------------

//! The 0/1 knapsack values {60, 100, 120}, weights {10, 20, 30}, capacity 50 (maximized).
LinearProgram knapsack(bool integer) {
  LinearProgram p;
  for (double v : {60.0, 100.0, 120.0}) p.add_variable(-v, 0.0, 1.0, integer);
  p.add_row({0, 1, 2}, {10.0, 20.0, 30.0}, -kInfinity, 50.0);
  return p;
}

TEST(Milp, KnapsackIntegerOptimumDiffersFromItsRelaxation) {
  // Relaxation: by value/weight 6 > 5 > 4, items 1 and 2 whole (weight 30) and 20/30 of item 3:
  // 60 + 100 + 80 = 240. Integer: {1,2} 160, {1,3} 180, {2,3} 220 (weight 50), {1,2,3} too heavy.
  const LinearProgram relaxed = knapsack(false);
  expect_optimum(relaxed, solve_program(relaxed), {1.0, 1.0, 2.0 / 3.0}, -240.0);
  const LinearProgram p = knapsack(true);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.solver, "CBC branch and cut");
  expect_optimum(p, r, {0.0, 1.0, 1.0}, -220.0);
}

TEST(Milp, MixedIntegerAndContinuousVariables) {
  // max 2x + y, x + y <= 4, 2x <= 5, x integer >= 0, y >= 0. Relaxation: x = 2.5, y = 1.5: 6.5.
  // For integer x <= 2, y = 4 - x and 2x + y = 4 + x: best at x = 2, y = 2: 6.
  LinearProgram p;
  p.add_variable(-2.0, 0.0, kInfinity, true);
  p.add_variable(-1.0, 0.0);
  p.add_row({0, 1}, {1.0, 1.0}, -kInfinity, 4.0);
  p.add_row({0}, {2.0}, -kInfinity, 5.0);
  expect_optimum(p, solve_program(p), {2.0, 2.0}, -6.0);
  p.integer.clear();  // all continuous: the relaxation
  expect_optimum(p, solve_program(p), {2.5, 1.5}, -6.5);
}

TEST(Milp, InfeasibleMilpWithFeasibleRelaxation) {
  // 2x + 2y = 3 with x, y integer in [0, 5]: the left side is even. (x = 1.5, y = 0 solves the LP.)
  LinearProgram p;
  p.add_variable(1.0, 0.0, 5.0, true);
  p.add_variable(1.0, 0.0, 5.0, true);
  p.add_row({0, 1}, {2.0, 2.0}, 3.0, 3.0);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.status, MilpStatus::Infeasible) << status_name(r.status);
  EXPECT_TRUE(r.x.empty());
  p.integer.clear();
  EXPECT_EQ(solve_program(p).status, MilpStatus::Optimal);
}

TEST(Milp, UnboundedMilp) {
  // min -x - y, x - y <= 1, x integer >= 0, y >= 0: (t, t) for every integer t, cost -2t.
  LinearProgram p;
  p.add_variable(-1.0, 0.0, kInfinity, true);
  p.add_variable(-1.0, 0.0);
  p.add_row({0, 1}, {1.0, -1.0}, -kInfinity, 1.0);
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.solver, "CBC branch and cut");
  EXPECT_EQ(r.status, MilpStatus::Unbounded) << status_name(r.status);
  EXPECT_TRUE(r.x.empty());
  // Both variables integer and a row x - y = -1: (t, t + 1) for every integer t >= 0.
  p.integer = {1, 1};
  p.rows[0].lower = -1.0;
  p.rows[0].upper = -1.0;
  EXPECT_EQ(solve_program(p).status, MilpStatus::Unbounded);
}

TEST(Milp, IntegerInfeasibleProgramWithUnboundedRelaxationIsNotUnbounded) {
  // min -x, 2x - 2y = 1, x, y integer >= 0: the relaxation is unbounded ((t + 1/2, t)) but the
  // left side is even, so there is no point. Branch and bound cannot prove that (it may branch
  // forever): infeasible or failed (undecided), never unbounded nor a solution.
  LinearProgram p;
  p.add_variable(-1.0, 0.0, kInfinity, true);
  p.add_variable(0.0, 0.0, kInfinity, true);
  p.add_row({0, 1}, {2.0, -2.0}, 1.0, 1.0);
  const MilpResult r = solve_program(p);
  EXPECT_TRUE(r.status == MilpStatus::Infeasible || r.status == MilpStatus::Failed) << status_name(r.status);
  EXPECT_TRUE(r.x.empty());
}

//! A market split instance (Cornuéjols & Dawande) with slacks: rows sum_j a_ij x_j + s_i - t_i = b_i,
//! x binary, s, t >= 0, minimize sum (s_i + t_i). Every a_ij is even and every b_i odd, so the
//! optimum is >= 1 per row while the LP relaxation reaches 0: branch and bound must enumerate.
LinearProgram market_split(int rows, int columns, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> half(0, 49);
  LinearProgram p;
  for (int j = 0; j < columns; ++j) p.add_variable(0.0, 0.0, 1.0, true);
  for (int i = 0; i < rows; ++i) {
    std::vector<int> cols;
    std::vector<double> coef;
    double sum = 0;
    for (int j = 0; j < columns; ++j) {
      const double a = 2.0 * half(rng);
      cols.push_back(j);
      coef.push_back(a);
      sum += a;
    }
    cols.push_back(p.add_variable(1.0, 0.0));
    coef.push_back(1.0);
    cols.push_back(p.add_variable(1.0, 0.0));
    coef.push_back(-1.0);
    const double b = 2.0 * std::floor(sum / 4.0) + 1.0;  // odd, about half the row sum
    p.add_row(std::move(cols), std::move(coef), b, b);
  }
  return p;
}

TEST(Milp, TimeLimitStopsBranchAndBound) {
  const LinearProgram p = market_split(4, 40, 2024);
  MilpOptions o;
  o.time_limit = 0.01;
  const auto t0 = std::chrono::steady_clock::now();
  const MilpResult r = solve_program(p, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.status, MilpStatus::Stopped) << status_name(r.status);
  // Branch and bound over 2^40 leaves would not end: the limit was honoured (generous bound).
  EXPECT_LT(seconds, 30.0);
  if (!r.x.empty()) {
    ASSERT_EQ(static_cast<int>(r.x.size()), p.num_variables());
    EXPECT_LE(infeasibility(p, r.x), 1e-6);
    EXPECT_NEAR(r.objective, cost_of(p, r.x), 1e-6);
    EXPECT_GE(r.objective, 4.0 - 1e-6);  // parity: every row misses its odd target by >= 1
  }
}

TEST(Milp, StoppedRunReturnsAFeasibleIncumbent) {
  // x = 0 with slacks = b is feasible and depth-first search reaches an integer leaf within some
  // 50 nodes (CBC's limit is CPU time, some 10^4 nodes in half a second, so load does not matter):
  // the run stops with a feasible incumbent, no better than the parity bound 4.
  const LinearProgram p = market_split(4, 40, 7);
  MilpOptions o;
  o.time_limit = 0.5;
  const MilpResult r = solve_program(p, o);
  EXPECT_EQ(r.status, MilpStatus::Stopped) << status_name(r.status);
  ASSERT_EQ(static_cast<int>(r.x.size()), p.num_variables());
  EXPECT_LE(infeasibility(p, r.x), 1e-6);
  EXPECT_NEAR(r.objective, cost_of(p, r.x), 1e-6);
  EXPECT_GE(r.objective, 4.0 - 1e-6);
}

TEST(Milp, AnIntegralRelaxationIsTheOptimumWithoutBranching) {
  // Assignment of 3 workers to 3 jobs (rows and columns sum to 1): the constraint matrix is
  // totally unimodular, so the relaxation's vertex optimum is integral and no branching is
  // needed. Costs: the six assignments cost 6, 6, 5, 7, 9, 11; the unique optimum is
  // worker 0 -> job 1, 1 -> 0, 2 -> 2 at 1 + 2 + 2 = 5.
  const double cost[3][3] = {{4, 1, 3}, {2, 0, 5}, {3, 2, 2}};
  LinearProgram p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.add_variable(cost[i][j], 0.0, 1.0, true);
  for (int i = 0; i < 3; ++i) {
    p.add_row({3 * i, 3 * i + 1, 3 * i + 2}, {1, 1, 1}, 1.0, 1.0);
    p.add_row({i, 3 + i, 6 + i}, {1, 1, 1}, 1.0, 1.0);
  }
  const MilpResult r = solve_program(p);
  EXPECT_EQ(r.solver, "CLP dual simplex (integral LP relaxation)");
  expect_optimum(p, r, {0, 1, 0, 1, 0, 0, 0, 0, 1}, 5.0);
  EXPECT_DOUBLE_EQ(r.bound, r.objective);
}

TEST(Milp, AFeasibleStartIsKeptUnderATimeLimitAndAnInfeasibleOneIgnored) {
  // x = 0 with slacks s = b is feasible, cost sum b: under a limit too short to search, the
  // result is that start or better. A start that breaks a row is ignored: the knapsack's
  // three items together weigh 60 > 50, and the optimum 220 is still found.
  const LinearProgram split = market_split(4, 40, 11);
  std::vector<double> start(static_cast<std::size_t>(split.num_variables()), 0.0);
  double start_cost = 0.0;
  for (std::size_t i = 0; i < split.rows.size(); ++i) {
    start[static_cast<std::size_t>(split.rows[i].columns[40])] = split.rows[i].lower;  // s_i = b_i
    start_cost += split.rows[i].lower;
  }
  ASSERT_LE(infeasibility(split, start), 1e-9);
  MilpOptions o;
  o.time_limit = 0.01;
  o.start = start;
  const MilpResult stopped = solve_program(split, o);
  ASSERT_EQ(static_cast<int>(stopped.x.size()), split.num_variables()) << status_name(stopped.status);
  EXPECT_LE(infeasibility(split, stopped.x), 1e-6);
  EXPECT_LE(stopped.objective, start_cost + 1e-9);

  const LinearProgram p = knapsack(true);
  MilpOptions bad;
  bad.start = {1.0, 1.0, 1.0};
  expect_optimum(p, solve_program(p, bad), {0.0, 1.0, 1.0}, -220.0);
}

//! An integer transportation problem, n sources of supply n to n sinks of demand n, random
//! costs: n² variables, 2n rows. Its matrix is totally unimodular, so its relaxation is integral.
LinearProgram transportation(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> cost(1, 1000);
  LinearProgram p;
  for (int i = 0; i < n * n; ++i) p.add_variable(cost(rng), 0.0, n, true);
  for (int i = 0; i < n; ++i) {
    std::vector<int> source, sink;
    for (int j = 0; j < n; ++j) {
      source.push_back(i * n + j);
      sink.push_back(j * n + i);
    }
    p.add_row(source, std::vector<double>(n, 1.0), n, n);
    p.add_row(sink, std::vector<double>(n, 1.0), n, n);
  }
  return p;
}

TEST(Milp, TheTimeLimitHoldsInsideTheRelaxationAndTheStartIsReturned) {
  // 90,000 variables: CLP needs far longer than the millisecond given for its relaxation (a
  // degenerate relaxation of the padding problem once ran for over 10 minutes under a 60 s
  // limit, which CBC checks only between nodes). The start: every source sends to its own sink.
  const int n = 300;
  const LinearProgram p = transportation(n, 5);
  std::vector<double> start(static_cast<std::size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) start[static_cast<std::size_t>(i) * n + i] = n;
  MilpOptions o;
  o.time_limit = 1e-3;
  o.start = start;
  const auto t0 = std::chrono::steady_clock::now();
  const MilpResult r = solve_program(p, o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.status, MilpStatus::Stopped) << status_name(r.status) << ", " << r.solver;
  EXPECT_EQ(r.x, start);
  EXPECT_NEAR(r.objective, cost_of(p, start), 1e-9);
  // Nothing proven: the bound is the least over the variables' bounds alone (all at 0).
  EXPECT_EQ(r.bound, 0.0);
  EXPECT_LT(seconds, 10.0);  // what the solve takes without a limit, several times over
  // Without a limit, the relaxation's integral optimum, which beats the start.
  const MilpResult optimum = solve_program(p);
  EXPECT_EQ(optimum.status, MilpStatus::Optimal);
  EXPECT_LT(optimum.objective, r.objective);
}

// --- neighbourhoods and rounding ------------------------------------------------------------------

TEST(Milp, ARestrictedProgramMovesTheFixedVariablesIntoItsRows) {
  // The knapsack with item 0 fixed out: items 1 and 2 (weights 20 and 30) fit together, 220.
  // With item 2 fixed in, 20 of the capacity is left: items 0 and 1 cannot both go, 120 + 100.
  const LinearProgram p = knapsack(true);
  const RestrictedProgram without0 = restrict_program(p, {1, 0, 0}, {0.0, 0.0, 0.0});
  ASSERT_TRUE(without0.consistent);
  EXPECT_EQ(without0.column, (std::vector<int>{1, 2}));
  EXPECT_EQ(without0.constant, 0.0);
  ASSERT_EQ(without0.program.num_rows(), 1);
  EXPECT_EQ(without0.program.rows[0].upper, 50.0);
  const MilpResult r0 = solve_program(without0.program);
  ASSERT_EQ(r0.status, MilpStatus::Optimal);
  EXPECT_EQ(without0.expand({0.0, 0.0, 0.0}, r0.x), (std::vector<double>{0.0, 1.0, 1.0}));

  const RestrictedProgram with2 = restrict_program(p, {0, 0, 1}, {0.0, 0.0, 1.0});
  ASSERT_TRUE(with2.consistent);
  EXPECT_EQ(with2.constant, -120.0);
  EXPECT_EQ(with2.program.rows[0].upper, 20.0);
  const MilpResult r2 = solve_program(with2.program);
  ASSERT_EQ(r2.status, MilpStatus::Optimal);
  EXPECT_NEAR(r2.objective + with2.constant, -220.0, kTol);
  EXPECT_EQ(with2.expand({0.0, 0.0, 1.0}, r2.x), (std::vector<double>{0.0, 1.0, 1.0}));

  // Every item fixed in: no variable left, and the row they break is reported.
  const RestrictedProgram all = restrict_program(p, {1, 1, 1}, {1.0, 1.0, 1.0});
  EXPECT_EQ(all.program.num_variables(), 0);
  EXPECT_EQ(all.program.num_rows(), 0);
  EXPECT_FALSE(all.consistent);
  EXPECT_THROW(restrict_program(p, {1, 0}, {0.0, 0.0, 0.0}), core::InternalError);
}

TEST(Milp, TheRoundingGetsTheFractionalRelaxationAndAFeasiblePointStartsTheSearch) {
  // The knapsack's relaxation is {1, 1, 2/3}: the rounding sees it, and its point ({0, 1, 1},
  // the optimum) is taken, while an infeasible one (all three items) is ignored.
  const LinearProgram p = knapsack(true);
  for (const std::vector<double>& point : {std::vector<double>{0.0, 1.0, 1.0}, std::vector<double>{1.0, 1.0, 1.0}}) {
    std::vector<double> seen;
    MilpOptions o;
    o.round = [&](const std::vector<double>& relaxation) {
      seen = relaxation;
      return point;
    };
    expect_optimum(p, solve_program(p, o), {0.0, 1.0, 1.0}, -220.0);
    ASSERT_EQ(seen.size(), 3u);
    EXPECT_NEAR(seen[0], 1.0, kTol);
    EXPECT_NEAR(seen[1], 1.0, kTol);
    EXPECT_NEAR(seen[2], 2.0 / 3.0, kTol);
  }
  // An integral relaxation needs no rounding.
  LinearProgram tu;
  tu.add_variable(1.0, 0.0, 1.0, true);
  tu.add_variable(2.0, 0.0, 1.0, true);
  tu.add_row({0, 1}, {1.0, 1.0}, 1.0);
  MilpOptions o;
  bool called = false;
  o.round = [&](const std::vector<double>&) {
    called = true;
    return std::vector<double>{};
  };
  expect_optimum(tu, solve_program(tu, o), {1.0, 0.0}, 1.0);
  EXPECT_FALSE(called);
}

TEST(Milp, ANodeLimitStopsTheSameWayEachTimeAndTheToolkitKeepsOptima) {
  // Market split is hard (parity: every row misses its odd target, cost >= 4), so 20 nodes do not
  // prove anything: the run stops, and the point it keeps does not depend on the clock.
  const LinearProgram split = market_split(4, 40, 7);
  MilpOptions o;
  o.node_limit = 20;
  o.cuts_and_heuristics = true;
  const MilpResult first = solve_program(split, o);
  EXPECT_EQ(first.status, MilpStatus::Stopped) << status_name(first.status);
  ASSERT_EQ(static_cast<int>(first.x.size()), split.num_variables());
  EXPECT_LE(infeasibility(split, first.x), 1e-6);
  EXPECT_GE(first.objective, 4.0 - 1e-6);
  EXPECT_EQ(solve_program(split, o).x, first.x);
  // The cut generators and heuristics change how, not what: the hand-solved optima again.
  const LinearProgram p = knapsack(true);
  MilpOptions with;
  with.cuts_and_heuristics = true;
  expect_optimum(p, solve_program(p, with), {0.0, 1.0, 1.0}, -220.0);
}

TEST(Milp, AProgramLargerThanBranchAndCutsCapReturnsItsBestStartWithTheRelaxationsBound) {
  // The knapsack's relaxation is fractional (240 against 220): with a time limit and a cap below
  // its 3 variables, no search runs; the start (nothing packed) comes back, not proven optimal,
  // with the relaxation's bound. At the cap or without a limit the optimum is found as before.
  const LinearProgram p = knapsack(true);
  MilpOptions o;
  o.time_limit = 60;
  o.start = {0.0, 0.0, 0.0};
  o.branch_and_cut_max_variables = 2;
  const MilpResult capped = solve_program(p, o);
  EXPECT_EQ(capped.status, MilpStatus::Stopped) << status_name(capped.status);
  EXPECT_EQ(capped.x, o.start);
  EXPECT_DOUBLE_EQ(capped.objective, 0.0);
  EXPECT_NEAR(capped.bound, -240.0, 1e-6);
  EXPECT_NE(capped.solver.find("no branch and cut"), std::string::npos) << capped.solver;
  o.branch_and_cut_max_variables = 3;
  expect_optimum(p, solve_program(p, o), {0.0, 1.0, 1.0}, -220.0);
  o.branch_and_cut_max_variables = 2;
  o.time_limit = 0;
  expect_optimum(p, solve_program(p, o), {0.0, 1.0, 1.0}, -220.0);
}

TEST(Milp, SatisfiedByChecksBoundsRowsAndIntegrality) {
  const LinearProgram p = knapsack(true);
  EXPECT_TRUE(p.satisfied_by({0.0, 1.0, 1.0}));
  EXPECT_FALSE(p.satisfied_by({1.0, 1.0, 1.0}));  // 60 > 50
  EXPECT_FALSE(p.satisfied_by({0.5, 0.0, 0.0}));  // not integral
  EXPECT_FALSE(p.satisfied_by({0.0, 2.0, 0.0}));  // above its bound
  EXPECT_FALSE(p.satisfied_by({0.0, 1.0}));       // the wrong size
  EXPECT_DOUBLE_EQ(p.objective({0.0, 1.0, 1.0}), -220.0);
}

// --- errors and names -------------------------------------------------------------------------

TEST(Milp, InconsistentSizesAndColumnsThrow) {
  const LinearProgram good = knapsack(true);
  ASSERT_EQ(solve_program(good).status, MilpStatus::Optimal);
  {
    LinearProgram p = good;
    p.lower.pop_back();
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = good;
    p.upper.push_back(1.0);
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = good;
    p.integer.pop_back();
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = good;
    p.rows[0].coefficients.pop_back();
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = good;
    p.add_row({0, 3}, {1.0, 1.0}, 0.0);  // column 3 of 3
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = good;
    p.add_row({-1}, {1.0}, 0.0);
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
  {
    LinearProgram p = knapsack(false);  // the LP path checks columns as well
    p.add_row({2, 5}, {1.0, 1.0}, 0.0);
    EXPECT_THROW(solve_program(p), core::InternalError);
  }
}

TEST(Milp, AddVariableKeepsIntegerFlagsAligned) {
  // Continuous variables before the first integer one get a 0 flag; later ones as well.
  LinearProgram p;
  p.add_variable(1.0);
  p.add_variable(1.0);
  EXPECT_TRUE(p.integer.empty());
  EXPECT_EQ(p.add_variable(1.0, 0.0, 1.0, true), 2);
  p.add_variable(1.0);
  EXPECT_EQ(p.integer, (std::vector<char>{0, 0, 1, 0}));
  EXPECT_EQ(p.num_variables(), 4);
}

TEST(Milp, StatusNames) {
  EXPECT_STREQ(status_name(MilpStatus::Optimal), "optimal");
  EXPECT_STREQ(status_name(MilpStatus::Infeasible), "infeasible");
  EXPECT_STREQ(status_name(MilpStatus::Unbounded), "unbounded");
  EXPECT_STREQ(status_name(MilpStatus::Stopped), "stopped");
  EXPECT_STREQ(status_name(MilpStatus::Failed), "failed");
}

}  // namespace
}  // namespace polycube::solve
