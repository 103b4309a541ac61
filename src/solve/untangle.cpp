//! Elliptic untangling engine (see untangle.h). Garanzha et al. 2021, with Newton steps on a
//! per-element projected Hessian instead of the paper's L-BFGS.
#include "solve/untangle.h"

#include "core/stopwatch.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/progress.h"
#include "solve/sparse_solver.h"
#include "solve/svd3.h"

#include <Eigen/Geometry>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/LU>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

namespace polycube::solve {

double chi(double det, double epsilon) {
  const double s = std::sqrt(epsilon * epsilon + det * det);
  if (det > 0) return 0.5 * (det + s);
  return 0.5 * epsilon * epsilon / (s - det);  // same value, no cancellation for det < 0
}

namespace {

using Mat3 = Eigen::Matrix3d;
using Mat9 = Eigen::Matrix<double, 9, 9>;
using Vec9 = Eigen::Matrix<double, 9, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Grad = Eigen::Matrix<double, 4, 3>;

//! E(v)_ij = sum_k eps_ijk v_k: the block d²(r_a . (r_b x r_c))/dr_a dr_b for (a,b,c) cyclic.
Mat3 levi(const Eigen::Vector3d& v) {
  Mat3 m;
  m << 0, v.z(), -v.y(), -v.z(), 0, v.x(), v.y(), -v.x(), 0;
  return m;
}

//! Cofactor matrix K = d det / dJ (rows r1 x r2, r2 x r0, r0 x r1).
Mat3 cofactor(const Mat3& J) {
  Mat3 K;
  K.row(0) = J.row(1).cross(J.row(2));
  K.row(1) = J.row(2).cross(J.row(0));
  K.row(2) = J.row(0).cross(J.row(1));
  return K;
}

Vec9 vec(const Mat3& m) {
  Vec9 v;
  for (int d = 0; d < 3; ++d)
    for (int k = 0; k < 3; ++k) v[3 * d + k] = m(d, k);
  return v;
}

//! Value only (fast path for line searches), from |J|² and det J.
double energy_value(double squared_norm, double det, double eps, double lambda) {
  const double c = chi(det, eps);
  return squared_norm / 3.0 / std::cbrt(c * c) + lambda * (det * det + 1.0) / c;
}

//! Whether G is the gradient of a right-angled corner along the axes (rows 1–3 diagonal, a_k,
//! and row 0 = −a): the hex optimizer's elements, whose products with G are scalings.
bool corner_frame(const Grad& G) {
  return G(0, 0) == -G(1, 0) && G(0, 1) == -G(2, 1) && G(0, 2) == -G(3, 2) && G(1, 1) == 0 && G(1, 2) == 0 &&
         G(2, 0) == 0 && G(2, 2) == 0 && G(3, 0) == 0 && G(3, 1) == 0;
}

Mat3 jacobian(const Grad& G, const Eigen::VectorXd& x, const std::array<int, 4>& tet) {
  if (corner_frame(G)) {  // J's column k: a_k (x_{k+1} − x_0)
    const Eigen::Vector3d p0 = x.segment<3>(3 * tet[0]);
    Mat3 J;
    for (int k = 0; k < 3; ++k) J.col(k) = G(k + 1, k) * (x.segment<3>(3 * tet[k + 1]) - p0);
    return J;
  }
  Mat3 J = Mat3::Zero();
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d p = x.segment<3>(3 * tet[i]);
    J += p * G.row(i);
  }
  return J;
}

//! Solve A x = -g by conjugate gradients preconditioned with an earlier factorization of a
//! matrix close to A (the Newton systems of successive steps differ mostly near the elements
//! that move most). True when the relative residual fell to tol within max_it iterations.
bool stale_factor_cg(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& g, const SparseSpdSolver& M,
                     int max_it, double tol, Eigen::VectorXd& x, int& its) {
  const Eigen::VectorXd b = -g;
  const double bn = b.norm();
  x = Eigen::VectorXd::Zero(b.size());
  if (!(bn > 0)) return true;
  Eigen::VectorXd r = b;
  Eigen::VectorXd z = M.solve(r);
  Eigen::VectorXd p = z;
  double rz = r.dot(z);
  Eigen::VectorXd Ap(b.size());
  for (its = 1; its <= max_it; ++its) {
    Ap.noalias() = A.selfadjointView<Eigen::Upper>() * p;
    const double pAp = p.dot(Ap);
    if (!(pAp > 0)) return false;
    const double alpha = rz / pAp;
    x += alpha * p;
    r -= alpha * Ap;
    if (r.norm() <= tol * bn) return true;
    z = M.solve(r);
    const double rz_next = r.dot(z);
    p = z + (rz_next / rz) * p;
    rz = rz_next;
  }
  its = max_it;
  return false;
}

}  // namespace

// Outside the anonymous namespace: PatternCache (untangle.h) holds an Assembly.
namespace detail {

//! One reduction entry: local coordinate `local` of a term equals coef * y[col] (+ const).
struct Entry {
  int local;
  int col;
  double coef;
};

//! Terms (elements, attractions) gathered through the reduction, with Hessian slots.
struct Assembly {
  int n = 0;                          // #y
  Eigen::SparseMatrix<double> H;      // upper triangle pattern, CSC
  std::vector<int> diag_slot;         // #y
  // elements
  std::vector<int> elem_offset;       // #T+1 into entries
  std::vector<Entry> entries;
  // An element with more entries than its 12 local coordinates has derived points (a coordinate
  // that combines several variables, e.g. a hex's face centroid): its Hessian is first reduced
  // to its distinct columns (dense, in the parallel phase), so its slots are the upper pairs of
  // those columns instead of every pair of entries (a hex's centre tet: 300 instead of 2,600).
  std::vector<int> elem_cols_offset;  // #T+1 into elem_cols (empty range: not reduced)
  std::vector<int> elem_cols;         // a reduced element's distinct columns, ascending
  std::vector<int> entry_col;         // #entries: a reduced element's entry's index in its columns
  std::vector<int> elem_slot_offset;  // #T+1 into slots
  std::vector<int> slots;
  std::vector<int> elem_grad_offset;  // #T+1: an element's gradient values (entries, or columns if reduced)
  // attractions (3 local coordinates each)
  std::vector<int> attr_offset;
  std::vector<Entry> attr_entries;
  std::vector<int> attr_slot_offset;
  std::vector<int> attr_slots;
};

void gather(const LinearReduction& R, const int* verts, int nv, std::vector<Entry>& out) {
  for (int i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d) {
      const int row = 3 * verts[i] + d;
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(R.B, row); it; ++it)
        if (it.value() != 0.0) out.push_back({3 * i + d, static_cast<int>(it.col()), it.value()});
    }
}

