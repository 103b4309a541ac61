#include "solve/milp.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"

#include <CbcHeuristic.hpp>
#include <CbcHeuristicFPump.hpp>
#include <CbcHeuristicLocal.hpp>
#include <CbcHeuristicRINS.hpp>
#include <CbcModel.hpp>
#include <CglClique.hpp>
#include <CglGomory.hpp>
#include <CglMixedIntegerRounding2.hpp>
#include <CglProbing.hpp>
#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <OsiClpSolverInterface.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace polycube::solve {

namespace {

double coin_bound(double v, double inf) {
  if (std::isinf(v)) return v > 0 ? inf : -inf;
  return v;
}

//! Node limit of the search for a feasible point in infeasible_or_unbounded().
constexpr int kFeasibilityNodes = 1000;

//! CBC 2.10 reports a MILP whose LP relaxation is unbounded as proven infeasible. Such a MILP is
//! unbounded when it has a feasible point at all (rational data, Meyer 1974), so: Infeasible when
//! the relaxation is bounded (or infeasible), else Unbounded when a short branch and bound with a
//! zero objective finds a point, Infeasible when it proves there is none, Failed when undecided.
MilpStatus infeasible_or_unbounded(const OsiClpSolverInterface& original, const MilpOptions& options) {
  OsiClpSolverInterface relaxation(original);
  relaxation.messageHandler()->setLogLevel(0);
  relaxation.getModelPtr()->messageHandler()->setLogLevel(0);
  // A deadline of its own: the copy keeps the original's, which may have passed.
  relaxation.getModelPtr()->setMaximumWallSeconds(options.time_limit > 0 ? options.time_limit : -1.0);
  relaxation.initialSolve();
  if (!relaxation.isProvenDualInfeasible()) return MilpStatus::Infeasible;
  OsiClpSolverInterface feasibility(original);
  const std::vector<double> zero(static_cast<std::size_t>(original.getNumCols()), 0.0);
  feasibility.setObjective(zero.data());
  CbcModel model(feasibility);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  model.setMaximumNodes(kFeasibilityNodes);
  if (options.time_limit > 0) model.setMaximumSeconds(options.time_limit);
  model.branchAndBound();
  if (model.bestSolution()) return MilpStatus::Unbounded;
  if (model.isProvenInfeasible()) return MilpStatus::Infeasible;
  return MilpStatus::Failed;
}

//! CBC's default integer tolerance: a value this close to an integer counts as that integer.
constexpr double kIntegerTolerance = 1e-6;
//! Feasibility tolerance of a given start (rows and bounds), as CLP's primal tolerance.
constexpr double kFeasibilityTolerance = 1e-7;
//! An integer point within this relative distance of the relaxation's optimum is optimal (CLP's
//! optimum is itself only this exact).
constexpr double kBoundTolerance = 1e-7;

//! The LP relaxation's solution with its integer variables rounded, when every one of them is
//! within kIntegerTolerance of an integer; empty otherwise.
std::vector<double> integral_solution(const LinearProgram& p, const double* x) {
  std::vector<double> out(x, x + p.num_variables());
  for (std::size_t j = 0; j < out.size(); ++j) {
    if (!p.integer[j]) continue;
    const double r = std::round(out[j]);
    if (std::abs(out[j] - r) > kIntegerTolerance) return {};
    out[j] = r;
  }
  return out;
}

//! CBC's usual cut generators and primal heuristics (MilpOptions::cuts_and_heuristics). The
//! model copies them.
void add_cuts_and_heuristics(CbcModel& model) {
  CglProbing probing;
  probing.setUsingObjective(1);
  probing.setMaxPass(1);
  probing.setMaxProbe(10);
  probing.setMaxLook(10);
  model.addCutGenerator(&probing, -1, "Probing");
  CglGomory gomory;
  gomory.setLimit(100);
  model.addCutGenerator(&gomory, -1, "Gomory");
  CglClique clique;
  clique.setStarCliqueReport(false);  // they print to stdout otherwise
  clique.setRowCliqueReport(false);
  model.addCutGenerator(&clique, -1, "Clique");
  CglMixedIntegerRounding2 mir;
  model.addCutGenerator(&mir, -1, "MixedIntegerRounding2");
  CbcRounding rounding(model);
  model.addHeuristic(&rounding);
  CbcHeuristicFPump pump(model);
  model.addHeuristic(&pump);
  CbcHeuristicLocal local(model);
  model.addHeuristic(&local);
  CbcHeuristicRINS rins(model);
  model.addHeuristic(&rins);
}

//! The cheaper of the start and the caller's rounding of the relaxation (when each is feasible),
//! for branch and cut to start from; empty when neither is.
std::vector<double> best_start(const LinearProgram& p, const MilpOptions& options, const OsiClpSolverInterface& si) {
  std::vector<double> best;
  if (!options.start.empty() && p.satisfied_by(options.start)) best = options.start;
  if (options.round && si.isProvenOptimal()) {
    const double* x = si.getColSolution();
    std::vector<double> rounded = options.round(std::vector<double>(x, x + p.num_variables()));
    if (p.satisfied_by(rounded) && (best.empty() || p.objective(rounded) < p.objective(best)))
      best = std::move(rounded);
  }
  return best;
}

//! ClpModel::status() of a solve stopped on its iteration or time limit.
constexpr int kStoppedOnLimit = 3;

//! The least the objective can be over the variables' bounds alone (the rows ignored): a valid
//! lower bound on the optimum when nothing better was proven (-infinity when unbounded below).
double bound_over_the_box(const LinearProgram& p) {
  double b = 0.0;
  for (int j = 0; j < p.num_variables(); ++j) {
    if (p.cost[j] == 0.0) continue;
    const double end = p.cost[j] > 0.0 ? p.lower[j] : p.upper[j];
    if (std::isinf(end)) return -kInfinity;
    b += p.cost[j] * end;
  }
  return b;
}

//! The result when the time limit ran out or branch and cut is not run: `best` (its incumbent,
//! or null) or else the start when it is feasible (else no point), not proven optimal, with
//! `bound`.
MilpResult stopped_at_the_limit(const LinearProgram& p, const MilpOptions& options, const double* best,
                                double bound, std::string solver) {
  MilpResult res;
  res.solver = std::move(solver);
  res.status = MilpStatus::Stopped;
  if (best != nullptr) {
    res.x.assign(best, best + p.num_variables());
  } else if (!options.start.empty() && p.satisfied_by(options.start)) {
    res.x = options.start;
  }
  if (!res.x.empty()) res.objective = p.objective(res.x);
  res.bound = bound;
  return res;
}

}  // namespace

