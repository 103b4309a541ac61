//! CHOLMOD adapter (see sparse_solver.h).
#include "solve/sparse_solver.h"

#include "core/errors.h"
#include "core/log.h"

#include <algorithm>
#include <cholmod.h>
#include <dlfcn.h>

#include <mutex>

#include <string>

namespace polycube::solve {

namespace {

//! View an Eigen compressed column-major matrix as a CHOLMOD matrix (no copy), upper triangle.
cholmod_sparse view(const Eigen::SparseMatrix<double>& A) {
  if (!A.isCompressed()) throw core::SolverError("sparse solver: matrix is not compressed");
  cholmod_sparse s{};
  s.nrow = static_cast<size_t>(A.rows());
  s.ncol = static_cast<size_t>(A.cols());
  s.nzmax = static_cast<size_t>(A.nonZeros());
  s.p = const_cast<int*>(A.outerIndexPtr());
  s.i = const_cast<int*>(A.innerIndexPtr());
  s.nz = nullptr;
  s.x = const_cast<double*>(A.valuePtr());
  s.z = nullptr;
  s.stype = 1;  // symmetric, upper triangle stored (lower entries ignored)
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

std::string status_text(int status) {
  switch (status) {
    case CHOLMOD_OK: return "ok";
    case CHOLMOD_NOT_INSTALLED: return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
    case CHOLMOD_TOO_LARGE: return "problem too large";
    case CHOLMOD_INVALID: return "invalid input";
    case CHOLMOD_GPU_PROBLEM: return "GPU problem";
    case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
    case CHOLMOD_DSMALL: return "tiny diagonal entry";
    default: return "status " + std::to_string(status);
  }
}

//! The supernodal factorization's dense blocks go to the BLAS, and a threaded BLAS (OpenBLAS,
//! Debian's default) splits them by its thread count, which changes the rounding: the same
//! input gave other maps on one thread than on two. Run the BLAS (and OpenMP) on one thread,
//! so results do not depend on the machine's cores; our own parallel loops (TBB) are
//! deterministic. Its idle threads also spin, which slowed two jobs side by side by 1.4x.
//! CHOLMOD's own OpenMP loops (clearing its workspace and each supernode) ask for four threads
//! with a num_threads clause, which omp_set_num_threads does not lower; those threads then
//! spun beside ours after every loop (a fifth of the optimizer's time on a small mesh). With
//! no active parallel level allowed, every region runs on the thread that opens it. The
//! OpenMP settings belong to the calling thread, so each thread that factorizes makes them.
//! Where the program's GOMP_parallel (end of this file) is bound, the regions never reach the
//! runtime and these settings are the fallback for a link where it is not.
//! Looked up by name, so that any BLAS and any OpenMP runtime link.
void single_threaded_blas() {
  using SetInt = void (*)(int);
  const auto call = [](const char* name, int value) {
    if (void* f = dlsym(RTLD_DEFAULT, name)) reinterpret_cast<SetInt>(f)(value);
  };
  static std::once_flag once;
  std::call_once(once, [&call] { call("openblas_set_num_threads", 1); });
  thread_local bool openmp_set = false;
  if (openmp_set) return;
  openmp_set = true;
  call("omp_set_num_threads", 1);
  call("omp_set_max_active_levels", 0);
}

}  // namespace

struct SparseSpdSolver::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  int n = 0;
  bool ok = false;
  double lnz = 0;    // nonzeros of the factor (analysis)
  double flops = 0;  // flops of one factorization (analysis)

