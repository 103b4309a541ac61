#pragma once
//! \file untangle.h
//! \brief Foldover-free untangling and shape optimization of simplicial (tet) elements with the
//! barrier-free elliptic energy of Garanzha, Kaporin, Kudryavtseva, Protais, Ray, Sokolov,
//! "Foldover-free maps in 50 lines of code" (ACM TOG 40(4), 2021).
//!
//! Each element t has a Jacobian J_t (3 by 3) mapping its **reference shape** to its current
//! shape, so J_t = I when the element has its reference shape. The energy is
//! \f[ E(x) = \sum_t w_t \Big( \frac{\mathrm{tr}(J_t^\top J_t)/3}{\chi(\det J_t,\varepsilon)^{2/3}}
//!        + \lambda\,\frac{\det^2 J_t + 1}{\chi(\det J_t,\varepsilon)} \Big)
//!        + \sum_k \omega_k \lVert x_{v_k} - p_k \rVert^2 ,\qquad
//!   \chi(D,\varepsilon) = \tfrac12\big(D + \sqrt{\varepsilon^2 + D^2}\big), \f]
//! defined for every configuration (tangled ones too). ε decreases along the outer iterations
//! by the paper's rule, so the minimizers approach the foldover-free minimizer of the ε = 0
//! energy, which is a barrier against inversion. The last term gives optional attractions of
//! vertices to target points (e.g. to a surface for hex-mesh optimization).
//!
//! Variables are reduced linearly: the 3·#V coordinates are x = B·y + x0, so fixed coordinates
//! (row of B empty) and shared coordinates (several rows selecting one column, e.g. every
//! vertex of a polycube chart sharing one coordinate) are exact constraints, not penalties.
//! Minimization is Newton's method with a per-element Hessian projected to positive
//! semi-definite, sparse Cholesky solves (solve/sparse_solver.h) and a backtracking line search.
//!
//! The engine is generic: polycube deformation uses model tets as references; hex-mesh
//! optimization can use the corner tets of hexes with unit-corner references.

#include "core/types.h"

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <array>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace polycube::solve {

//! The elements and their reference shapes.
struct TetElements {
  std::vector<std::array<int, 4>> tets;  //!< #T vertex indices (orientation: core/elements.h)
  //! #T reference gradients: row i is the gradient of the i-th barycentric function of the
  //! reference tet, so J_t = sum_i x_{tets[t][i]} * gradients[t].row(i) (3 by 3).
  std::vector<Eigen::Matrix<double, 4, 3>> gradients;
  std::vector<double> weights;  //!< #T element weights (typically reference volumes)

  [[nodiscard]] int size() const { return static_cast<int>(tets.size()); }
};

//! Elements whose reference shapes are the given tets (weights = their volumes).
//! \param points  #V reference positions
//! \param tets    #T tets, positively oriented in the reference positions
//! \param scale   reference positions are multiplied by this (so J = I means "scaled copy")
//! \throw core::GeometryError when a reference tet is flat or negatively oriented
TetElements reference_elements(const std::vector<core::Vec3>& points,
                               const std::vector<std::array<int, 4>>& tets, double scale = 1.0);

//! The Newton system's sparsity pattern of one problem's structure, kept between calls
//! (UntangleOptions::pattern_cache); make_pattern_cache() gives an empty one.
struct PatternCache;
std::shared_ptr<PatternCache> make_pattern_cache();

//! Linear reduction x = B·y + x0 of the 3·#V coordinates (coordinate d of vertex v is row 3v+d).
struct LinearReduction {
  Eigen::SparseMatrix<double, Eigen::RowMajor> B;  //!< 3#V by #y
  Eigen::VectorXd x0;                              //!< 3#V constant part

  [[nodiscard]] int num_variables() const { return static_cast<int>(B.cols()); }
  [[nodiscard]] int num_points() const { return static_cast<int>(B.rows() / 3); }
  //! x = B·y + x0.
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& y) const { return B * y + x0; }
};

//! The reduction "coordinate i is variable var[i], or fixed at fixed_value[i] when var[i] < 0".
//! Rows with a variable have coefficient exactly 1 and x0 = 0, so those coordinates equal
//! their variable bit for bit.
//! \param var          3#V variable index per coordinate, in [-1, num_variables)
//! \param fixed_value  3#V values used where var < 0
LinearReduction index_reduction(const std::vector<int>& var, int num_variables,
                                const Eigen::VectorXd& fixed_value);

//! Identity reduction (every coordinate free), with y = the flattened points.
LinearReduction identity_reduction(int num_points);