int LinearProgram::add_variable(double cost_coefficient, double lower_bound, double upper_bound, bool is_integer) {
  cost.push_back(cost_coefficient);
  lower.push_back(lower_bound);
  upper.push_back(upper_bound);
  if (is_integer || !integer.empty()) {
    integer.resize(cost.size() - 1, 0);
    integer.push_back(is_integer ? 1 : 0);
  }
  return static_cast<int>(cost.size()) - 1;
}

int LinearProgram::add_row(std::vector<int> columns, std::vector<double> coefficients, double lower_bound,
                           double upper_bound) {
  Row r;
  r.columns = std::move(columns);
  r.coefficients = std::move(coefficients);
  r.lower = lower_bound;
  r.upper = upper_bound;
  rows.push_back(std::move(r));
  return static_cast<int>(rows.size()) - 1;
}

bool LinearProgram::satisfied_by(const std::vector<double>& x) const {
  if (static_cast<int>(x.size()) != num_variables()) return false;
  for (int j = 0; j < num_variables(); ++j) {
    if (!(x[j] >= lower[j] - kFeasibilityTolerance && x[j] <= upper[j] + kFeasibilityTolerance)) return false;
    if (!integer.empty() && integer[j] && std::abs(x[j] - std::round(x[j])) > kIntegerTolerance) return false;
  }
  for (const auto& r : rows) {
    double a = 0.0;
    for (std::size_t k = 0; k < r.columns.size(); ++k) a += r.coefficients[k] * x[r.columns[k]];
    if (!(a >= r.lower - kFeasibilityTolerance && a <= r.upper + kFeasibilityTolerance)) return false;
  }
  return true;
}

double LinearProgram::objective(const std::vector<double>& x) const {
  double c = 0.0;
  for (int j = 0; j < num_variables(); ++j) c += cost[j] * x[j];
  return c;
}

std::vector<double> RestrictedProgram::expand(const std::vector<double>& values, const std::vector<double>& x) const {
  std::vector<double> out = values;
  for (std::size_t j = 0; j < column.size(); ++j) out[column[j]] = x[j];
  return out;
}