Assembly build_assembly(const TetElements& el, const LinearReduction& R,
                        const std::vector<Attraction>& attractions) {
  Assembly a;
  a.n = R.num_variables();
  a.elem_offset.reserve(el.tets.size() + 1);
  a.entries.reserve(12 * el.tets.size());  // exact for an index reduction
  a.elem_offset.push_back(0);
  for (const auto& t : el.tets) {
    gather(R, t.data(), 4, a.entries);
    a.elem_offset.push_back(static_cast<int>(a.entries.size()));
  }
  a.attr_offset.push_back(0);
  for (const Attraction& at : attractions) {
    gather(R, &at.vertex, 1, a.attr_entries);
    a.attr_offset.push_back(static_cast<int>(a.attr_entries.size()));
  }
  // Pattern: upper-triangle pairs of every term plus the whole diagonal, built column by column
  // from each term's distinct columns (a triplet list would hold every pair of every term,
  // duplicates included: hundreds of MB on a 50k-hex mesh).
  const auto terms = static_cast<int>(el.tets.size() + attractions.size());
  auto term_entries = [&](int t) -> std::pair<const Entry*, const Entry*> {
    if (t < static_cast<int>(el.tets.size())) return {a.entries.data() + a.elem_offset[t], a.entries.data() + a.elem_offset[t + 1]};
    const int k = t - static_cast<int>(el.tets.size());
    return {a.attr_entries.data() + a.attr_offset[k], a.attr_entries.data() + a.attr_offset[k + 1]};
  };
  std::vector<int> cols_offset(static_cast<std::size_t>(terms) + 1, 0);
  std::vector<int> cols;
  cols.reserve(a.entries.size() + a.attr_entries.size());
  for (int t = 0; t < terms; ++t) {
    const auto [b, e] = term_entries(t);
    const std::size_t first = cols.size();
    for (const Entry* it = b; it != e; ++it) cols.push_back(it->col);
    std::sort(cols.begin() + static_cast<std::ptrdiff_t>(first), cols.end());
    cols.erase(std::unique(cols.begin() + static_cast<std::ptrdiff_t>(first), cols.end()), cols.end());
    cols_offset[static_cast<std::size_t>(t) + 1] = static_cast<int>(cols.size());
  }
  std::vector<int> col_terms_offset(static_cast<std::size_t>(a.n) + 1, 0);
  for (int c : cols) ++col_terms_offset[static_cast<std::size_t>(c) + 1];
  for (int j = 0; j < a.n; ++j) col_terms_offset[j + 1] += col_terms_offset[j];
  std::vector<int> col_terms(cols.size());
  {
    std::vector<int> fill(col_terms_offset.begin(), col_terms_offset.end() - 1);
    for (int t = 0; t < terms; ++t)
      for (int p = cols_offset[t]; p < cols_offset[t + 1]; ++p) col_terms[fill[cols[p]]++] = t;
  }
  std::vector<int> outer(static_cast<std::size_t>(a.n) + 1, 0);
  std::vector<int> inner;
  {
    std::vector<int> mark(static_cast<std::size_t>(a.n), -1);
    for (int j = 0; j < a.n; ++j) {
      const std::size_t first = inner.size();
      inner.push_back(j);  // the diagonal, always
      mark[j] = j;
      for (int k = col_terms_offset[j]; k < col_terms_offset[j + 1]; ++k) {
        const int t = col_terms[k];
        for (int p = cols_offset[t]; p < cols_offset[t + 1] && cols[p] < j; ++p)
          if (mark[cols[p]] != j) {
            mark[cols[p]] = j;
            inner.push_back(cols[p]);
          }
      }
      std::sort(inner.begin() + static_cast<std::ptrdiff_t>(first), inner.end());
      outer[j + 1] = static_cast<int>(inner.size());
    }
  }
  const std::vector<double> zeros(inner.size(), 0.0);
  a.H = Eigen::Map<const Eigen::SparseMatrix<double>>(a.n, a.n, static_cast<Eigen::Index>(inner.size()),
                                                      outer.data(), inner.data(), zeros.data());
  a.H.makeCompressed();
  const int* outer_ptr = a.H.outerIndexPtr();
  const int* inner_ptr = a.H.innerIndexPtr();
  auto slot_of = [&](int r, int c) {
    const int* b = inner_ptr + outer_ptr[c];
    const int* e = inner_ptr + outer_ptr[c + 1];
    const int* it = std::lower_bound(b, e, r);
    PC_REQUIRE(it != e && *it == r, "untangle: missing Hessian slot");
    return static_cast<int>(it - inner_ptr);
  };
  // The reduced elements (see Assembly): their distinct columns, and each entry's among them.
  const auto T = static_cast<int>(el.tets.size());
  a.elem_cols_offset.assign(static_cast<std::size_t>(T) + 1, 0);
  a.entry_col.assign(a.entries.size(), -1);
  a.elem_grad_offset.assign(static_cast<std::size_t>(T) + 1, 0);
  for (int t = 0; t < T; ++t) {
    const int n_entries = a.elem_offset[t + 1] - a.elem_offset[t];
    const bool reduced = n_entries > 12;
    if (reduced) {
      const auto first = cols.begin() + cols_offset[t], last = cols.begin() + cols_offset[t + 1];
      a.elem_cols.insert(a.elem_cols.end(), first, last);
      for (int p = a.elem_offset[t]; p < a.elem_offset[t + 1]; ++p)
        a.entry_col[p] = static_cast<int>(std::lower_bound(first, last, a.entries[p].col) - first);
    }
    a.elem_cols_offset[t + 1] = static_cast<int>(a.elem_cols.size());
    a.elem_grad_offset[t + 1] = a.elem_grad_offset[t] + (reduced ? cols_offset[t + 1] - cols_offset[t] : n_entries);
  }
  // Slots of every term's upper pairs (counted first, then filled in parallel).
  auto make_slots = [&](const std::vector<Entry>& e, const std::vector<int>& off, std::vector<int>& so,
                        std::vector<int>& slots, const std::vector<int>* reduced_offset) {
    const std::size_t count = off.size() - 1;
    auto reduced_columns = [&](std::size_t t) {
      return reduced_offset ? (*reduced_offset)[t + 1] - (*reduced_offset)[t] : 0;
    };
    so.assign(count + 1, 0);
    for (std::size_t t = 0; t < count; ++t) {
      int pairs = 0;
      if (const int nc = reduced_columns(t); nc > 0) {
        pairs = nc * (nc + 1) / 2;
      } else {
        for (int p = off[t]; p < off[t + 1]; ++p)
          for (int q = off[t]; q < off[t + 1]; ++q) pairs += e[p].col <= e[q].col;
      }
      so[t + 1] = so[t] + pairs;
    }
    slots.resize(static_cast<std::size_t>(so[count]));
    tbb::parallel_for(std::size_t{0}, count, [&](std::size_t t) {
      if (const int nc = reduced_columns(t); nc > 0) {  // upper pairs (i ≤ j) of the columns, row by row
        const int* c = a.elem_cols.data() + (*reduced_offset)[t];
        int s = so[t];
        for (int i = 0; i < nc; ++i)
          for (int j = i; j < nc; ++j) slots[s++] = slot_of(c[i], c[j]);
        return;
      }
      // A vertex's coordinates are consecutive entries and, when free, consecutive rows of each
      // column, so the slot below the last one found in a column is usually the next row's:
      // checked, and searched for only where it is not.
      thread_local std::vector<int> last_row, last_slot;
      const int n_entries = off[t + 1] - off[t];
      last_row.assign(static_cast<std::size_t>(n_entries), -2);
      last_slot.resize(static_cast<std::size_t>(n_entries));
      int s = so[t];
      for (int p = off[t]; p < off[t + 1]; ++p)
        for (int q = off[t]; q < off[t + 1]; ++q) {
          const int r = e[p].col, c = e[q].col;
          if (r > c) continue;
          const std::size_t k = static_cast<std::size_t>(q - off[t]);
          const int next = last_slot[k] + 1;
          const bool below = r == last_row[k] + 1 && next < outer_ptr[c + 1] && inner_ptr[next] == r;
          last_slot[k] = below ? next : slot_of(r, c);
          last_row[k] = r;
          slots[s++] = last_slot[k];
        }
    });
  };
  make_slots(a.entries, a.elem_offset, a.elem_slot_offset, a.slots, &a.elem_cols_offset);
  make_slots(a.attr_entries, a.attr_offset, a.attr_slot_offset, a.attr_slots, nullptr);
  a.diag_slot.resize(a.n);
  for (int j = 0; j < a.n; ++j) a.diag_slot[j] = slot_of(j, j);
  return a;
}

}  // namespace detail

