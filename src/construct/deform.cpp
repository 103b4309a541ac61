//! Polycube deformation (see deform.h).
#include "construct/deform.h"
#include "construct/boundary_first.h"
#include "construct/corner_fans.h"
#include "construct/labeling.h"
#include "construct/planarity_flow.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "solve/rotation.h"
#include "solve/sparse_solver.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <Eigen/SparseCore>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <numeric>

namespace polycube::construct {

namespace {

using core::Tri;
using core::Vec3;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


std::array<int, 3> sorted(const Tri& t) {
  std::array<int, 3> k{t[0], t[1], t[2]};
  std::sort(k.begin(), k.end());
  return k;
}

//! Boundary faces of the mesh (outward) with their owning tet/local face, and the labels of the
//! caller's triangles transferred onto them.
struct LabeledBoundary {
  std::vector<Tri> tris;
  std::vector<int> labels;
  std::vector<int> cell;
  std::vector<int> local;
};

LabeledBoundary match_boundary(const core::TetMesh& mesh, const std::vector<Tri>& given, const std::vector<int>& labels) {
  const core::TetBoundary b = core::boundary(mesh);
  const std::size_t nb = b.surface.cells.size();
  if (given.size() != nb)
    throw core::InputError(fmt::format("deform: {} labeled triangles given but the tet mesh has {} boundary faces",
                                       given.size(), nb));
  if (labels.size() != given.size())
    throw core::InputError(fmt::format("deform: {} labels for {} boundary triangles", labels.size(), given.size()));
  std::vector<std::pair<std::array<int, 3>, int>> keys(nb);
  for (std::size_t i = 0; i < nb; ++i) {
    if (labels[i] < 0 || labels[i] > 5)
      throw core::InputError(fmt::format("deform: label {} of triangle {} is not in 0..5", labels[i], i));
    keys[i] = {sorted(given[i]), labels[i]};
  }
  std::sort(keys.begin(), keys.end());
  LabeledBoundary out;
  out.tris.resize(nb);
  out.labels.resize(nb);
  out.cell = b.cell_of_face;
  out.local = b.local_face;
  for (std::size_t f = 0; f < nb; ++f) {
    const Tri& s = b.surface.cells[f];
    out.tris[f] = {b.vertex_map[s[0]], b.vertex_map[s[1]], b.vertex_map[s[2]]};
    const auto k = sorted(out.tris[f]);
    auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    if (it == keys.end() || it->first != k)
      throw core::InputError(fmt::format("deform: boundary face ({}, {}, {}) of the tet mesh has no label", k[0], k[1], k[2]));
    out.labels[f] = it->second;
  }
  return out;
}

//! Charts and the chart coordinate variable of each (vertex, axis).
struct ChartVars {
  std::vector<int> tri_chart;  // #B
  int num_charts = 0;
  std::vector<int> vertex_group;  // 3#V: group id of (v, axis), -1 when v is on no chart of that axis
  int num_groups = 0;
};

ChartVars chart_variables(int nv, const std::vector<Tri>& tris, const std::vector<int>& labels) {
  ChartVars cv;
  const int nb = static_cast<int>(tris.size());
  // edge -> triangles, by sorting
  std::vector<std::array<int, 3>> edges;  // (a, b, tri)
  edges.reserve(3 * tris.size());
  for (int t = 0; t < nb; ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = tris[t][e], b = tris[t][(e + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), t});
    }
  std::sort(edges.begin(), edges.end());
  core::DisjointSets uf(static_cast<std::size_t>(nb));
  for (std::size_t i = 0; i + 1 < edges.size(); ++i)
    if (edges[i][0] == edges[i + 1][0] && edges[i][1] == edges[i + 1][1] &&
        labels[edges[i][2]] == labels[edges[i + 1][2]])
      uf.unite(edges[i][2], edges[i + 1][2]);
  cv.tri_chart.assign(static_cast<std::size_t>(nb), -1);
  std::vector<int> root_id(static_cast<std::size_t>(nb), -1);
  for (int t = 0; t < nb; ++t) {
    const int r = uf.find(t);
    if (root_id[r] < 0) root_id[r] = cv.num_charts++;
    cv.tri_chart[t] = root_id[r];
  }
  std::vector<int> chart_axis(static_cast<std::size_t>(cv.num_charts));
  for (int t = 0; t < nb; ++t) chart_axis[cv.tri_chart[t]] = labels[t] / 2;
  // Charts of one axis sharing a vertex share their coordinate.
  core::DisjointSets cu(static_cast<std::size_t>(cv.num_charts));
  std::vector<int> first(3 * static_cast<std::size_t>(nv), -1);
  for (int t = 0; t < nb; ++t) {
    const int c = cv.tri_chart[t];
    const int a = chart_axis[c];
    for (int v : tris[t]) {
      int& f = first[3 * static_cast<std::size_t>(v) + a];
      if (f < 0) f = c;
      else cu.unite(f, c);
    }
  }
  std::vector<int> group_of_root(static_cast<std::size_t>(cv.num_charts), -1);
  for (int c = 0; c < cv.num_charts; ++c) {
    const int r = cu.find(c);
    if (group_of_root[r] < 0) group_of_root[r] = cv.num_groups++;
  }
  cv.vertex_group.assign(3 * static_cast<std::size_t>(nv), -1);
  for (std::size_t i = 0; i < first.size(); ++i)
    if (first[i] >= 0) cv.vertex_group[i] = group_of_root[cu.find(first[i])];
  return cv;
}

//! Boundary triangles whose three vertices share the chart coordinate of an in-plane axis.
std::vector<int> forced_flat_triangles(const std::vector<Tri>& tris, const std::vector<int>& labels,
                                       const ChartVars& cv) {
  std::vector<int> out;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    const int a = labels[t] / 2;
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      const int g0 = cv.vertex_group[3 * static_cast<std::size_t>(tris[t][0]) + b];
      if (g0 >= 0 && g0 == cv.vertex_group[3 * static_cast<std::size_t>(tris[t][1]) + b] &&
          g0 == cv.vertex_group[3 * static_cast<std::size_t>(tris[t][2]) + b]) {
        out.push_back(static_cast<int>(t));
        break;
      }
    }
  }
  return out;
}