RestrictedProgram restrict_program(const LinearProgram& p, const std::vector<char>& fixed,
                                   const std::vector<double>& values) {
  PC_REQUIRE(static_cast<int>(fixed.size()) == p.num_variables() && values.size() == fixed.size(),
             "fixed flags or values differ in size from the program");
  RestrictedProgram r;
  std::vector<int> index(fixed.size(), -1);
  for (int j = 0; j < p.num_variables(); ++j) {
    if (fixed[j]) {
      r.constant += p.cost[j] * values[j];
      continue;
    }
    index[j] = r.program.add_variable(p.cost[j], p.lower[j], p.upper[j], !p.integer.empty() && p.integer[j] != 0);
    r.column.push_back(j);
  }
  for (const auto& row : p.rows) {
    std::vector<int> cols;
    std::vector<double> coefs;
    double moved = 0.0;
    for (std::size_t k = 0; k < row.columns.size(); ++k) {
      const int j = row.columns[k];
      if (fixed[j]) {
        moved += row.coefficients[k] * values[j];
      } else {
        cols.push_back(index[j]);
        coefs.push_back(row.coefficients[k]);
      }
    }
    if (cols.empty()) {
      r.consistent = r.consistent && moved >= row.lower - kFeasibilityTolerance && moved <= row.upper + kFeasibilityTolerance;
      continue;
    }
    r.program.add_row(std::move(cols), std::move(coefs), row.lower - moved, row.upper - moved);
  }
  return r;
}

bool meets_bound(double objective, double bound) {
  return objective - bound <= kBoundTolerance * std::max(1.0, std::abs(bound));
}

const char* status_name(MilpStatus status) {
  switch (status) {
    case MilpStatus::Optimal: return "optimal";
    case MilpStatus::Infeasible: return "infeasible";
    case MilpStatus::Unbounded: return "unbounded";
    case MilpStatus::Stopped: return "stopped";
    case MilpStatus::Failed: return "failed";
  }
  return "?";
}