//! The pattern of the last call, and what it was built from (UntangleOptions::pattern_cache).
struct PatternCache {
  std::vector<std::array<int, 4>> tets;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B;
  std::vector<int> attracted;
  detail::Assembly assembly;
  bool built = false;
};

std::shared_ptr<PatternCache> make_pattern_cache() { return std::make_shared<PatternCache>(); }

namespace {

using detail::Assembly;
using detail::Entry;

//! One element's values for the assembly: its Hessian slot by slot (A.slots' order) and its
//! gradient by entry, or, for a reduced element, Wᵀ H W and Wᵀ g with W the 12 × #columns map of
//! its entries (each column's sums formed here, in the parallel phase).
void element_values(const Assembly& A, int t, const Vec12& ge, const Mat12& He, double* hv, double* gv) {
  const Entry* e = A.entries.data() + A.elem_offset[t];
  const int ne = A.elem_offset[t + 1] - A.elem_offset[t];
  const int nc = A.elem_cols_offset[t + 1] - A.elem_cols_offset[t];
  if (nc == 0) {
    for (int p = 0; p < ne; ++p) {
      gv[p] = e[p].coef * ge[e[p].local];
      for (int q = 0; q < ne; ++q)
        if (e[p].col <= e[q].col) *hv++ = e[p].coef * e[q].coef * He(e[p].local, e[q].local);
    }
    return;
  }
  const int* col = A.entry_col.data() + A.elem_offset[t];
  thread_local std::vector<double> HW;  // H W (12 × nc)
  HW.assign(static_cast<std::size_t>(12 * nc), 0.0);
  for (int q = 0; q < ne; ++q)
    for (int l = 0; l < 12; ++l) HW[l * nc + col[q]] += e[q].coef * He(l, e[q].local);
  // Wᵀ H W's upper triangle straight into the slot values (row i's pairs start at
  // i·nc − i(i−1)/2, in A.slots' order).
  std::fill(hv, hv + nc * (nc + 1) / 2, 0.0);
  std::fill(gv, gv + nc, 0.0);
  for (int p = 0; p < ne; ++p) {
    const int i = col[p];
    const double* hw = HW.data() + e[p].local * nc;
    double* r = hv + i * nc - i * (i - 1) / 2 - i;  // r[j] is pair (i, j)
    for (int j = i; j < nc; ++j) r[j] += e[p].coef * hw[j];
    gv[i] += e[p].coef * ge[e[p].local];
  }
}

//! Same sparse matrix, entry for entry (structure and values).
bool same_matrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& a,
                 const Eigen::SparseMatrix<double, Eigen::RowMajor>& b) {
  if (!a.isCompressed() || !b.isCompressed()) return false;  // raw arrays compare only then
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.nonZeros() != b.nonZeros()) return false;
  const auto rows = static_cast<std::size_t>(a.rows()) + 1;
  const auto nnz = static_cast<std::size_t>(a.nonZeros());
  return std::equal(a.outerIndexPtr(), a.outerIndexPtr() + rows, b.outerIndexPtr()) &&
         std::equal(a.innerIndexPtr(), a.innerIndexPtr() + nnz, b.innerIndexPtr()) &&
         std::equal(a.valuePtr(), a.valuePtr() + nnz, b.valuePtr());
}

//! The pattern for these elements, reduction and attractions: the cache's when it was built
//! from the same ones (the assembly depends on nothing else), else built (and kept there).
const Assembly& pattern_for(const TetElements& el, const LinearReduction& R, const std::vector<Attraction>& attr,
                            PatternCache* cache, Assembly& own) {
  std::vector<int> attracted(attr.size());
  for (std::size_t k = 0; k < attr.size(); ++k) attracted[k] = attr[k].vertex;
  if (cache && cache->built && cache->tets == el.tets && cache->attracted == attracted && same_matrix(cache->B, R.B)) {
    core::logger().debug("untangle: the pattern of the previous call");
    return cache->assembly;
  }
  Assembly a = detail::build_assembly(el, R, attr);
  if (!cache) {
    own = std::move(a);
    return own;
  }
  cache->tets = el.tets;
  cache->B = R.B;
  cache->attracted = std::move(attracted);
  cache->assembly = std::move(a);
  cache->built = true;
  return cache->assembly;
}

struct Stats {
  double energy = 0;
  double min_det = std::numeric_limits<double>::infinity();
  int inverted = 0;
};

//! Each element's |J|² and det J at some x: all the energy depends on, so a change of ε alone
//! needs no Jacobian again.
using Invariants = std::vector<std::array<double, 2>>;

