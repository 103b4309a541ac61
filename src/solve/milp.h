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
  [[nodiscard]] int num_variables() const { return static_cast<int>(cost.size()); }
  [[nodiscard]] int num_rows() const { return static_cast<int>(rows.size()); }
};

//! Options of solve_program().
struct MilpOptions {
  double time_limit = 0.0;  //!< seconds for the relaxation and branch and cut (0: none); ignored for LPs
  double relative_gap = 0.0;  //!< stop branch and cut at this relative optimality gap
  //! A feasible solution to start branch and cut from (#x values; empty: none). Checked: an
  //! infeasible start is ignored. With a time limit, the result is never worse than the start.
  std::vector<double> start;
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

//! Solve the program. Never throws for infeasible or unbounded programs (see status).
//! \throw core::InternalError on inconsistent sizes or out-of-range columns
MilpResult solve_program(const LinearProgram& program, const MilpOptions& options = {});

//! "optimal", "infeasible", ...
const char* status_name(MilpStatus status);

}  // namespace polycube::solve