//! Chart-interior boundary edges (both triangles in one chart) whose endpoints share the chart
//! coordinate of an in-plane axis: the constraints put the edge on a polycube edge line while
//! the chart lies on both sides of it, which forces a fold.
std::vector<std::array<int, 2>> chord_edges(const std::vector<Tri>& tris, const std::vector<int>& labels,
                                            const ChartVars& cv) {
  std::vector<std::array<int, 3>> edges;  // (a, b, tri)
  edges.reserve(3 * tris.size());
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = tris[t][e], b = tris[t][(e + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<int>(t)});
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::array<int, 2>> out;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    if (edges[i][0] != edges[i + 1][0] || edges[i][1] != edges[i + 1][1]) continue;
    const int t0 = edges[i][2], t1 = edges[i + 1][2];
    if (cv.tri_chart[t0] != cv.tri_chart[t1]) continue;
    const int a = labels[t0] / 2;
    const auto u = static_cast<std::size_t>(edges[i][0]), v = static_cast<std::size_t>(edges[i][1]);
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      const int g = cv.vertex_group[3 * u + b];
      if (g >= 0 && g == cv.vertex_group[3 * v + b]) {
        out.push_back({edges[i][0], edges[i][1]});
        break;
      }
    }
  }
  return out;
}

//! Boundary edges to split so that, at every polycube corner (a vertex whose triangles carry
//! three axes), each chart's fan of triangles has at least `min_fan` triangles: a chart may have
//! to open to 270° there, which two or three triangles (each below 180°) cannot do without
//! nearly flat tets beneath them. Splitting the edge opposite the corner in each triangle of a
//! thin fan doubles the fan (splitting a spoke would not: both halves keep one triangle at the
//! corner).
std::vector<std::array<int, 2>> thin_fan_edges(int nv, const std::vector<Tri>& tris, const std::vector<int>& labels,
                                               int min_fan) {
  std::vector<std::array<int, 2>> out;
  if (min_fan <= 1) return out;
  std::vector<std::vector<int>> vt(static_cast<std::size_t>(nv));
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v : tris[t]) vt[v].push_back(static_cast<int>(t));
  for (int v = 0; v < nv; ++v) {
    if (vt[v].empty()) continue;
    int axes = 0;
    for (int t : vt[v]) axes |= 1 << (labels[t] / 2);
    if (axes != 7) continue;
    for (int l = 0; l < 6; ++l) {
      std::vector<int> fan;
      for (int t : vt[v])
        if (labels[t] == l) fan.push_back(t);
      if (fan.empty() || static_cast<int>(fan.size()) >= min_fan) continue;
      for (int f : fan) {
        const Tri& t = tris[f];
        const int k = static_cast<int>(std::find(t.begin(), t.end(), v) - t.begin());
        const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
        out.push_back({std::min(a, b), std::max(a, b)});
      }
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

//! Split the edges at their midpoints (every tet and boundary triangle around each edge in
//! two). Edges whose tets were already modified in this call are left for the next round.
//! Returns the number of edges split.
int split_edges(core::TetMesh& mesh, LabeledBoundary& lb, const std::vector<std::array<int, 2>>& edges,
                std::vector<Vec3>* other = nullptr) {
  // Vertex -> cells and vertex -> boundary triangles, kept up to date while splitting: an edge
  // that shares a vertex with an edge split earlier in this call must see the new cells, or it
  // would be split in some of its tets only (a hanging node, a non-conforming mesh).
  std::vector<std::vector<int>> vc(static_cast<std::size_t>(mesh.num_points()));
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (int w : mesh.cells[c]) vc[w].push_back(static_cast<int>(c));
  std::vector<std::vector<int>> vt(static_cast<std::size_t>(mesh.num_points()));
  for (std::size_t t = 0; t < lb.tris.size(); ++t)
    for (int w : lb.tris[t]) vt[w].push_back(static_cast<int>(t));
  auto drop = [](std::vector<int>& list, int item) { list.erase(std::remove(list.begin(), list.end(), item), list.end()); };
  std::vector<char> touched(mesh.cells.size(), 0);
  int count = 0;
  for (const auto& e : edges) {
    const int u = e[0], v = e[1];
    std::vector<int> around;
    for (int c : vc[u])
      if (std::find(mesh.cells[c].begin(), mesh.cells[c].end(), v) != mesh.cells[c].end()) around.push_back(c);
    bool busy = around.empty();
    for (int c : around) busy = busy || touched[c];
    if (busy) continue;
    const int m = mesh.num_points();
    mesh.points.push_back(0.5 * (mesh.points[u] + mesh.points[v]));
    if (other) other->push_back(0.5 * ((*other)[u] + (*other)[v]));  // exact where u, v share a coordinate
    vc.emplace_back();
    vt.emplace_back();
    for (int c : around) {
      // Replacing an edge end by a point inside the edge keeps the orientation.
      core::Tet second = mesh.cells[c];
      for (int& w : mesh.cells[c])
        if (w == v) w = m;
      for (int& w : second)
        if (w == u) w = m;
      const int c2 = static_cast<int>(mesh.cells.size());
      mesh.cells.push_back(second);
      if (!mesh.labels.empty()) mesh.labels.push_back(mesh.labels[c]);
      touched[c] = 1;
      drop(vc[v], c);
      vc[m].push_back(c);
      for (int w : second) vc[w].push_back(c2);
    }
    touched.resize(mesh.cells.size(), 1);
    const std::vector<int> tris_u = vt[u];
    for (int t : tris_u) {
      Tri& tri = lb.tris[t];
      if (std::find(tri.begin(), tri.end(), v) == tri.end()) continue;
      Tri second = tri;
      for (int& w : tri)
        if (w == v) w = m;
      for (int& w : second)
        if (w == u) w = m;
      const int t2 = static_cast<int>(lb.tris.size());
      lb.tris.push_back(second);
      lb.labels.push_back(lb.labels[t]);
      drop(vt[v], t);
      vt[m].push_back(t);
      for (int w : second) vt[w].push_back(t2);
    }
    ++count;
  }
  return count;
}

//! Split boundary triangle f (and its tet) at the triangle's centroid. Returns false when the
//! tet was already modified in this round.
bool split_boundary_triangle(core::TetMesh& mesh, LabeledBoundary& lb, int f, std::vector<char>& touched,
                             std::vector<Vec3>* other = nullptr) {
  const int t = lb.cell[f];
  if (touched[t]) return false;
  const Tri tri = lb.tris[f];
  const int m = mesh.num_points();
  mesh.points.push_back((mesh.points[tri[0]] + mesh.points[tri[1]] + mesh.points[tri[2]]) / 3.0);
  if (other) other->push_back(((*other)[tri[0]] + (*other)[tri[1]] + (*other)[tri[2]]) / 3.0);
  const core::Tet old = mesh.cells[t];
  // Replacing one face vertex by a point inside the face keeps the orientation.
  bool first = true;
  for (int k = 0; k < 3; ++k) {
    core::Tet nt = old;
    for (int& v : nt)
      if (v == tri[k]) v = m;
    if (first) {
      mesh.cells[t] = nt;
      first = false;
    } else {
      mesh.cells.push_back(nt);
      if (!mesh.labels.empty()) mesh.labels.push_back(mesh.labels[t]);
    }
  }
  touched.resize(mesh.cells.size(), 1);
  touched[t] = 1;
  const int label = lb.labels[f];
  lb.tris[f] = {m, tri[1], tri[2]};
  lb.tris.push_back({tri[0], m, tri[2]});
  lb.tris.push_back({tri[0], tri[1], m});
  lb.labels.push_back(label);
  lb.labels.push_back(label);
  return true;
}

//! The elliptic optimization of the polycube positions P, with one **ghost tet** per boundary
//! triangle: the triangle plus a ghost vertex at height h above its chart plane along the
//! label's direction (its in-plane coordinates free). The ghost tet is positive exactly when
//! the triangle faces its label, so the barrier also keeps the boundary from folding over
//! itself while every real tet is positive (a fold the real tets alone cannot see). Its
//! reference shape is the model triangle with a point at height h along the model normal.
//! P (the real vertices) is updated in place.
solve::UntangleResult untangle_with_ghosts(const core::TetMesh& mesh, const LabeledBoundary& lb,
                                           const std::vector<int>& vertex_group, const std::vector<int>& var,
                                           int nvar, std::vector<Vec3>& P, const solve::UntangleOptions& uo,
                                           double h) {
  const int np = mesh.num_points();
  const int nb = static_cast<int>(lb.tris.size());
  std::vector<Vec3> ref = mesh.points;
  std::vector<core::Tet> tets = mesh.cells;
  ref.reserve(static_cast<std::size_t>(np + nb));
  tets.reserve(mesh.cells.size() + static_cast<std::size_t>(nb));
  for (int f = 0; f < nb; ++f) {
    const Tri& t = lb.tris[f];
    const Vec3 c = (mesh.points[t[0]] + mesh.points[t[1]] + mesh.points[t[2]]) / 3.0;
    const Vec3 n = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]).normalized();
    ref.push_back(c + h * n);
    tets.push_back({t[0], t[1], t[2], np + f});
  }
  // Reduction: the real coordinates as given; each ghost's label-axis coordinate is its
  // chart's variable + sign·h, the two others are new free variables.
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
    const Tri& t = lb.tris[f];
    const int a = lb.labels[f] / 2;
    const double sign = lb.labels[f] % 2 == 0 ? 1.0 : -1.0;
    const int row = 3 * (np + f);
    const int chart_var = var[3 * static_cast<std::size_t>(t[0]) + a];
    PC_REQUIRE(vertex_group[3 * static_cast<std::size_t>(t[0]) + a] >= 0 && chart_var >= 0,
               "deform: a boundary triangle's chart coordinate is not a variable");
    const Vec3 c = (P[t[0]] + P[t[1]] + P[t[2]]) / 3.0;
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

//! Tet c has a positive volume in P.
//! Boundary triangles of lb facing away from their label in P.
int facing_away(const LabeledBoundary& lb, const std::vector<Vec3>& P) {
  int n = 0;
  for (std::size_t f = 0; f < lb.tris.size(); ++f) n += !faces_label(P, lb.tris[f], lb.labels[f]);
  return n;
}

//! Failures of a polycube P: tets with det <= 0 and boundary triangles facing away from their label.
int failures(const core::TetMesh& mesh, const LabeledBoundary& lb, const std::vector<Vec3>& P) {
  int n = facing_away(lb, P);
  for (const auto& c : mesh.cells) n += !core::positive_tet(P, c);
  return n;
}

//! Height of the ghost tets: `fraction` of the mean boundary edge length (model space).
double ghost_height(const core::TetMesh& mesh, const LabeledBoundary& lb, double fraction) {
  if (!(fraction > 0)) return 0.0;
  double sum = 0;
  for (const Tri& t : lb.tris)
    for (int e = 0; e < 3; ++e) sum += (mesh.points[t[e]] - mesh.points[t[(e + 1) % 3]]).norm();
  return fraction * sum / static_cast<double>(std::max<std::size_t>(1, 3 * lb.tris.size()));
}

//! Local untangling (after the global optimization left a few failures): only the coordinates
//! within `rings` tet rings of the failures (inverted tets, boundary triangles facing away) and
//! of the `seeds` move, chart coordinates stay at their current value, and ε starts afresh
//! (large ε is safe here, the fixed surroundings keep the region from shrinking). The boundary
//! triangles of the region carry ghost tets of height h (as in untangle_with_ghosts; none when
//! h is 0). Returns the number of failures in the whole mesh afterwards (never more than before).
int untangle_locally(const core::TetMesh& mesh, const LabeledBoundary& lb, const std::vector<int>& vertex_group,
                     std::vector<Vec3>& P, int rings, const solve::UntangleOptions& base, double h,
                     const std::vector<int>& seeds = {}) {
  const int nv = mesh.num_points();
  std::vector<char> in(static_cast<std::size_t>(nv), 0);
  for (const auto& c : mesh.cells)
    if (!core::positive_tet(P, c))
      for (int v : c) in[v] = 1;
  for (std::size_t f = 0; f < lb.tris.size(); ++f)
    if (!faces_label(P, lb.tris[f], lb.labels[f]))
      for (int v : lb.tris[f]) in[v] = 1;
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
  std::vector<core::Tet> local;
  for (const auto& c : mesh.cells)
    if (in[c[0]] || in[c[1]] || in[c[2]] || in[c[3]]) local.push_back(c);
  // Ghost tets of the region's boundary triangles: apex at h above the (fixed) chart plane.
  std::vector<Vec3> ref = mesh.points;
  std::vector<Vec3> ghost_start;
  std::vector<int> ghost_axis;
  if (h > 0)
    for (std::size_t f = 0; f < lb.tris.size(); ++f) {
      const Tri& t = lb.tris[f];
      if (!in[t[0]] && !in[t[1]] && !in[t[2]]) continue;
      const Vec3& m0 = mesh.points[t[0]];
      const Vec3 n = (mesh.points[t[1]] - m0).cross(mesh.points[t[2]] - m0).normalized();
      ref.push_back((m0 + mesh.points[t[1]] + mesh.points[t[2]]) / 3.0 + h * n);
      local.push_back({t[0], t[1], t[2], static_cast<int>(ref.size()) - 1});
      const int a = lb.labels[f] / 2;
      Vec3 apex = (P[t[0]] + P[t[1]] + P[t[2]]) / 3.0;
      apex[a] = P[t[0]][a] + (lb.labels[f] % 2 == 0 ? h : -h);
      ghost_start.push_back(apex);
      ghost_axis.push_back(a);
    }
  const int np = static_cast<int>(ref.size());
  std::vector<int> var(3 * static_cast<std::size_t>(np), -1);
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (in[v])
      for (int d = 0; d < 3; ++d)
        if (vertex_group[3 * static_cast<std::size_t>(v) + d] < 0) var[3 * static_cast<std::size_t>(v) + d] = n++;
  Eigen::VectorXd fixed(3 * static_cast<Eigen::Index>(np));
  for (int v = 0; v < nv; ++v) fixed.segment<3>(3 * v) = P[v];
  for (std::size_t g = 0; g < ghost_start.size(); ++g) {
    const int v = nv + static_cast<int>(g);
    fixed.segment<3>(3 * v) = ghost_start[g];
    for (int d = 0; d < 3; ++d)
      if (d != ghost_axis[g]) var[3 * static_cast<std::size_t>(v) + d] = n++;
  }
  const solve::LinearReduction R = solve::index_reduction(var, n, fixed);
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < var.size(); ++i)
    if (var[i] >= 0) y[var[i]] = fixed[static_cast<Eigen::Index>(i)];
  solve::UntangleOptions uo = base;
  uo.initial_epsilon = 1.0;
  uo.max_iterations = std::max(base.max_iterations, 200);
  const solve::UntangleResult ur = solve::untangle(solve::reference_elements(ref, local), R, y, uo);
  const Eigen::VectorXd x = R.apply(y);
  std::vector<Vec3> Q = P;
  for (int v = 0; v < nv; ++v) Q[v] = x.segment<3>(3 * v);
  const int before = failures(mesh, lb, P);
  int after = failures(mesh, lb, Q);
  if (after <= before) std::swap(P, Q);  // never make it worse
  else after = before;
  core::logger().debug("deform: local untangling ({} rings, {} tets with {} ghosts, {} variables): {} -> {} failures",
                       rings, local.size(), ghost_start.size(), n, before, after);
  (void)ur;
  return after;
}

}  // namespace