//! Energy, min det and #inverted at x (parallel over elements, deterministic reduction order
//! within fixed blocks). With `known`, the elements' invariants at x are taken from there;
//! else they are computed, and kept in `keep` when given.
Stats evaluate(const TetElements& el, const std::vector<Attraction>& attr, const Eigen::VectorXd& x, double eps,
               double lambda, double det_target, Invariants* keep = nullptr, const Invariants* known = nullptr) {
  const int T = el.size();
  if (keep) keep->resize(static_cast<std::size_t>(T));
  constexpr int kBlock = 2048;
  const int nb = (T + kBlock - 1) / kBlock;
  std::vector<Stats> part(static_cast<std::size_t>(nb));
  tbb::parallel_for(0, nb, [&](int b) {
    Stats s;
    const int e = std::min(T, (b + 1) * kBlock);
    for (int t = b * kBlock; t < e; ++t) {
      std::array<double, 2> inv;
      if (known) {
        inv = (*known)[t];
      } else {
        const Mat3 J = jacobian(el.gradients[t], x, el.tets[t]);
        inv = {J.squaredNorm(), J.determinant()};
        if (keep) (*keep)[t] = inv;
      }
      const double det = inv[1];
      s.min_det = std::min(s.min_det, det);
      s.inverted += det <= det_target;
      s.energy += el.weights[t] * energy_value(inv[0], det, eps, lambda);
    }
    part[static_cast<std::size_t>(b)] = s;
  });
  Stats total;
  for (const Stats& s : part) {
    total.energy += s.energy;
    total.min_det = std::min(total.min_det, s.min_det);
    total.inverted += s.inverted;
  }
  for (const Attraction& a : attr)
    total.energy += a.weight * (x.segment<3>(3 * a.vertex) - a.target).cwiseAbs2().dot(a.axis_weights);
  return total;
}

//! The elliptic energy depends on J only through |J|² and det J, so its Hessian in vec(J) is
//! c0·I + c1·(j kᵀ + k jᵀ) + c2·k kᵀ + c3·∇²det, with j = vec J and k = vec cof J.
struct EnergyTerms {
  double value = 0;
  double c0 = 0, c1 = 0, c2 = 0, c3 = 0;
};

EnergyTerms energy_terms(const Mat3& J, double eps, double lambda) {
  const double D = J.determinant();
  const double s = std::sqrt(eps * eps + D * D);
  const double c = chi(D, eps);
  const double c1 = c / s;                          // dχ/dD
  const double c2 = 0.5 * eps * eps / (s * s * s);  // d²χ/dD²
  // shape term a(J) g(D): a = |J|²/3, g = χ^(-2/3)
  const double a = J.squaredNorm() / 3.0;
  const double g = 1.0 / std::cbrt(c * c);
  const double g1 = -2.0 / 3.0 * g / c * c1;
  const double g2 = 10.0 / 9.0 * g / (c * c) * c1 * c1 - 2.0 / 3.0 * g / c * c2;
  // volume term h(D) = (D²+1)/χ
  const double q = D * D + 1.0;
  const double h = q / c;
  const double h1 = 2.0 * D / c - q * c1 / (c * c);
  const double h2 = 2.0 / c - 4.0 * D * c1 / (c * c) - q * c2 / (c * c) + 2.0 * q * c1 * c1 / (c * c * c);
  return {a * g + lambda * h, (2.0 / 3.0) * g, (2.0 / 3.0) * g1, a * g2 + lambda * h2, a * g1 + lambda * h1};
}

ElementEnergy energy_derivatives(const Mat3& J, const EnergyTerms& t) {
  const Mat3 K = cofactor(J);
  const Vec9 j = vec(J);
  const Vec9 k = vec(K);
  // Hessian of det: blocks (a,b) for (a,b,c) cyclic are levi(r_c), transposes below.
  Mat9 HD = Mat9::Zero();
  const Eigen::Vector3d r0 = J.row(0).transpose(), r1 = J.row(1).transpose(), r2 = J.row(2).transpose();
  HD.block<3, 3>(0, 3) = levi(r2);
  HD.block<3, 3>(3, 6) = levi(r0);
  HD.block<3, 3>(6, 0) = levi(r1);
  HD.block<3, 3>(3, 0) = HD.block<3, 3>(0, 3).transpose();
  HD.block<3, 3>(6, 3) = HD.block<3, 3>(3, 6).transpose();
  HD.block<3, 3>(0, 6) = HD.block<3, 3>(6, 0).transpose();
  ElementEnergy out;
  out.value = t.value;
  out.gradient = t.c0 * j + t.c3 * k;
  out.hessian =
      t.c0 * Mat9::Identity() + t.c1 * (j * k.transpose() + k * j.transpose()) + t.c2 * (k * k.transpose()) + t.c3 * HD;
  return out;
}

//! PSD projection of the Hessian H of the energy at J from its analytic eigensystem (Smith et al.
//! 2019, "Analytic eigensystems for isotropic distortion energies"), instead of a 9 × 9 numeric
//! eigensolver: the energy is invariant under rotations on either side, so in J's signed singular
//! frame J = U diag(s) Vᵀ (U, V rotations, s₂ carrying det's sign) the Hessian splits into one
//! 3 × 3 block on the scalings u_a v_aᵀ and three 2 × 2 blocks on the pairs u_a v_bᵀ, u_b v_aᵀ,
//! whose eigenvalues are c0 ∓ c3·s_z (z the third index).
//! `frame`, when given, is the V of the element's last projection: the start of this one's SVD,
//! and updated.
Mat9 project_psd(const Mat3& J, const Mat9& H, const EnergyTerms& t, Mat3* frame = nullptr) {
  if (Eigen::LLT<Mat9>(H).info() == Eigen::Success) return H;  // already PD: nothing to project
  Mat3 U, V;
  Eigen::Vector3d s;
  signed_svd3(J, U, s, V, frame);
  if (frame) *frame = V;
  const Eigen::Vector3d k(s[1] * s[2], s[0] * s[2], s[0] * s[1]);
  Mat3 A = t.c0 * Mat3::Identity() + t.c1 * (s * k.transpose() + k * s.transpose()) + t.c2 * (k * k.transpose());
  for (int z = 0; z < 3; ++z) {
    const int a = (z + 1) % 3, b = (z + 2) % 3;
    A(a, b) += t.c3 * s[z];
    A(b, a) += t.c3 * s[z];
  }
  // H is the sum of λ q qᵀ over its 9 eigenpairs: subtracting the negative ones' terms (one to
  // three, usually) projects it at a fraction of the cost of summing the positive ones.
  // The eigenvectors are formed only for the negative eigenvalues (most of the nine are not).
  Mat9 P = H;
  auto clamp = [&](double eigenvalue, const Mat3& Q) {
    const Vec9 q = vec(Q);
    P.noalias() -= eigenvalue * (q * q.transpose());
  };
  // The scaling block is usually positive definite (the negative modes are twists and flips):
  // its eigensystem is needed only where its Cholesky factorization fails.
  if (Eigen::LLT<Mat3>(A).info() != Eigen::Success) {
    Eigen::SelfAdjointEigenSolver<Mat3> scaling;
    scaling.computeDirect(A);
    // The closed form's eigenvectors lose their accuracy where two eigenvalues (nearly)
    // coincide, as for a scaled rotation, whose singular values are equal: there the iterative
    // solver.
    const Eigen::Vector3d& ev = scaling.eigenvalues();  // increasing
    if (std::min(ev[1] - ev[0], ev[2] - ev[1]) <= 1e-6 * ev.cwiseAbs().maxCoeff()) scaling.compute(A);
    for (int i = 0; i < 3; ++i)
      if (scaling.eigenvalues()[i] < 0)
        clamp(scaling.eigenvalues()[i], U * scaling.eigenvectors().col(i).asDiagonal() * V.transpose());
  }
  for (int z = 0; z < 3; ++z) {
    const double flip = t.c0 - t.c3 * s[z], twist = t.c0 + t.c3 * s[z];
    if (!(flip < 0) && !(twist < 0)) continue;
    const int a = (z + 1) % 3, b = (z + 2) % 3;
    const Mat3 ab = U.col(a) * V.col(b).transpose() * (std::numbers::sqrt2 / 2);
    const Mat3 ba = U.col(b) * V.col(a).transpose() * (std::numbers::sqrt2 / 2);
    if (flip < 0) clamp(flip, ab + ba);
    if (twist < 0) clamp(twist, ab - ba);
  }
  return P;
}

