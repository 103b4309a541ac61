//! Untangling of a polycube map under its chart constraints (see untangle_map.h).
#include "mapping/untangle_map.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/polycube_map.h"
#include "mapping/corner_fans.h"
#include "mapping/ghost_tets.h"

#include <algorithm>

namespace polycube::mapping {

namespace {

using core::Tri;
using core::Vec3;

//! The elliptic optimization with one ghost tet per boundary triangle (ghost_tets.h): each
//! apex's label-axis coordinate is its chart's variable + sign·h, the two others are new free
//! variables starting above the triangle's centroid.
solve::UntangleResult untangle_with_ghosts(const LabeledTetMesh& lm, const MapVariables& mv, std::vector<Vec3>& P,
                                           const solve::UntangleOptions& uo, double h) {
  const core::TetMesh& mesh = lm.mesh;
  const std::vector<int>& var = mv.var;
  const int nvar = mv.count;
  const int np = mesh.num_points();
  const int nb = static_cast<int>(lm.boundary.size());
  const GhostTets ghosts = ghost_tets(mesh.points, lm.boundary, lm.labels, h, np);
  std::vector<Vec3> ref = mesh.points;
  std::vector<core::Tet> tets = mesh.cells;
  ref.insert(ref.end(), ghosts.reference.begin(), ghosts.reference.end());
  tets.insert(tets.end(), ghosts.tets.begin(), ghosts.tets.end());
  // Reduction: the real coordinates as given, then the ghosts'.
  const int rows = 3 * (np + nb);
  int n = nvar;
  Eigen::SparseMatrix<double, Eigen::RowMajor> B(rows, nvar + 2 * nb);
  B.reserve(Eigen::VectorXi::Constant(rows, 1));
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(rows);
  for (int i = 0; i < 3 * np; ++i) {
    if (var[i] >= 0) B.insert(i, var[i]) = 1.0;
    else x0[i] = P[i / 3][i % 3];
  }
  Eigen::VectorXd y = Eigen::VectorXd::Zero(nvar + 2 * nb);
  for (int i = 0; i < 3 * np; ++i)
    if (var[i] >= 0) y[var[i]] = P[i / 3][i % 3];
  for (int f = 0; f < nb; ++f) {
    const Tri& t = lm.boundary[f];
    const int a = lm.labels[f] / 2;
    const double sign = lm.labels[f] % 2 == 0 ? 1.0 : -1.0;
    const int row = 3 * (np + f);
    const int chart_var = var[3 * static_cast<std::size_t>(t[0]) + a];
    PC_REQUIRE(lm.charts.vertex_group[3 * static_cast<std::size_t>(t[0]) + a] >= 0 && chart_var >= 0,
               "deform: a boundary triangle's chart coordinate is not a variable");
    const Vec3 c = ghost_apex(P, t, lm.labels[f], h);
    for (int d = 0; d < 3; ++d) {
      if (d == a) {
        B.insert(row + d, chart_var) = 1.0;
        x0[row + d] = sign * h;
      } else {
        B.insert(row + d, n) = 1.0;
        y[n++] = c[d];
      }
    }
  }
  B.makeCompressed();
  solve::LinearReduction R;
  R.B = std::move(B);
  R.x0 = std::move(x0);
  Eigen::VectorXd yy = y.head(n);
  const solve::UntangleResult ur = solve::untangle(solve::reference_elements(ref, tets), R, yy, uo);
  const Eigen::VectorXd x = R.apply(yy);
  for (int v = 0; v < np; ++v) P[v] = x.segment<3>(3 * v);
  return ur;
}

//! The elliptic optimization of the real tets alone.
solve::UntangleResult untangle_without_ghosts(const LabeledTetMesh& lm, const MapVariables& mv, std::vector<Vec3>& P,
                                              const solve::UntangleOptions& uo) {
  const core::TetMesh& mesh = lm.mesh;
  const int np = mesh.num_points();
  const solve::LinearReduction R = solve::index_reduction(mv.var, mv.count, Eigen::VectorXd::Zero(3 * np));
  Eigen::VectorXd y = Eigen::VectorXd::Zero(mv.count);
  for (int v = 0; v < np; ++v)
    for (int d = 0; d < 3; ++d) y[mv.var[3 * static_cast<std::size_t>(v) + d]] = P[v][d];
  const solve::UntangleResult r = solve::untangle(solve::reference_elements(mesh.points, mesh.cells), R, y, uo);
  for (int v = 0; v < np; ++v)
    for (int d = 0; d < 3; ++d) P[v][d] = y[mv.var[3 * static_cast<std::size_t>(v) + d]];
  return r;
}

//! The vertices within `rings` tet rings of the failures of P and of `seeds`.
std::vector<char> region_around_failures(const LabeledTetMesh& lm, const std::vector<Vec3>& P, int rings,
                                         const std::vector<int>& seeds) {
  const core::TetMesh& mesh = lm.mesh;
  const int nv = mesh.num_points();
  std::vector<char> in(static_cast<std::size_t>(nv), 0);
  for (const auto& c : mesh.cells)
    if (!core::positive_tet(P, c))
      for (int v : c) in[v] = 1;
  for (std::size_t f = 0; f < lm.boundary.size(); ++f)
    if (!core::faces_label(P, lm.boundary[f], lm.labels[f]))
      for (int v : lm.boundary[f]) in[v] = 1;
  for (int v : seeds) in[v] = 1;
  std::vector<std::vector<int>> vc(static_cast<std::size_t>(nv));
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (int v : mesh.cells[c]) vc[v].push_back(static_cast<int>(c));
  for (int r = 0; r < rings; ++r) {
    std::vector<char> next = in;
    for (int v = 0; v < nv; ++v)
      if (in[v])
        for (int c : vc[v])
          for (int w : mesh.cells[c]) next[w] = 1;
    in.swap(next);
  }
  return in;
}

//! Local untangling: only the coordinates within `rings` tet rings of the failures and of the
//! `seeds` move; the region's boundary triangles carry ghost tets of height h (none when h is
//! 0). Returns the number of failures in the whole mesh afterwards (never more than before).
int untangle_locally(const LabeledTetMesh& lm, std::vector<Vec3>& P, int rings, const solve::UntangleOptions& base,
                     double h, const std::vector<int>& seeds) {
  const core::TetMesh& mesh = lm.mesh;
  const std::vector<int>& vertex_group = lm.charts.vertex_group;
  const int nv = mesh.num_points();
  const std::vector<char> in = region_around_failures(lm, P, rings, seeds);
  std::vector<core::Tet> local;
  for (const auto& c : mesh.cells)
    if (in[c[0]] || in[c[1]] || in[c[2]] || in[c[3]]) local.push_back(c);
  // Ghost tets of the region's boundary triangles: apex at h above the (fixed) chart plane.
  std::vector<Tri> region_tris;
  std::vector<int> region_labels;
  if (h > 0)
    for (std::size_t f = 0; f < lm.boundary.size(); ++f) {
      const Tri& t = lm.boundary[f];
      if (!in[t[0]] && !in[t[1]] && !in[t[2]]) continue;
      region_tris.push_back(t);
      region_labels.push_back(lm.labels[f]);
    }
  const GhostTets ghosts = ghost_tets(mesh.points, region_tris, region_labels, h, nv);
  std::vector<Vec3> ref = mesh.points;
  ref.insert(ref.end(), ghosts.reference.begin(), ghosts.reference.end());
  local.insert(local.end(), ghosts.tets.begin(), ghosts.tets.end());
  const int np = static_cast<int>(ref.size());
  std::vector<int> var(3 * static_cast<std::size_t>(np), -1);
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (in[v])
      for (int d = 0; d < 3; ++d)
        if (vertex_group[3 * static_cast<std::size_t>(v) + d] < 0) var[3 * static_cast<std::size_t>(v) + d] = n++;
  Eigen::VectorXd fixed(3 * static_cast<Eigen::Index>(np));
  for (int v = 0; v < nv; ++v) fixed.segment<3>(3 * v) = P[v];
  for (std::size_t g = 0; g < region_tris.size(); ++g) {
    const int v = nv + static_cast<int>(g);
    fixed.segment<3>(3 * v) = ghost_apex(P, region_tris[g], region_labels[g], h);
    for (int d = 0; d < 3; ++d)
      if (d != core::label_axis(region_labels[g])) var[3 * static_cast<std::size_t>(v) + d] = n++;
  }
  const solve::LinearReduction R = solve::index_reduction(var, n, fixed);
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < var.size(); ++i)
    if (var[i] >= 0) y[var[i]] = fixed[static_cast<Eigen::Index>(i)];
  solve::UntangleOptions uo = base;
  uo.initial_epsilon = 1.0;
  uo.max_iterations = std::max(base.max_iterations, 200);
  solve::untangle(solve::reference_elements(ref, local), R, y, uo);
  const Eigen::VectorXd x = R.apply(y);
  std::vector<Vec3> Q = P;
  for (int v = 0; v < nv; ++v) Q[v] = x.segment<3>(3 * v);
  const int before = failures(lm, P);
  int after = failures(lm, Q);
  if (after <= before) std::swap(P, Q);  // never make it worse
  else after = before;
  core::logger().debug("deform: local untangling ({} rings, {} tets with {} ghosts, {} variables): {} -> {} failures",
                       rings, local.size(), region_tris.size(), n, before, after);
  return after;
}

}  // namespace