//! A point that follows the reduction's points: sum of weight[i] * point(vertex[i]) (entries
//! with vertex -1 unused) plus a constant offset.
struct DerivedPoint {
  std::array<int, 4> vertex{-1, -1, -1, -1};
  std::array<double, 4> weight{};
  core::Vec3 offset = core::Vec3::Zero();
};

//! The reduction extended by derived points: point k is reduction point num_points + k, its
//! coordinates exactly the combination of its vertices' rows (fixed ones included).
LinearReduction with_derived_points(const LinearReduction& reduction, const std::vector<DerivedPoint>& points);

//! Flatten points into a 3#V vector / unflatten.
Eigen::VectorXd flatten(const std::vector<core::Vec3>& points);
std::vector<core::Vec3> unflatten(const Eigen::VectorXd& x);

//! Quadratic attraction ω ||x_v − p||² of one vertex to a target point (per-axis factors optional).
struct Attraction {
  int vertex = -1;
  core::Vec3 target = core::Vec3::Zero();
  double weight = 0.0;  //!< ω, in energy per squared length (elements' energy ~ weight ~ volume)
  //! Per-coordinate factors of ω: the term is ω Σ_d axis_weights_d (x_{v,d} − p_d)², so a zero
  //! factor leaves that coordinate free (e.g. attraction to a plane along one axis only).
  core::Vec3 axis_weights = core::Vec3::Ones();
};

//! How untangle() solves each Newton system.
enum class NewtonSolver {
  Cholesky,           //!< sparse Cholesky (CHOLMOD): exact Newton steps
  ConjugateGradient,  //!< truncated Newton: a few Jacobi-preconditioned CG iterations (large meshes)
};

//! Options of untangle().
struct UntangleOptions {
  int max_iterations = 200;       //!< outer iterations (each ends with an ε update)
  int newton_steps = 2;           //!< Newton steps per outer iteration
  double volume_weight = 1.0;     //!< λ, weight of the volume term
  //! ε at the start (relative to det J = 1 at the reference). With few fixed coordinates a
  //! large ε lets the whole mesh shrink (χ(0, ε) = ε/2 makes a collapsed element cheap), so
  //! keep it well below 1 then.
  double initial_epsilon = 1.0;
  double min_epsilon = 1e-9;      //!< ε never goes below this
  //! Floor of σ in the ε update (σ = max(1 − E/E_prev, min_sigma), ε shrinking by about
  //! min_sigma per outer iteration while the energy rises): 0.1 is the paper's. A higher floor
  //! unfolds a hard tangle less surely (bench/RESULTS.md, stop 53) but reaches a mild one sooner.
  double min_sigma = 0.1;
  //! Stop when no element is inverted and the relative energy decrease of an outer iteration
  //! is below this.
  double tolerance = 1e-5;
  //! Stop as soon as no element is inverted (min det > min_det_target) instead of going on
  //! to reduce the distortion.
  bool stop_when_untangled = false;
  //! Elements count as inverted when det J <= this (relative to the reference; > 0 asks for
  //! a margin).
  double min_det_target = 0.0;
  //! Give up when, for this many outer iterations, neither the number of inverted elements
  //! decreased nor the min det rose by 2% of its magnitude (0 = never).
  int stall_iterations = 20;
  //! A rise of the (negative) min det counts as progress only when it is at least this much
  //! (det J relative to the reference) as well as 2% of its magnitude: with 0, a min det
  //! creeping towards 0 from below (ε following it down) counts as progress forever.
  double stall_min_det_rise = 0.0;
  std::vector<Attraction> attractions;  //!< optional extra quadratic terms
  //! Polled after every outer iteration: true ends the untangling there (the best state is kept,
  //! as when it stalls). A caller's time budget; empty: never.
  std::function<bool()> expired;
  NewtonSolver linear_solver = NewtonSolver::Cholesky;  //!< Newton system solver
  int cg_iterations = 100;     //!< ConjugateGradient: iterations per Newton step at most
  double cg_tolerance = 1e-3;  //!< ConjugateGradient: relative residual to stop at
  //! Cholesky: a step first tries at most this many conjugate-gradient iterations preconditioned
  //! by the last factorization, and factorizes anew only when they miss the tolerance below. Where
  //! the systems of successive steps differ little (a barrier that tightens around a few elements,
  //! quality rounds), a few iterations cost less than a factorization. 0: factorize every step.
  int stale_factor_iterations = 10;
  //! Relative residual ‖H d + g‖ / ‖g‖ the preconditioned iterations must reach.
  double stale_factor_tolerance = 1e-6;
  //! Optional hook called after every outer iteration with the iteration index, the current
  //! coordinates x (3#V) and the attractions; it may change their targets and weights (not
  //! their vertices), e.g. to re-project vertices onto a surface. Return false to stop.
  std::function<bool(int iteration, const Eigen::VectorXd& x, std::vector<Attraction>& attractions)>
      on_iteration;
  //! Where to keep the Newton system's sparsity pattern for the next call (make_pattern_cache;
  //! null: built every call). A call on the same element vertices, reduction and attracted
  //! vertices reuses it as it is: the quality rounds of one optimization, where building it
  //! took a third of a round's time.
  std::shared_ptr<PatternCache> pattern_cache;
};