//! element_derivatives' products with G for a corner frame (corner_frame): with S = diag(a) M
//! diag(a) for each 3 × 3 block M of HJ, the 4 × 4 block G M Gᵀ is [ΣS, −column sums; −row sums, S].
void corner_derivatives(const Eigen::Vector3d& a, const Vec9& gradient, const Mat9& HJ, double w, Vec12& g, Mat12& H) {
  for (int d = 0; d < 3; ++d) {
    const Eigen::Vector3d v = a.cwiseProduct(gradient.segment<3>(3 * d));
    g[d] = -w * v.sum();
    for (int k = 0; k < 3; ++k) g[3 * (k + 1) + d] = w * v[k];
  }
  for (int d = 0; d < 3; ++d)
    for (int f = 0; f < 3; ++f) {
      const Mat3 S = w * (a.asDiagonal() * HJ.block<3, 3>(3 * d, 3 * f) * a.asDiagonal());
      const Eigen::Vector3d rows = S.rowwise().sum(), cols = S.colwise().sum().transpose();
      H(d, f) = rows.sum();
      for (int k = 0; k < 3; ++k) {
        H(3 * (k + 1) + d, f) = -rows[k];
        H(d, 3 * (k + 1) + f) = -cols[k];
        for (int l = 0; l < 3; ++l) H(3 * (k + 1) + d, 3 * (l + 1) + f) = S(k, l);
      }
    }
}

//! Local gradient and projected Hessian in the 12 coordinates of one element.
void element_derivatives(const Grad& G, const Mat3& J, double w, double eps, double lambda, Vec12& g, Mat12& H,
                         Mat3* frame = nullptr) {
  const EnergyTerms terms = energy_terms(J, eps, lambda);
  const ElementEnergy e = energy_derivatives(J, terms);
  const Mat9 HJ = project_psd(J, e.hessian, terms, frame);
  if (corner_frame(G)) {
    corner_derivatives(Eigen::Vector3d(G(1, 0), G(2, 1), G(3, 2)), e.gradient, HJ, w, g, H);
    return;
  }
  for (int d = 0; d < 3; ++d) {
    const Eigen::Vector4d gd = G * e.gradient.segment<3>(3 * d);
    for (int i = 0; i < 4; ++i) g[3 * i + d] = w * gd[i];
  }
  for (int d = 0; d < 3; ++d)
    for (int f = 0; f < 3; ++f) {
      const Eigen::Matrix4d blk = G * HJ.block<3, 3>(3 * d, 3 * f) * G.transpose();
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) H(3 * i + d, 3 * j + f) = w * blk(i, j);
    }
}

//! The Newton system's gradient and projected Hessian in y, term by term into the pattern of A.
class NewtonAssembler {
 public:
  NewtonAssembler(const TetElements& el, const Assembly& A)
      : el_(el), A_(A), frames_(static_cast<std::size_t>(el.size()), Mat3::Identity()) {
    for (int b0 = 0; b0 < el_.size(); b0 += kBlock) {
      const int b1 = std::min(el_.size(), b0 + kBlock);
      block_slots_ = std::max(block_slots_, A_.elem_slot_offset[b1] - A_.elem_slot_offset[b0]);
      block_grads_ = std::max(block_grads_, A_.elem_grad_offset[b1] - A_.elem_grad_offset[b0]);
    }
    for (int buf = 0; buf < 2; ++buf) {
      hl_[buf].resize(static_cast<std::size_t>(block_slots_));
      gl_[buf].resize(static_cast<std::size_t>(block_grads_));
    }
  }

  //! H (A's pattern) and g at x: the elements, then the attractions.
  void assemble(const Eigen::VectorXd& x, double eps, double lambda, const std::vector<Attraction>& attractions,
                Eigen::SparseMatrix<double>& H, Eigen::VectorXd& g) {
    double* hv = H.valuePtr();
    std::fill(hv, hv + H.nonZeros(), 0.0);
    g.setZero();
    add_elements(x, eps, lambda, hv, g);
    add_attractions(x, attractions, hv, g);
  }

 private:
  static constexpr int kBlock = 1024;

  //! Elements in blocks: the values of a block in parallel, then added into H and g in element
  //! order (the same sums whatever the thread count). The adding is serial, so the next block's
  //! values are computed meanwhile, in the other buffer.
  void add_elements(const Eigen::VectorXd& x, double eps, double lambda, double* hv, Eigen::VectorXd& g) {
    const int T = el_.size();
    if (T > 0) values(x, eps, lambda, 0, 0);
    for (int b0 = 0, buf = 0; b0 < T; b0 += kBlock, buf ^= 1) {
      tbb::task_group next;
      if (b0 + kBlock < T) next.run([&, b0, buf] { values(x, eps, lambda, b0 + kBlock, buf ^ 1); });
      add(b0, buf, hv, g);
      next.wait();
    }
  }

  //! The values of the elements of block b0 into buffer buf (element_values), in parallel.
  void values(const Eigen::VectorXd& x, double eps, double lambda, int b0, int buf) {
    const int b1 = std::min(el_.size(), b0 + kBlock);
    tbb::parallel_for(tbb::blocked_range<int>(b0, b1, 64), [&](const tbb::blocked_range<int>& r) {
      Vec12 ge;
      Mat12 He;
      for (int t = r.begin(); t < r.end(); ++t) {
        const Mat3 J = jacobian(el_.gradients[t], x, el_.tets[t]);
        element_derivatives(el_.gradients[t], J, el_.weights[t], eps, lambda, ge, He, &frames_[t]);
        element_values(A_, t, ge, He, hl_[buf].data() + (A_.elem_slot_offset[t] - A_.elem_slot_offset[b0]),
                       gl_[buf].data() + (A_.elem_grad_offset[t] - A_.elem_grad_offset[b0]));
      }
    });
  }