solve::UntangleResult untangle_globally(const LabeledTetMesh& lm, std::vector<Vec3>& P, const UntangleMapOptions& o) {
  const MapVariables mv = map_variables(lm);
  if (o.ghost_height > 0) return untangle_with_ghosts(lm, mv, P, o.untangle, o.ghost_height);
  return untangle_without_ghosts(lm, mv, P, o.untangle);
}

LocalRepairResult repair_locally(const LabeledTetMesh& lm, std::vector<Vec3>& P, const UntangleMapOptions& u,
                                 const LocalRepairOptions& o) {
  LocalRepairResult res;
  std::vector<int> seeds;
  for (int rings : o.rings) {
    bool fixed = untangle_locally(lm, P, rings, u.untangle, u.ghost_height, seeds) == 0;
    if (!fixed && o.reopen_fans) {
      const int before = failures(lm, P);
      std::vector<Vec3> trial = P;
      const ReopenedFans rf = reopen_flipped_fans(lm.boundary, lm.labels, trial);
      if (rf.fans > 0) {
        core::logger().debug("deform: {} flipped corner fans placed on their long sweep ({} vertices)", rf.fans,
                             rf.vertices.size());
        res.reopened_fans += rf.fans;
        P.swap(trial);
        seeds.insert(seeds.end(), rf.vertices.begin(), rf.vertices.end());
        const int after = untangle_locally(lm, P, rings, u.untangle, u.ghost_height, seeds);
        if (after > before) P.swap(trial);  // compare with the state before the fans moved
        fixed = after == 0;
      }
    }
    if (fixed) {
      res.fixed = true;
      return res;
    }
  }
  return res;
}

}  // namespace polycube::mapping