//! Result of untangle().
struct UntangleResult {
  bool untangled = false;     //!< no inverted element at the end
  int iterations = 0;         //!< outer iterations run
  int newton_steps = 0;       //!< Newton steps run
  int factorizations = 0;     //!< Cholesky: sparse factorizations (the other steps used an earlier one)
  int stale_factor_steps = 0; //!< Cholesky: steps solved with an earlier factorization as preconditioner
  int inverted_before = 0;    //!< elements with det J <= min_det_target at the start
  int inverted_after = 0;     //!< ... at the end
  double min_det_before = 0;  //!< min det J at the start
  double min_det = 0;         //!< min det J at the end
  double energy = 0;          //!< final energy (with the final ε)
  double epsilon = 0;         //!< final ε
  double seconds = 0;         //!< wall time
  //! untangle_fast_first(): the fast schedule left elements inverted, so the options' own ran
  //! from the start again (seconds: both runs')
  bool slower_schedule = false;
};

//! Untangle and optimize: minimize the energy over y, starting from y (updated in place).
//! Never throws for a tangled result: check result.untangled.
//! \param elements   #T elements; vertex indices < reduction.num_points()
//! \param reduction  x = B·y + x0 with 3#V rows
//! \param y          #y variables, initial and final values
//! \throw core::SolverError when the sparse factorization fails beyond repair
//! \throw core::InternalError on inconsistent sizes
UntangleResult untangle(const TetElements& elements, const LinearReduction& reduction,
                        Eigen::VectorXd& y, const UntangleOptions& options = {});

//! untangle() with ε falling at least `fast_sigma` per outer iteration first (options.min_sigma
//! raised to it) and, when that leaves elements inverted, again from the same y with the
//! options' own schedule (result.slower_schedule), whose result is then exactly untangle()'s.
//! While ε is far above the |det| of the few inverted elements of a mild tangle, the paper's
//! tenth per iteration only waits for it to come down; a hard tangle unfolds more surely under
//! the slower fall (bench/RESULTS.md, stop 53), at the cost of the fast attempt.
UntangleResult untangle_fast_first(const TetElements& elements, const LinearReduction& reduction,
                                   Eigen::VectorXd& y, const UntangleOptions& options, double fast_sigma);

namespace detail {
//! The Newton system untangle() assembles at y, exposed for tests: the upper triangle of the
//! projected Hessian in y (pattern included) and the gradient in y.
std::pair<Eigen::SparseMatrix<double>, Eigen::VectorXd> newton_system(const TetElements& elements,
                                                                     const LinearReduction& reduction,
                                                                     const Eigen::VectorXd& y, double epsilon,
                                                                     double volume_weight,
                                                                     const std::vector<Attraction>& attractions = {});
}  // namespace detail

//! Elliptic energy of one Jacobian (shape + λ·volume terms, weight 1) and its derivatives with
//! respect to the 9 entries of J in row-major order (exposed for tests and other optimizers).
struct ElementEnergy {
  double value = 0;
  Eigen::Matrix<double, 9, 1> gradient;
  Eigen::Matrix<double, 9, 9> hessian;  //!< exact (not projected)
};
ElementEnergy elliptic_energy(const Eigen::Matrix3d& J, double epsilon, double volume_weight);

//! The Hessian the Newton steps use: elliptic_energy's when positive semi-definite, else its
//! projection onto the PSD cone (negative eigenvalues set to 0), from the energy's analytic
//! eigensystem in J's singular frame.
Eigen::Matrix<double, 9, 9> projected_elliptic_hessian(const Eigen::Matrix3d& J, double epsilon, double volume_weight);

//! χ(D, ε) evaluated stably for negative D.
double chi(double det, double epsilon);

}  // namespace polycube::solve