  //! Block b0's values from buffer buf into H and g, in element order.
  void add(int b0, int buf, double* hv, Eigen::VectorXd& g) const {
    const int b1 = std::min(el_.size(), b0 + kBlock);
    const double* gv = gl_[buf].data();
    for (int t = b0; t < b1; ++t) {
      if (A_.elem_cols_offset[t + 1] > A_.elem_cols_offset[t]) {
        for (int c = A_.elem_cols_offset[t]; c < A_.elem_cols_offset[t + 1]; ++c) g[A_.elem_cols[c]] += *gv++;
      } else {
        for (int p = A_.elem_offset[t]; p < A_.elem_offset[t + 1]; ++p) g[A_.entries[p].col] += *gv++;
      }
    }
    const double* v = hl_[buf].data();
    for (int s = A_.elem_slot_offset[b0]; s < A_.elem_slot_offset[b1]; ++s) hv[A_.slots[s]] += *v++;
  }

  void add_attractions(const Eigen::VectorXd& x, const std::vector<Attraction>& attractions, double* hv,
                       Eigen::VectorXd& g) const {
    for (std::size_t k = 0; k < attractions.size(); ++k) {
      const Attraction& at = attractions[k];
      const Eigen::Vector3d ga = 2.0 * at.weight * (x.segment<3>(3 * at.vertex) - at.target).cwiseProduct(at.axis_weights);
      int s = A_.attr_slot_offset[k];
      for (int p = A_.attr_offset[k]; p < A_.attr_offset[k + 1]; ++p) {
        const Entry& ep = A_.attr_entries[p];
        g[ep.col] += ep.coef * ga[ep.local];
        for (int q = A_.attr_offset[k]; q < A_.attr_offset[k + 1]; ++q) {
          const Entry& eq = A_.attr_entries[q];
          if (ep.col <= eq.col)
            hv[A_.attr_slots[s++]] += ep.local == eq.local ? 2.0 * at.weight * at.axis_weights[ep.local] * ep.coef * eq.coef : 0.0;
        }
      }
    }
  }

  const TetElements& el_;
  const Assembly& A_;
  int block_slots_ = 0, block_grads_ = 0;
  std::array<std::vector<double>, 2> hl_, gl_;  // a block's Hessian and gradient values
  // Each element's last singular frame V: J moves little between Newton steps, so its next SVD
  // starts there and needs fewer Jacobi rotations (bench/RESULTS.md).
  std::vector<Mat3> frames_;
};

}  // namespace

ElementEnergy elliptic_energy(const Eigen::Matrix3d& J, double eps, double lambda) {
  return energy_derivatives(J, energy_terms(J, eps, lambda));
}

Eigen::Matrix<double, 9, 9> projected_elliptic_hessian(const Eigen::Matrix3d& J, double eps, double lambda) {
  const EnergyTerms terms = energy_terms(J, eps, lambda);
  return project_psd(J, energy_derivatives(J, terms).hessian, terms);
}

TetElements reference_elements(const std::vector<core::Vec3>& points, const std::vector<std::array<int, 4>>& tets,
                               double scale) {
  TetElements el;
  el.tets = tets;
  el.gradients.resize(tets.size());
  el.weights.resize(tets.size());
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& c = tets[t];
    for (int i = 0; i < 4; ++i)
      if (c[i] < 0 || c[i] >= static_cast<int>(points.size()))
        throw core::GeometryError("reference tet " + std::to_string(t) + " has an out-of-range vertex");
    Mat3 S;
    S.col(0) = scale * (points[c[1]] - points[c[0]]);
    S.col(1) = scale * (points[c[2]] - points[c[0]]);
    S.col(2) = scale * (points[c[3]] - points[c[0]]);
    const double det = S.determinant();
    const double len = std::max({S.col(0).norm(), S.col(1).norm(), S.col(2).norm()});
    if (!(det > 1e-14 * len * len * len))
      throw core::GeometryError("reference tet " + std::to_string(t) + " is flat or negatively oriented");
    const Mat3 Si = S.inverse();
    Grad G;
    G.row(1) = Si.row(0);
    G.row(2) = Si.row(1);
    G.row(3) = Si.row(2);
    G.row(0) = -(Si.row(0) + Si.row(1) + Si.row(2));
    el.gradients[t] = G;
    el.weights[t] = det / 6.0;
  }
  return el;
}

LinearReduction index_reduction(const std::vector<int>& var, int num_variables, const Eigen::VectorXd& fixed_value) {
  PC_REQUIRE(static_cast<Eigen::Index>(var.size()) == fixed_value.size() && var.size() % 3 == 0,
             "index_reduction: sizes");
  LinearReduction r;
  const int rows = static_cast<int>(var.size());
  r.B.resize(rows, num_variables);
  r.B.reserve(Eigen::VectorXi::Constant(rows, 1));
  r.x0 = Eigen::VectorXd::Zero(rows);
  for (int i = 0; i < rows; ++i) {
    PC_REQUIRE(var[i] < num_variables, "index_reduction: variable out of range");
    if (var[i] >= 0) r.B.insert(i, var[i]) = 1.0;
    else r.x0[i] = fixed_value[i];
  }
  r.B.makeCompressed();
  return r;
}

LinearReduction identity_reduction(int num_points) {
  std::vector<int> var(static_cast<std::size_t>(3 * num_points));
  for (int i = 0; i < 3 * num_points; ++i) var[i] = i;
  return index_reduction(var, 3 * num_points, Eigen::VectorXd::Zero(3 * num_points));
}

LinearReduction with_derived_points(const LinearReduction& r, const std::vector<DerivedPoint>& points) {
  // The rows are written straight into the compressed arrays: the old rows copied, each new row
  // merged from its vertices' rows (the optimizer rebuilds these reductions every round, and a
  // triplet list of the whole matrix cost a sort and its memory each time).
  Eigen::SparseMatrix<double, Eigen::RowMajor> compressed;  // only for an uncompressed input
  if (!r.B.isCompressed()) {
    compressed = r.B;
    compressed.makeCompressed();
  }
  const Eigen::SparseMatrix<double, Eigen::RowMajor>& base = r.B.isCompressed() ? r.B : compressed;
  const auto rows = static_cast<Eigen::Index>(base.rows());
  const auto extra = static_cast<Eigen::Index>(3 * points.size());
  std::vector<int> outer(static_cast<std::size_t>(rows + extra) + 1);
  std::copy(base.outerIndexPtr(), base.outerIndexPtr() + rows + 1, outer.begin());
  std::vector<int> inner(base.innerIndexPtr(), base.innerIndexPtr() + base.nonZeros());
  std::vector<double> value(base.valuePtr(), base.valuePtr() + base.nonZeros());
  inner.reserve(inner.size() + 12 * points.size());
  value.reserve(value.size() + 12 * points.size());
  LinearReduction out;
  out.x0 = Eigen::VectorXd::Zero(rows + extra);
  out.x0.head(rows) = r.x0;
  std::vector<std::pair<int, double>> terms;  // one new row's (column, value), in vertex order
  for (std::size_t k = 0; k < points.size(); ++k)
    for (int d = 0; d < 3; ++d) {
      const Eigen::Index dst = rows + 3 * static_cast<Eigen::Index>(k) + d;
      out.x0[dst] = points[k].offset[d];
      terms.clear();
      for (int i = 0; i < 4; ++i) {
        if (points[k].vertex[i] < 0) continue;
        const double w = points[k].weight[i];
        const Eigen::Index src = 3 * static_cast<Eigen::Index>(points[k].vertex[i]) + d;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(base, src); it; ++it)
          terms.emplace_back(static_cast<int>(it.col()), w * it.value());
        out.x0[dst] += w * r.x0[src];
      }
      // A variable shared by several vertices: summed in vertex order, an exact zero kept.
      std::stable_sort(terms.begin(), terms.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (std::size_t t = 0; t < terms.size(); ++t) {
        if (t > 0 && terms[t].first == terms[t - 1].first) {
          value.back() += terms[t].second;
          continue;
        }
        inner.push_back(terms[t].first);
        value.push_back(terms[t].second);
      }
      outer[static_cast<std::size_t>(dst) + 1] = static_cast<int>(inner.size());
    }
  out.B = Eigen::Map<const Eigen::SparseMatrix<double, Eigen::RowMajor>>(
      rows + extra, base.cols(), static_cast<Eigen::Index>(inner.size()), outer.data(), inner.data(), value.data());
  return out;
}