DeformResult deform_to_polycube(const core::TetMesh& input, const std::vector<Tri>& boundary,
                                const std::vector<int>& labels, const DeformOptions& o,
                                const std::vector<Vec3>* initial) {
  const auto t_start = Clock::now();
  DeformResult res;
  res.mesh = input;
  core::TetMesh& mesh = res.mesh;
  core::check_indices(mesh);
  LabeledBoundary lb = match_boundary(mesh, boundary, labels);
  if (initial && initial->size() != mesh.points.size())
    throw core::InputError(fmt::format("deform: {} initial positions for {} vertices", initial->size(), mesh.points.size()));
  // Starting positions: the model, or the caller's (a pre-deformed model), refined alongside.
  std::vector<Vec3> start = initial ? *initial : std::vector<Vec3>{};
  std::vector<Vec3>* start_ptr = initial ? &start : nullptr;

  // 1–2. Charts, chart variables; split boundary triangles the constraints would flatten.
  ChartVars cv;
  for (int round = 0;; ++round) {
    cv = chart_variables(mesh.num_points(), lb.tris, lb.labels);
    const std::vector<std::array<int, 2>> chords = chord_edges(lb.tris, lb.labels, cv);
    const std::vector<int> flat = chords.empty() ? forced_flat_triangles(lb.tris, lb.labels, cv) : std::vector<int>{};
    const std::vector<std::array<int, 2>> fans = chords.empty() && flat.empty()
                                                     ? thin_fan_edges(mesh.num_points(), lb.tris, lb.labels, o.min_fan)
                                                     : std::vector<std::array<int, 2>>{};
    if (chords.empty() && flat.empty() && (fans.empty() || round >= 12)) break;
    if (!fans.empty()) {
      res.split_fan_edges += split_edges(mesh, lb, fans, start_ptr);
      lb = match_boundary(mesh, lb.tris, lb.labels);
      continue;
    }
    if (round >= 12) {
      std::vector<int> where;
      for (const auto& e : chords) where.insert(where.end(), e.begin(), e.end());
      for (int f : flat) where.insert(where.end(), lb.tris[f].begin(), lb.tris[f].end());
      throw UnrealizableLabeling(fmt::format("deform: {} boundary edges and {} triangles stay forced onto polycube "
                                             "edges by the labeling after splitting",
                                             chords.size(), flat.size()),
                                 std::move(where));
    }
    if (!chords.empty()) {
      res.split_edges += split_edges(mesh, lb, chords, start_ptr);
    } else {
      std::vector<char> touched(mesh.cells.size(), 0);
      for (int f : flat) res.split_triangles += split_boundary_triangle(mesh, lb, f, touched, start_ptr) ? 1 : 0;
    }
    LabeledBoundary refreshed = match_boundary(mesh, lb.tris, lb.labels);  // refresh owners
    lb = std::move(refreshed);
  }
  const int nv = mesh.num_points();
  const std::vector<Vec3>& X0 = initial ? start : mesh.points;
  // Two distinct vertices tied to the same chart coordinates on all three axes would coincide.
  {
    const auto et = core::unique_edges(mesh);
    for (const auto& e : et.edges) {
      bool same = true;
      for (int a = 0; a < 3 && same; ++a) {
        const int g = cv.vertex_group[3 * static_cast<std::size_t>(e[0]) + a];
        same = g >= 0 && g == cv.vertex_group[3 * static_cast<std::size_t>(e[1]) + a];
      }
      if (same)
        throw UnrealizableLabeling(fmt::format(
            "deform: the labeling forces vertices {} and {} (an edge) onto one polycube point: both are corners of the "
            "same three charts",
            e[0], e[1]), {e[0], e[1]});
    }
  }
  // Reduction: chart coordinates first (one per group), then every free coordinate.
  auto make_vars = [&](std::vector<int>& var) {
    var.assign(3 * static_cast<std::size_t>(mesh.num_points()), -1);
    int n = cv.num_groups;
    for (std::size_t i = 0; i < var.size(); ++i) var[i] = cv.vertex_group[i] >= 0 ? cv.vertex_group[i] : n++;
    return n;
  };
  std::vector<int> var;
  int nvar = make_vars(var);
  // Variables from positions X: free coordinates as they are, chart coordinates the mean of
  // their vertices' coordinates.
  Eigen::VectorXd y = Eigen::VectorXd::Zero(nvar);
  auto variables_from = [&](const std::vector<Vec3>& X) {
    y.setZero();
    std::vector<double> count(static_cast<std::size_t>(cv.num_groups), 0.0);
    for (int v = 0; v < nv; ++v)
      for (int d = 0; d < 3; ++d) {
        const int j = var[3 * static_cast<std::size_t>(v) + d];
        y[j] += X[v][d];
        if (j < cv.num_groups) count[j] += 1.0;
      }
    for (int j = 0; j < cv.num_groups; ++j) y[j] /= count[j];
  };
  variables_from(X0);
  const double ghost_h = ghost_height(mesh, lb, o.ghost_height);

  // 3. First polycube: the foldover-free planarity flow (planarity_flow.h), snapped onto exact
  //    chart planes; or as-rigid-as-possible least squares under the chart constraints:
  //    minimize sum_t w_t |J_t - R_t|² with R_t the rotation closest to the current J_t.
  if (o.flow) {
    const PlanarityFlowResult fr =
        planarity_flow(mesh, X0, cv.vertex_group, cv.num_groups, lb.tris, lb.labels, ghost_h, o.flow_options);
    variables_from(fr.points);
    res.flow_iterations = fr.iterations;
    res.flow_residual = fr.residual;
    std::vector<Vec3> snapped(static_cast<std::size_t>(nv));
    for (int v = 0; v < nv; ++v)
      for (int d = 0; d < 3; ++d) snapped[v][d] = y[var[3 * static_cast<std::size_t>(v) + d]];
    for (const auto& c : mesh.cells) res.inverted_after_linear += !core::positive_tet(snapped, c);
    core::logger().info("deform: planarity flow: {} iterations, plane residual {:.3g} edge lengths, {} inverted "
                        "({} tets inverted and {} boundary triangles facing away after the snap), {:.2f} s",
                        fr.iterations, fr.residual, fr.inverted, res.inverted_after_linear, facing_away(lb, snapped),
                        fr.seconds);
  } else if (o.arap_iterations > 0) {
    const solve::TetElements el = solve::reference_elements(mesh.points, mesh.cells);
    const solve::LinearReduction R = solve::index_reduction(var, nvar, Eigen::VectorXd::Zero(3 * nv));
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(el.tets.size() * 16 * 3 / 2 + nvar);
    for (int t = 0; t < el.size(); ++t) {
      const Eigen::Matrix4d L = el.weights[t] * el.gradients[t] * el.gradients[t].transpose();
      for (int d = 0; d < 3; ++d)
        for (int i = 0; i < 4; ++i)
          for (int j = 0; j < 4; ++j) {
            const int vi = var[3 * static_cast<std::size_t>(el.tets[t][i]) + d];
            const int vj = var[3 * static_cast<std::size_t>(el.tets[t][j]) + d];
            if (vi <= vj) trip.emplace_back(vi, vj, L(i, j));
          }
    }
    const double reg = solve::add_tiny_diagonal(trip, nvar);  // removes the translations' null space
    Eigen::SparseMatrix<double> A(nvar, nvar);
    A.setFromTriplets(trip.begin(), trip.end());
    A.makeCompressed();
    trip.clear();
    solve::SparseSpdSolver solver;
    if (!solver.factorize(A)) throw core::SolverError("deform: the least-squares system is not positive definite");
    Eigen::VectorXd x = R.apply(y);
    std::vector<Eigen::Matrix3d> rot(el.tets.size(), Eigen::Matrix3d::Identity());
    if (initial)  // the pre-deformation's rotations
      for (int t = 0; t < el.size(); ++t) {
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        for (int i = 0; i < 4; ++i) J += X0[el.tets[t][i]] * el.gradients[t].row(i);
        rot[t] = solve::closest_rotation(J);
      }
    for (int it = 0; it < o.arap_iterations; ++it) {
      if (it > 0)
        for (int t = 0; t < el.size(); ++t) {
          Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
          for (int i = 0; i < 4; ++i) J += x.segment<3>(3 * el.tets[t][i]) * el.gradients[t].row(i);
          rot[t] = solve::closest_rotation(J);
        }
      Eigen::VectorXd rhs = reg * y;
      for (int t = 0; t < el.size(); ++t) {
        // d/dx of w |X^T G - R|²: rhs_(i,d) += w (G R^T)_(i,d)
        const Eigen::Matrix<double, 4, 3> b = el.weights[t] * el.gradients[t] * rot[t].transpose();
        for (int i = 0; i < 4; ++i)
          for (int d = 0; d < 3; ++d) rhs[var[3 * static_cast<std::size_t>(el.tets[t][i]) + d]] += b(i, d);
      }
      y = solver.solve(rhs);
      x = R.apply(y);
    }
    for (int t = 0; t < el.size(); ++t) {
      Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
      for (int i = 0; i < 4; ++i) J += x.segment<3>(3 * el.tets[t][i]) * el.gradients[t].row(i);
      res.inverted_after_linear += J.determinant() <= 0;
    }
  }
  // Polycube positions (chart coordinates copied from their variable, hence exactly shared).
  std::vector<Vec3> P(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v)
    for (int d = 0; d < 3; ++d) P[v][d] = y[var[3 * static_cast<std::size_t>(v) + d]];
  res.seconds_linear = since(t_start);

  // 4. Untangle, then lower the distortion, keeping the chart constraints exactly. When some
  //    tets stay inverted, refine locally (split every edge of those tets) and start again
  //    from the current positions.
  const auto t_unt = Clock::now();
  solve::UntangleOptions uo;
  uo.max_iterations = o.max_iterations;
  uo.newton_steps = o.newton_steps;
  uo.volume_weight = o.volume_weight;
  // After the flow the map is almost untangled: a large ε would undo it (ε's rule raises it
  // again where a tet is still inverted).
  uo.initial_epsilon = o.flow ? o.flow_options.snap_epsilon : o.initial_epsilon;
  uo.tolerance = o.tolerance;
  uo.min_det_target = o.min_det;
  uo.stall_min_det_rise = o.stall_min_det_rise;
  bool retry_boundary_first = o.boundary_first && o.boundary_first_start && ghost_h > 0;
  int boundary_first_rounds = 0;
  for (int round = 0;; ++round) {
    nvar = make_vars(var);
    const int n_points = mesh.num_points();
    const solve::LinearReduction R = solve::index_reduction(var, nvar, Eigen::VectorXd::Zero(3 * n_points));
    y = Eigen::VectorXd::Zero(nvar);
    for (int v = 0; v < n_points; ++v)
      for (int d = 0; d < 3; ++d) y[var[3 * static_cast<std::size_t>(v) + d]] = P[v][d];
    const solve::TetElements el = solve::reference_elements(mesh.points, mesh.cells);
    // One elliptic optimization from P (with ghost tets unless disabled); P and y follow.
    auto optimize = [&] {
      if (o.ghost_height > 0) {
        const solve::UntangleResult r = untangle_with_ghosts(mesh, lb, cv.vertex_group, var, nvar, P, uo, ghost_h);
        for (int v = 0; v < n_points; ++v)
          for (int d = 0; d < 3; ++d) y[var[3 * static_cast<std::size_t>(v) + d]] = P[v][d];
        return r;
      }
      for (int v = 0; v < n_points; ++v)
        for (int d = 0; d < 3; ++d) y[var[3 * static_cast<std::size_t>(v) + d]] = P[v][d];
      const solve::UntangleResult r = solve::untangle(el, R, y, uo);
      for (int v = 0; v < n_points; ++v)
        for (int d = 0; d < 3; ++d) P[v][d] = y[var[3 * static_cast<std::size_t>(v) + d]];
      return r;
    };
    // Keep the first run's "before" figures and the last run's outcome.
    auto merge = [&](const solve::UntangleResult& r) {
      res.untangle.untangled = r.untangled;
      res.untangle.iterations += r.iterations;
      res.untangle.newton_steps += r.newton_steps;
      res.untangle.inverted_after = r.inverted_after;
      res.untangle.min_det = r.min_det;
      res.untangle.energy = r.energy;
      res.untangle.epsilon = r.epsilon;
    };
    // Edges of the tets with det J <= min det in P (to refine around them).
    auto inverted_tet_edges = [&] {
      std::vector<std::array<int, 2>> edges;
      for (int t = 0; t < el.size(); ++t) {
        const auto& c = el.tets[t];
        Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
        for (int i = 0; i < 4; ++i) J += P[c[i]] * el.gradients[t].row(i);
        if (J.determinant() > o.min_det) continue;
        for (const auto& e : core::kTetEdges) edges.push_back({std::min(c[e[0]], c[e[1]]), std::max(c[e[0]], c[e[1]])});
      }
      std::sort(edges.begin(), edges.end());
      edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
      return edges;
    };
    // The boundary first (boundary_first.h). A valid placement goes through the global
    // optimizer once more with the boundary free (from a valid state it stays valid; a tighter
    // tolerance, since the energy is dominated by the many good tets while the few bad ones
    // still improve); a placement that leaves a few tets inverted is refined around them and
    // placed again in the next round.
    enum class Placed { Valid, Retry, Failed };
    auto boundary_first_step = [&] {
      std::vector<Vec3> valid = P;
      const BoundaryFirstResult bf =
          place_boundary_first(mesh.points, mesh.cells, lb.tris, lb.labels, cv.vertex_group, valid, uo, ghost_h);
      core::logger().info("deform: boundary-first placement: {} chains; charts {} ({} facing away, {:.1f} s); volume "
                          "{} ({} inverted, {:.1f} s){}{}",
                          bf.chains, bf.chart_step.untangled ? "untangled" : "tangled", bf.charts_inverted,
                          bf.chart_step.seconds, bf.volume_step.untangled ? "untangled" : "tangled", bf.tets_inverted,
                          bf.volume_step.seconds, bf.valid ? "" : ": ", bf.reason);
      if (bf.valid) {
        P = valid;
        const solve::UntangleOptions keep = uo;
        uo.tolerance = o.tolerance * o.boundary_first_relax_tolerance;
        uo.max_iterations = std::min(o.max_iterations, o.boundary_first_relax_iterations);
        solve::UntangleResult r = optimize();  // the boundary free again
        uo = keep;
        if (!r.untangled || failures(mesh, lb, P) > 0) {
          P = valid;  // keep the valid placement
          r.untangled = true;
          r.inverted_after = 0;
        }
        merge(r);
        res.boundary_first = true;
        return Placed::Valid;
      }
      if (!bf.placement.empty() && boundary_first_rounds < o.boundary_first_refinements) {
        ++boundary_first_rounds;
        P = bf.placement;
        return Placed::Retry;
      }
      return Placed::Failed;
    };
    const bool use_boundary_first = o.boundary_first && ghost_h > 0;
    bool tried_boundary_first = false;
    if (retry_boundary_first || (round == 0 && use_boundary_first && o.boundary_first_start)) {
      tried_boundary_first = true;
      const Placed placed = boundary_first_step();
      if (placed == Placed::Valid) break;
      retry_boundary_first = placed == Placed::Retry;
    }
    if (!retry_boundary_first) {
      const solve::UntangleResult ur = optimize();
      if (round == 0 && !tried_boundary_first) res.untangle = ur;
      else merge(ur);
      if (ur.untangled) break;
      // A few tets left: untangle locally with a fresh ε, in growing regions, then go back
      // through the global optimizer (from a valid state it stays valid) to spread the
      // distortion, and take its verdict. First the plain local untangling; when it stays
      // stuck, place the chart fans that stayed flipped at concave corners on their long sweep
      // (corner_fans.h) and untangle around them.
      std::vector<int> seeds;
      for (int rings : {2, 4, 8}) {
        bool fixed = untangle_locally(mesh, lb, cv.vertex_group, P, rings, uo, ghost_h, seeds) == 0;
        if (!fixed && o.reopen_fans) {
          const int before = failures(mesh, lb, P);
          std::vector<Vec3> trial = P;
          const ReopenedFans rf = reopen_flipped_fans(lb.tris, lb.labels, trial);
          if (rf.fans > 0) {
            core::logger().debug("deform: {} flipped corner fans placed on their long sweep ({} vertices)", rf.fans,
                                 rf.vertices.size());
            res.reopened_fans += rf.fans;
            P.swap(trial);
            seeds.insert(seeds.end(), rf.vertices.begin(), rf.vertices.end());
            const int after = untangle_locally(mesh, lb, cv.vertex_group, P, rings, uo, ghost_h, seeds);
            if (after > before) P.swap(trial);  // compare with the state before the fans moved
            fixed = after == 0;
          }
        }
        if (fixed) {
          merge(optimize());
          break;
        }
      }
      if (res.untangle.untangled) break;
      if (use_boundary_first && !tried_boundary_first) {
        const Placed placed = boundary_first_step();
        if (placed == Placed::Valid) break;
        retry_boundary_first = placed == Placed::Retry;
      }
    }
    if (!retry_boundary_first && round >= o.refine_rounds) break;
    // Local refinement around the tets that stay inverted.
    const int split = split_edges(mesh, lb, inverted_tet_edges(), &P);
    res.refined_edges += split;
    core::logger().debug("deform: {} tets stay inverted; refinement round {} split {} edges",
                         res.untangle.inverted_after, round + 1, split);
    if (split == 0) break;
    lb = match_boundary(mesh, lb.tris, lb.labels);
    cv = chart_variables(mesh.num_points(), lb.tris, lb.labels);
  }
  res.seconds_untangle = since(t_unt);
  res.boundary = lb.tris;
  res.labels = lb.labels;
  res.triangle_chart = cv.tri_chart;
  res.num_charts = cv.num_charts;
  res.num_chart_variables = cv.num_groups;
  res.polycube = std::move(P);
  return res;
}

}  // namespace polycube::construct