  Impl() {
    single_threaded_blas();
    cholmod_start(&common);
    common.print = 0;  // the library never prints
    common.error_handler = nullptr;
    // Always LL' (supernodal): a simplicial LDL' would accept indefinite matrices silently.
    common.supernodal = CHOLMOD_SUPERNODAL;
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

SparseSpdSolver::SparseSpdSolver() : impl_(std::make_unique<Impl>()) {}
SparseSpdSolver::~SparseSpdSolver() = default;
SparseSpdSolver::SparseSpdSolver(SparseSpdSolver&&) noexcept = default;
SparseSpdSolver& SparseSpdSolver::operator=(SparseSpdSolver&&) noexcept = default;

void SparseSpdSolver::analyze(const Eigen::SparseMatrix<double>& A) {
  if (A.rows() != A.cols()) throw core::SolverError("sparse solver: matrix is not square");
  Impl& m = *impl_;
  if (m.factor) cholmod_free_factor(&m.factor, &m.common);
  m.ok = false;
  m.n = static_cast<int>(A.rows());
  cholmod_sparse s = view(A);
  m.factor = cholmod_analyze(&s, &m.common);
  if (!m.factor || m.common.status < CHOLMOD_OK)
    throw core::SolverError("sparse solver: CHOLMOD analysis failed: " + status_text(m.common.status));
  m.lnz = m.common.lnz;
  m.flops = m.common.fl;
  core::logger().debug("sparse solver: n {}, nnz(A) {}, nnz(L) {:.0f}, flops {:.3g}, ordering {}", m.n, A.nonZeros(),
                       m.common.lnz, m.common.fl, m.common.selected >= 0 ? m.common.method[m.common.selected].ordering : -1);
}

bool SparseSpdSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  single_threaded_blas();  // this thread may not be the one that made the solver
  Impl& m = *impl_;
  if (!m.factor || m.n != A.rows()) analyze(A);
  cholmod_sparse s = view(A);
  m.ok = false;
  const int rc = cholmod_factorize(&s, m.factor, &m.common);
  if (m.common.status == CHOLMOD_NOT_POSDEF) return false;
  if (!rc || m.common.status < CHOLMOD_OK)
    throw core::SolverError("sparse solver: CHOLMOD factorization failed: " + status_text(m.common.status));
  m.ok = true;
  return true;
}

Eigen::MatrixXd SparseSpdSolver::solve(const Eigen::MatrixXd& b) const {
  const Impl& cm = *impl_;
  Impl& m = const_cast<Impl&>(cm);  // CHOLMOD's workspace lives in the common object
  if (!m.ok) throw core::SolverError("sparse solver: no valid factorization to solve with");
  if (b.rows() != m.n) throw core::SolverError("sparse solver: right-hand side has the wrong size");
  cholmod_dense rhs{};
  rhs.nrow = static_cast<size_t>(b.rows());
  rhs.ncol = static_cast<size_t>(b.cols());
  rhs.nzmax = rhs.nrow * rhs.ncol;
  rhs.d = rhs.nrow;
  rhs.x = const_cast<double*>(b.data());
  rhs.z = nullptr;
  rhs.xtype = CHOLMOD_REAL;
  rhs.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, m.factor, &rhs, &m.common);
  if (!x) throw core::SolverError("sparse solver: CHOLMOD solve failed: " + status_text(m.common.status));
  Eigen::MatrixXd out = Eigen::Map<const Eigen::MatrixXd>(static_cast<const double*>(x->x), b.rows(), b.cols());
  cholmod_free_dense(&x, &m.common);
  return out;
}

Eigen::VectorXd SparseSpdSolver::solve(const Eigen::VectorXd& b) const {
  Eigen::MatrixXd bm = b;
  return solve(bm).col(0);
}

int SparseSpdSolver::size() const { return impl_->n; }
double SparseSpdSolver::factorization_flops_per_solve() const {
  return impl_->lnz > 0 ? impl_->flops / (4.0 * impl_->lnz) : 0.0;
}
bool SparseSpdSolver::factorized() const { return impl_->ok; }

Eigen::VectorXd solve_spd(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b) {
  SparseSpdSolver solver;
  Eigen::SparseMatrix<double> a = A;
  a.makeCompressed();
  if (!solver.factorize(a)) throw core::SolverError("sparse solver: matrix is not positive definite");
  return solver.solve(b);
}

double add_tiny_diagonal(std::vector<Eigen::Triplet<double>>& triplets, int n) {
  double trace = 0;
  for (const auto& t : triplets)
    if (t.row() == t.col()) trace += t.value();
  const double reg = 1e-8 * trace / std::max(1, n);
  for (int j = 0; j < n; ++j) triplets.emplace_back(j, j, reg);
  return reg;
}

}  // namespace polycube::solve

//! CHOLMOD's OpenMP regions, run on the calling thread without libgomp. They already run on one
//! thread (single_threaded_blas() above), but libgomp still opens a team of one for each and ends
//! it with a futex wake: about 78,000 system calls in one `run` of B0 at 880 hexes, 5 % of its
//! time on a virtual machine, where a system call is dear. A region's body called once, outside
//! any team (omp_get_num_threads() is 1, omp_get_thread_num() 0), is what a team of one runs, so
//! the factors are the same bit for bit. This definition in the program takes the place of
//! libgomp's for every library: only libcholmod calls libgomp, and GOMP_parallel is the one entry
//! point it imports (checked with `nm -D`), for `parallel` and `parallel for` with static
//! schedules. Test: SparseSpdSolver.OpenMpRegionsRunInline.
extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned /*num_threads*/, unsigned /*flags*/) {
  fn(data);
}