Eigen::VectorXd flatten(const std::vector<core::Vec3>& points) {
  Eigen::VectorXd x(3 * static_cast<Eigen::Index>(points.size()));
  for (std::size_t v = 0; v < points.size(); ++v) x.segment<3>(3 * static_cast<Eigen::Index>(v)) = points[v];
  return x;
}

std::vector<core::Vec3> unflatten(const Eigen::VectorXd& x) {
  std::vector<core::Vec3> p(static_cast<std::size_t>(x.size() / 3));
  for (std::size_t v = 0; v < p.size(); ++v) p[v] = x.segment<3>(3 * static_cast<Eigen::Index>(v));
  return p;
}

UntangleResult untangle(const TetElements& el, const LinearReduction& R, Eigen::VectorXd& y,
                        const UntangleOptions& o) {
  const core::Stopwatch clock;
  PC_REQUIRE(el.gradients.size() == el.tets.size() && el.weights.size() == el.tets.size(),
             "untangle: element arrays differ in size");
  PC_REQUIRE(y.size() == R.num_variables() && R.x0.size() == R.B.rows() && R.B.rows() % 3 == 0,
             "untangle: reduction and variables differ in size");
  const int nv = R.num_points();
  for (const auto& t : el.tets)
    for (int v : t) PC_REQUIRE(v >= 0 && v < nv, "untangle: element vertex out of range");
  for (const Attraction& a : o.attractions) PC_REQUIRE(a.vertex >= 0 && a.vertex < nv, "untangle: attraction vertex");

  UntangleResult res;
  std::vector<Attraction> attractions = o.attractions;  // the hook may move their targets
  const double lambda = o.volume_weight;
  const double det_target = o.min_det_target;
  Eigen::VectorXd x = R.apply(y);
  double eps = std::max(o.initial_epsilon, o.min_epsilon);
  // The invariants at x (the last accepted point) and at the line search's trial.
  Invariants at_x, at_trial;
  Stats st = evaluate(el, attractions, x, eps, lambda, det_target, &at_x);
  res.inverted_before = st.inverted;
  res.min_det_before = st.min_det;
  if (el.size() == 0 || R.num_variables() == 0) {
    res.untangled = st.inverted == 0;
    res.inverted_after = st.inverted;
    res.min_det = st.min_det;
    res.energy = st.energy;
    res.epsilon = eps;
    return res;
  }
  // Already valid meshes need no large ε: start small so the barrier keeps them valid.
  if (st.inverted == 0) eps = std::max(o.min_epsilon, std::min(eps, 1e-3 * std::max(st.min_det, 0.0)));

  const core::Stopwatch pattern_clock;
  Assembly own;
  const Assembly& A = pattern_for(el, R, attractions, o.pattern_cache.get(), own);
  core::logger().debug("untangle: {} unknowns, {} Hessian entries, pattern {:.2f} s", A.n, A.H.nonZeros(),
                       pattern_clock.seconds());
  Eigen::SparseMatrix<double> H = A.H;
  SparseSpdSolver solver;
  if (o.linear_solver == NewtonSolver::Cholesky) solver.analyze(H);
  // The regularized copy that is factorized: H's pattern, so its arrays are allocated once per
  // call and only the values are copied before each factorization attempt.
  Eigen::SparseMatrix<double> Hr;
  if (o.linear_solver == NewtonSolver::Cholesky) Hr = H;
  const int n = A.n;
  // Steps whose Newton system is solved with the last factorization as a preconditioner: after
  // a miss (the systems changed too much), the next `backoff` steps factorize without trying.
  int stale_misses = 0, stale_its = 0, skip_stale = 0, backoff = 1;
  // Iterations that may be spent before factorizing anyway: at most about half a factorization's
  // time (measured: a solve with the factor and a product with H take the time of 1/16 of the
  // flop ratio), none when that is less than two (small or sparse factors are cheap to redo).
  int stale_budget = 0;
  if (o.linear_solver == NewtonSolver::Cholesky && o.stale_factor_iterations > 0) {
    stale_budget = std::min(o.stale_factor_iterations, static_cast<int>(solver.factorization_flops_per_solve() / 10.0));
    if (stale_budget < 2) stale_budget = 0;
  }
  double damping = 0.0;
  double t_assemble = 0, t_factor = 0, t_search = 0;
  // Best state seen (fewest inverted elements, then lowest ε-independent order: latest).
  Eigen::VectorXd best_y = y;
  int best_inverted = st.inverted;
  int last_progress = 0;
  double progress_min_det = st.min_det;

  Eigen::VectorXd g(n);  // the gradient, refilled every Newton step
  NewtonAssembler assembler(el, A);
  core::ProgressTask task("untangle", std::max(1, o.max_iterations));
  for (int outer = 0; outer < o.max_iterations; ++outer) {
    task.set(outer);
    ++res.iterations;
    st = evaluate(el, attractions, x, eps, lambda, det_target, nullptr, &at_x);  // ε (and targets) changed
    const double E_prev = st.energy;
    // The stats at x as the steps move it (each accepted trial's): no evaluation twice.
    Stats here = st;
    for (int step = 0; step < o.newton_steps; ++step) {
      // Assemble the gradient and projected Hessian in y.
      core::Stopwatch phase;
      assembler.assemble(x, eps, lambda, attractions, H, g);
      double* hv = H.valuePtr();
      t_assemble += phase.seconds();
      phase.restart();
      // Regularize (translations and other null directions of a projected Hessian).
      double mean_diag = 0.0;
      for (int j = 0; j < n; ++j) mean_diag += hv[A.diag_slot[j]];
      mean_diag = std::max(mean_diag / n, 1e-300);
      double reg = std::max(1e-9 * mean_diag, damping);
      Eigen::VectorXd dir;
      if (o.linear_solver == NewtonSolver::Cholesky) {
        // Hr = H + reg·I, the system both ways below solve.
        const auto regularize = [&] {
          double* rv = Hr.valuePtr();
          std::copy(hv, hv + H.nonZeros(), rv);
          for (int j = 0; j < n; ++j) rv[A.diag_slot[j]] += reg;
        };
        regularize();
        bool reused = false;
        if (stale_budget > 0 && solver.factorized() && skip_stale-- <= 0) {
          int its = 0;
          reused = stale_factor_cg(Hr, g, solver, stale_budget, o.stale_factor_tolerance, dir, its);
          stale_its += its;
          if (reused) {
            ++res.stale_factor_steps;
            backoff = 1;
          } else {
            ++stale_misses;
            skip_stale = backoff;
            backoff = std::min(2 * backoff, 16);
          }
        }
        if (!reused) {
          ++res.factorizations;
          bool ok = false;
          for (int attempt = 0; attempt < 12 && !ok; ++attempt) {
            if (attempt > 0) regularize();
            ok = solver.factorize(Hr);
            if (!ok) reg *= 100.0;
          }
          if (!ok) throw core::SolverError("untangle: the Newton system could not be factorized");
          dir = solver.solve(Eigen::VectorXd(-g));
        }
      } else {
        // Truncated Newton: a few Jacobi-preconditioned CG iterations on the (PSD) system give
        // a descent direction at a fraction of a factorization's cost on large meshes.
        for (int j = 0; j < n; ++j) hv[A.diag_slot[j]] += reg;
        Eigen::ConjugateGradient<Eigen::SparseMatrix<double>, Eigen::Upper> cg;
        cg.setMaxIterations(o.cg_iterations);
        cg.setTolerance(o.cg_tolerance);
        cg.compute(H);
        dir = cg.solve(Eigen::VectorXd(-g));
        if (!dir.allFinite()) dir = -g;
      }
      ++res.newton_steps;
      const double slope = g.dot(dir);
      t_factor += phase.seconds();
      phase.restart();
      if (!(slope < 0)) break;  // converged (or numerically stuck)
      // Backtracking line search; once valid, never accept a step that inverts an element.
      const Stats cur = here;
      const bool keep_valid = cur.inverted == 0;
      double alpha = 1.0;
      bool accepted = false;
      for (int ls = 0; ls < 40; ++ls, alpha *= 0.5) {
        const Eigen::VectorXd yt = y + alpha * dir;
        const Eigen::VectorXd xt = R.apply(yt);
        const Stats trial = evaluate(el, attractions, xt, eps, lambda, det_target, &at_trial);
        if (std::isfinite(trial.energy) && trial.energy <= cur.energy + 1e-4 * alpha * slope &&
            (!keep_valid || trial.inverted == 0)) {
          y = yt;
          x = xt;
          at_x.swap(at_trial);
          here = trial;
          accepted = true;
          break;
        }
      }
      t_search += phase.seconds();
      if (!accepted) break;
      if (alpha < 1e-3) damping = std::max(damping * 10.0, 1e-6 * mean_diag);  // poor model: damp
      else damping *= 0.1;
      if (std::abs(alpha * slope) < 1e-14 * std::abs(cur.energy)) break;
    }
    st = here;
    const double E = st.energy;
    core::logger().debug("untangle: iteration {} E {:.6g} eps {:.3g} min det {:.3g} inverted {}", outer, E, eps,
                         st.min_det, st.inverted);
    // Progress: fewer inverted elements, or a clearly less negative min det (the inverted
    // count can stay flat for many iterations while the remaining ones unfold).
    if (st.inverted < best_inverted || (st.inverted > 0 && st.min_det > progress_min_det + std::max(0.02 * std::abs(progress_min_det),
                                                                      o.stall_min_det_rise))) {
      last_progress = outer;
      progress_min_det = st.min_det;
    }
    if (st.inverted <= best_inverted) {
      best_inverted = st.inverted;
      best_y = y;
    }
    if (st.inverted > 0 && o.stall_iterations > 0 && outer - last_progress >= o.stall_iterations) break;
    if (o.stop_when_untangled && st.inverted == 0) break;
    if (st.inverted == 0 && std::abs(E_prev - E) <= o.tolerance * std::abs(E)) break;
    // ε update of Garanzha et al. 2021 (section 4): follow the min det.
    const double sigma = std::max(1.0 - E / E_prev, o.min_sigma);
    const double mu = (1.0 - sigma) * chi(st.min_det, eps);
    if (st.min_det < mu) eps = std::max(o.min_epsilon, 2.0 * std::sqrt(mu * (mu - st.min_det)));
    else eps = o.min_epsilon;
    if (o.on_iteration && !o.on_iteration(outer, x, attractions)) break;
    if (o.expired && o.expired()) break;
  }
  if (st.inverted > best_inverted) {
    y = best_y;
    x = R.apply(y);
  }
  task.finish();
  core::logger().debug(
      "untangle: assembly {:.2f} s, factorization+solve {:.2f} s, line search {:.2f} s; {} factorizations, {} "
      "steps on an earlier one ({} missed, {} CG iterations)",
      t_assemble, t_factor, t_search, res.factorizations, res.stale_factor_steps, stale_misses, stale_its);
  st = evaluate(el, attractions, x, eps, lambda, det_target);
  res.untangled = st.inverted == 0;
  res.inverted_after = st.inverted;
  res.min_det = st.min_det;
  res.energy = st.energy;
  res.epsilon = eps;
  res.seconds = clock.seconds();
  return res;
}

