#pragma once
//! \file sparse_solver.h
//! \brief Sparse symmetric positive-definite linear systems through CHOLMOD (SuiteSparse):
//! analyze the pattern once, factorize many times with new values, solve many right-hand sides.
//!
//! The rest of the project never includes a CHOLMOD header: this adapter takes Eigen matrices.
//! Matrices are column-major `Eigen::SparseMatrix<double>`; only the **upper triangle** (row <=
//! column) is read, so callers may store the upper triangle only or the full symmetric matrix.

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

namespace polycube::solve {

//! Cholesky factorization of sparse SPD matrices sharing one sparsity pattern.
//!
//! Typical use (Newton iterations): analyze(A) once, then factorize(A) and solve(b) at every
//! iteration with the same pattern and new values.
class SparseSpdSolver {
 public:
  SparseSpdSolver();
  ~SparseSpdSolver();
  SparseSpdSolver(const SparseSpdSolver&) = delete;
  SparseSpdSolver& operator=(const SparseSpdSolver&) = delete;
  SparseSpdSolver(SparseSpdSolver&&) noexcept;
  SparseSpdSolver& operator=(SparseSpdSolver&&) noexcept;

  //! Symbolic analysis (fill-reducing ordering) of the pattern of A.
  //! \param A  n by n, compressed column-major; entries below the diagonal are ignored
  //! \throw core::SolverError when A is not square or CHOLMOD fails
  void analyze(const Eigen::SparseMatrix<double>& A);

  //! Numeric factorization of A, whose pattern must be the analyzed one (analyze() is called
  //! first when nothing was analyzed yet or the size changed).
  //! \return false when A is not (numerically) positive definite; the solver then cannot solve
  //!         until a later factorize() succeeds
  //! \throw core::SolverError on other CHOLMOD failures (out of memory, ...)
  bool factorize(const Eigen::SparseMatrix<double>& A);

  //! Solve A x = b with the last successful factorization.
  //! \param b  n right-hand side (or n by k block)
  //! \throw core::SolverError when no factorization is available or sizes differ
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  [[nodiscard]] Eigen::MatrixXd solve(const Eigen::MatrixXd& b) const;

  //! Size n of the analyzed matrix (0 before analyze()).
  [[nodiscard]] int size() const;
  //! The analysis' flops of one factorization over those of one solve (4 per factor nonzero):
  //! how many solves a factorization costs, counting flops (0 before analyze()). The solves are
  //! memory-bound, so in time a factorization is worth several times fewer of them.
  [[nodiscard]] double factorization_flops_per_solve() const;
  //! True when a successful factorization is available.
  [[nodiscard]] bool factorized() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Add ρ·I to a symmetric matrix given as triplets (n by n), with ρ = 1e-8 × the mean of the
//! diagonal entries: removes the null space of the translations of a Laplacian-like matrix
//! without changing its solutions measurably. Returns ρ (the right-hand side then gets ρ·x0 to
//! keep the system's solution near x0).
double add_tiny_diagonal(std::vector<Eigen::Triplet<double>>& triplets, int n);

//! One-shot solve of the SPD system A x = b (upper triangle of A read).
//! \throw core::SolverError when A is not positive definite or CHOLMOD fails
Eigen::VectorXd solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b);

}  // namespace polycube::solve