MilpResult solve_program(const LinearProgram& p, const MilpOptions& options) {
  const int n = p.num_variables();
  PC_REQUIRE(p.lower.size() == p.cost.size() && p.upper.size() == p.cost.size(), "variable arrays differ in size");
  PC_REQUIRE(p.integer.empty() || p.integer.size() == p.cost.size(), "integer flags differ in size");
  bool has_integer = false;
  for (char c : p.integer) has_integer = has_integer || c != 0;

  OsiClpSolverInterface si;
  const double inf = si.getInfinity();
  // The matrix from triplets in one go: appending rows one by one copies it each time
  // (quadratic; minutes for the 10^5 rows of the padding problem).
  std::vector<int> row_index, column_index;
  std::vector<double> element;
  std::vector<double> rlo, rup;
  rlo.reserve(p.rows.size());
  rup.reserve(p.rows.size());
  for (std::size_t i = 0; i < p.rows.size(); ++i) {
    const auto& r = p.rows[i];
    PC_REQUIRE(r.columns.size() == r.coefficients.size(), "row sizes differ");
    for (std::size_t k = 0; k < r.columns.size(); ++k) {
      PC_REQUIRE(r.columns[k] >= 0 && r.columns[k] < n, "row column out of range");
      row_index.push_back(static_cast<int>(i));
      column_index.push_back(r.columns[k]);
      element.push_back(r.coefficients[k]);
    }
    rlo.push_back(coin_bound(r.lower, inf));
    rup.push_back(coin_bound(r.upper, inf));
  }
  CoinPackedMatrix matrix(false, row_index.data(), column_index.data(), element.data(),
                          static_cast<CoinBigIndex>(element.size()));
  matrix.setDimensions(static_cast<int>(p.rows.size()), n);
  std::vector<double> clo(static_cast<std::size_t>(n)), cup(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    clo[j] = coin_bound(p.lower[j], inf);
    cup[j] = coin_bound(p.upper[j], inf);
  }
  si.loadProblem(matrix, clo.data(), cup.data(), p.cost.data(), rlo.data(), rup.data());
  si.messageHandler()->setLogLevel(0);
  si.getModelPtr()->messageHandler()->setLogLevel(0);

  MilpResult res;
  if (!has_integer) {
    res.solver = "CLP dual simplex";
    si.initialSolve();
    if (si.isProvenOptimal()) {
      res.status = MilpStatus::Optimal;
    } else if (si.isProvenPrimalInfeasible()) {
      res.status = MilpStatus::Infeasible;
      return res;
    } else if (si.isProvenDualInfeasible()) {
      res.status = MilpStatus::Unbounded;
      return res;
    } else {
      res.status = MilpStatus::Failed;
      return res;
    }
    const double* x = si.getColSolution();
    res.x.assign(x, x + n);
    res.objective = si.getObjValue();
    return res;
  }

  // The LP relaxation first, with CLP's presolve (several times faster on the 10^5-row padding
  // problem than CBC's own first solve). When its optimum is integral it is the program's
  // optimum: no integer point can cost less than the relaxation's. Otherwise branch and cut
  // starts from its basis.
  const core::Stopwatch clock;
  // CBC checks its limit only between nodes, so the relaxation gets the limit itself (a wall-
  // clock deadline that CBC's copies of the solver keep): a degenerate relaxation of the padding
  // problem ran in the primal simplex for over 10 minutes under a 60 s limit.
  if (options.time_limit > 0) si.getModelPtr()->setMaximumWallSeconds(options.time_limit);
  si.initialSolve();
  core::logger().debug("milp: relaxation {:.6f}, {} simplex iterations, {:.1f} s", si.getObjValue(),
                       si.getIterationCount(), clock.seconds());
  PC_REQUIRE(options.start.empty() || static_cast<int>(options.start.size()) == n, "start solution has the wrong size");
  if (si.getModelPtr()->status() == kStoppedOnLimit)
    return stopped_at_the_limit(p, options, nullptr, bound_over_the_box(p),
                                "CLP dual simplex (LP relaxation stopped at the time limit)");
  if (si.isProvenOptimal()) {
    std::vector<double> x = integral_solution(p, si.getColSolution());
    if (!x.empty()) {
      res.solver = "CLP dual simplex (integral LP relaxation)";
      res.status = MilpStatus::Optimal;
      res.objective = p.objective(x);
      res.bound = res.objective;
      res.x = std::move(x);
      return res;
    }
  } else if (si.isProvenPrimalInfeasible()) {
    res.solver = "CLP dual simplex (LP relaxation)";
    res.status = MilpStatus::Infeasible;  // no real point, so no integer one
    return res;
  }
  // The start, or the caller's rounding of the relaxation: when it costs what the relaxation
  // does, no integer point costs less, and branch and cut has nothing left to prove.
  const std::vector<double> first = best_start(p, options, si);
  if (!first.empty() && si.isProvenOptimal() &&
      meets_bound(p.objective(first), si.getObjValue())) {
    res.solver = "CLP dual simplex (LP relaxation, its bound met by a rounded point)";
    res.status = MilpStatus::Optimal;
    res.objective = p.objective(first);
    res.bound = si.getObjValue();
    res.x = first;
    return res;
  }
  if (options.time_limit > 0 && options.branch_and_cut_max_variables > 0 && n > options.branch_and_cut_max_variables)
    return stopped_at_the_limit(p, options, first.empty() ? nullptr : first.data(),
                                si.isProvenOptimal() ? si.getObjValue() : bound_over_the_box(p),
                                fmt::format("CLP dual simplex (LP relaxation; no branch and cut: {} variables, more than "
                                            "it can search within the time limit)",
                                            n));
  res.solver = "CBC branch and cut";
  for (int j = 0; j < n; ++j)
    if (p.integer[j]) si.setInteger(j);
  CbcModel model(si);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  // The time limit covers the relaxation too; CBC still gets a moment to return the start.
  if (options.time_limit > 0) model.setMaximumSeconds(std::max(options.time_limit - clock.seconds(), 1e-3));
  if (options.relative_gap > 0) model.setAllowableFractionGap(options.relative_gap);
  if (options.node_limit > 0) model.setMaximumNodes(options.node_limit);
  if (options.cuts_and_heuristics) add_cuts_and_heuristics(model);
  // Checked in one pass over the rows (best_start); CBC's own check re-solves the LP with the
  // integers fixed (seconds on the padding problem).
  if (!first.empty()) model.setBestSolution(first.data(), n, p.objective(first), false);
  const double relaxation_bound = si.isProvenOptimal() ? si.getObjValue() : bound_over_the_box(p);
  model.branchAndBound();
  core::logger().debug("milp: branch and cut: {} nodes, {:.1f} s, {}", model.getNodeCount(), clock.seconds(),
                       model.bestSolution() ? fmt::format("best {:.6f}", model.getObjValue()) : "no point of its own");
  // Past the deadline the LPs inside branch and cut were cut short, and CBC then takes a stopped
  // LP for an infeasible node: neither its verdict nor its bound is a proof; the relaxation's is.
  if (options.time_limit > 0 && clock.seconds() >= options.time_limit)
    return stopped_at_the_limit(p, options, model.bestSolution(), relaxation_bound, res.solver);
  if (model.isProvenOptimal()) {
    res.status = MilpStatus::Optimal;
  } else if (model.isProvenInfeasible()) {
    res.status = infeasible_or_unbounded(si, options);
    return res;
  } else if (model.isProvenDualInfeasible()) {
    res.status = MilpStatus::Unbounded;
    return res;
  } else {
    // Stopped on the time limit (with or without an incumbent), or abandoned.
    res.status = model.bestSolution() || model.status() == 1 ? MilpStatus::Stopped : MilpStatus::Failed;
  }
  if (const double* x = model.bestSolution()) {
    res.x.assign(x, x + n);
    res.objective = model.getObjValue();
  }
  res.bound = res.status == MilpStatus::Optimal ? res.objective : model.getBestPossibleObjValue();
  return res;
}

}  // namespace polycube::solve