std::pair<Eigen::SparseMatrix<double>, Eigen::VectorXd> detail::newton_system(const TetElements& el,
                                                                             const LinearReduction& R,
                                                                             const Eigen::VectorXd& y, double eps,
                                                                             double lambda,
                                                                             const std::vector<Attraction>& attr) {
  const Assembly A = build_assembly(el, R, attr);
  Eigen::SparseMatrix<double> H = A.H;
  Eigen::VectorXd g(A.n);
  NewtonAssembler(el, A).assemble(R.apply(y), eps, lambda, attr, H, g);
  return {std::move(H), std::move(g)};
}

UntangleResult untangle_fast_first(const TetElements& el, const LinearReduction& R, Eigen::VectorXd& y,
                                   const UntangleOptions& o, double fast_sigma) {
  if (o.min_sigma >= fast_sigma) return untangle(el, R, y, o);
  UntangleOptions fast = o;
  fast.min_sigma = fast_sigma;
  const Eigen::VectorXd start = y;
  const UntangleResult first = untangle(el, R, y, fast);
  if (first.untangled || (o.expired && o.expired())) return first;
  core::logger().debug("untangle: {} elements stay inverted with ε falling by {} or more: from the start again, by {}",
                       first.inverted_after, fast_sigma, o.min_sigma);
  y = start;
  UntangleResult second = untangle(el, R, y, o);
  second.slower_schedule = true;
  second.seconds += first.seconds;
  return second;
}

}  // namespace polycube::solve
