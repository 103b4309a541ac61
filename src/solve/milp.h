#pragma once
//! \file milp.h
//! \brief Linear and mixed-integer linear programs (thin adapter over COIN-OR CLP and CBC), so
//! the rest of the project never includes a COIN header.
//!
//! A program is: minimize c·x subject to row_lower <= A·x <= row_upper and
//! lower <= x <= upper, with some variables integer. Without integer variables it is solved as
//! an LP with CLP's dual simplex (a basic, i.e. vertex, solution is returned); with integer
//! variables its LP relaxation is solved first (an integral optimum of the relaxation is the
//! program's optimum), then, when that is fractional, by branch and cut with CBC.

#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace polycube::solve {

//! Infinity for bounds (= std::numeric_limits<double>::infinity()).
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

//! A (mixed-integer) linear program in row form.
struct LinearProgram {
  //! One linear row: row_lower <= sum coefficients[k] * x[columns[k]] <= row_upper.
  struct Row {
    std::vector<int> columns;
    std::vector<double> coefficients;
    double lower = -kInfinity;
    double upper = kInfinity;
  };

  std::vector<double> cost;    //!< #x objective coefficients (minimized)
  std::vector<double> lower;   //!< #x variable lower bounds (-kInfinity allowed)
  std::vector<double> upper;   //!< #x variable upper bounds (kInfinity allowed)
  std::vector<char> integer;   //!< #x 1 for integer variables (may be empty: all continuous)
  std::vector<Row> rows;

  //! Add a variable; returns its index.
  int add_variable(double cost_coefficient, double lower_bound = -kInfinity,
                   double upper_bound = kInfinity, bool is_integer = false);
  //! Add a row; returns its index.
  int add_row(std::vector<int> columns, std::vector<double> coefficients, double lower_bound,
              double upper_bound = kInfinity);
  //! Whether x keeps every bound and row (within CLP's primal tolerance, 1e-7) and its integer
  //! variables are integers (within CBC's, 1e-6).
  [[nodiscard]] bool satisfied_by(const std::vector<double>& x) const;
  //! c·x.
  [[nodiscard]] double objective(const std::vector<double>& x) const;
  [[nodiscard]] int num_variables() const { return static_cast<int>(cost.size()); }
  [[nodiscard]] int num_rows() const { return static_cast<int>(rows.size()); }
};

//! Options of solve_program().
struct MilpOptions {
  double time_limit = 0.0;  //!< seconds for the relaxation and branch and cut (0: none); ignored for LPs
  double relative_gap = 0.0;  //!< stop branch and cut at this relative optimality gap
  //! Stop branch and cut after this many nodes (0: no limit): unlike a time limit, a result
  //! that does not depend on the machine's speed or load.
  int node_limit = 0;
  //! Give branch and cut CBC's usual cut generators (probing, Gomory, clique, MIR) and primal
  //! heuristics (rounding, feasibility pump, local search, RINS), which a bare CBC model has none
  //! of. On programs of a few thousand rows they find points and close gaps that plain branching
  //! does not in thousands of nodes; on 10^5 rows each round of them costs minutes.
  bool cuts_and_heuristics = false;
  //! With a time limit, branch and cut runs only on programs of at most this many variables (0:
  //! any size). A larger program whose relaxation is fractional returns the cheaper of `start`
  //! and `round`'s point, status Stopped with the relaxation's bound: what it returns then does
  //! not depend on the machine's speed. On programs of 10^5 variables CBC's root node alone
  //! (strong branching on LPs that take tens of seconds each) outlasts a minute.
  int branch_and_cut_max_variables = 0;
  //! A feasible solution to start branch and cut from (#x values; empty: none). Checked: an
  //! infeasible start is ignored. With a time limit, the result is never worse than the start.
  std::vector<double> start;
  //! A heuristic that turns the LP relaxation's fractional solution (#x values) into an integer
  //! point (#x values; empty: none found), run once when the relaxation is not integral. Its
  //! point is checked like the start; the cheaper of the two starts branch and cut. Problem
  //! knowledge (which rounding keeps the rows) lives with the caller, not here.
  std::function<std::vector<double>(const std::vector<double>& relaxation)> round;
};

//! Status of a solve.
enum class MilpStatus { Optimal, Infeasible, Unbounded, Stopped, Failed };

//! Result of solve_program().
struct MilpResult {
  MilpStatus status = MilpStatus::Failed;
  std::vector<double> x;   //!< #x solution (empty unless Optimal or Stopped with a solution)
  double objective = 0.0;  //!< c·x
  //! Best lower bound on the optimum that branch and cut proved (= objective when Optimal).
  double bound = 0.0;
  //! "CLP dual simplex", "CLP dual simplex (integral LP relaxation)", "CLP dual simplex (LP
  //! relaxation)" (an infeasible relaxation), "CLP dual simplex (LP relaxation stopped at the
  //! time limit)" (Stopped, with the start as x when it is feasible) or "CBC branch and cut"
  std::string solver;
};

//! A program with some variables fixed, over the others (restrict_program()).
struct RestrictedProgram {
  LinearProgram program;    //!< over the free variables only
  std::vector<int> column;  //!< the original's index of each of program's variables
  double constant = 0.0;    //!< cost of the fixed variables
  bool consistent = true;   //!< false when a row of fixed variables only does not hold
  //! The original program's point: `values` with program's solution x written over the free
  //! variables.
  [[nodiscard]] std::vector<double> expand(const std::vector<double>& values, const std::vector<double>& x) const;
};

//! The program over the variables not `fixed`: each fixed variable's value (`values`) moves into
//! the bounds of its rows, and rows left without a variable are dropped (checked: `consistent`).
//! A neighbourhood of a few thousand variables of a 10^5-variable program solves in
//! milliseconds where the whole one takes minutes.
RestrictedProgram restrict_program(const LinearProgram& p, const std::vector<char>& fixed,
                                   const std::vector<double>& values);

//! Solve the program. Never throws for infeasible or unbounded programs (see status).
//! \throw core::InternalError on inconsistent sizes or out-of-range columns
MilpResult solve_program(const LinearProgram& program, const MilpOptions& options = {});

//! Whether an integer point of cost `objective` is optimal because it costs what the relaxation's
//! optimum `bound` does (within CLP's relative accuracy, 1e-7).
bool meets_bound(double objective, double bound);

//! "optimal", "infeasible", ...
const char* status_name(MilpStatus status);

}  // namespace polycube::solve
