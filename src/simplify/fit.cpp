#include "simplify/fit.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "mapping/boundary_first.h"
#include "mapping/ghost_tets.h"

#include "core/errors.h"
#include "core/topology.h"
#include "solve/untangle.h"
#include "structure/validate.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>

namespace polycube::simplify {

namespace {

using core::Vec3;

//! Piecewise-linear monotone map through (from[i], to[i]) (from sorted increasing), clamped.
double interpolate(const std::vector<double>& from, const std::vector<double>& to, double x) {
  if (from.empty()) return x;
  if (from.size() == 1 || x <= from.front()) return to.front() + (from.size() == 1 ? x - from.front() : 0.0);
  if (x >= from.back()) return to.back();
  const auto it = std::upper_bound(from.begin(), from.end(), x);
  const std::size_t i = static_cast<std::size_t>(it - from.begin()) - 1;
  const double t = (x - from[i]) / (from[i + 1] - from[i]);
  return to[i] + t * (to[i + 1] - to[i]);
}

int count_nonpositive(const std::vector<core::Tet>& tets, const std::vector<Vec3>& p) {
  int n = 0;
  for (const auto& t : tets)
    if ((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) <= 0.0) ++n;
  return n;
}


//! The initial placement of the fit: positions in lattice units and which coordinates are fixed.
struct Placement {
  std::vector<Vec3> old_pos;                  //!< the input polycube, scaled to lattice units
  std::vector<Vec3> pos;                      //!< the placement
  std::vector<std::array<char, 3>> fixed;     //!< coordinates on a chart plane (all three at corners)
  std::vector<std::vector<int>> vertex_charts;  //!< charts of every boundary vertex (sorted)
};

//! Chart planes and corners: the fixed coordinates.
void place_fixed_coordinates(const structure::PolycubeStructure& s, const AlignResult& al, Placement& pl) {
  const CornerSystem& sys = al.system;
  const int nv = static_cast<int>(pl.pos.size());
  pl.vertex_charts.assign(static_cast<std::size_t>(nv), {});
  for (std::size_t f = 0; f < s.triangles.size(); ++f)
    for (int v : s.triangles[f]) pl.vertex_charts[v].push_back(s.triangle_chart[f]);
  for (auto& c : pl.vertex_charts) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  pl.fixed.assign(static_cast<std::size_t>(nv), {0, 0, 0});
  for (int v = 0; v < nv; ++v)
    for (int p : pl.vertex_charts[v]) {
      const int a = s.charts[p].axis;
      pl.pos[v][a] = al.class_value[a][sys.axes[a].chart_class[p]];
      pl.fixed[v][a] = 1;
    }
  for (std::size_t c = 0; c < s.corners.size(); ++c) {
    pl.pos[s.corners[c].vertex] = al.corners[c];
    pl.fixed[s.corners[c].vertex] = {1, 1, 1};
  }
}

//! Chart vertices: the chart's monotone in-plane maps through its corners' old and new
//! coordinates.
void place_chart_vertices(const structure::PolycubeStructure& s, const AlignResult& al, Placement& pl) {
  const CornerSystem& sys = al.system;
  std::vector<std::array<std::vector<double>, 2>> from(s.charts.size()), to(s.charts.size());
  for (std::size_t p = 0; p < s.charts.size(); ++p) {
    const int a = s.charts[p].axis;
    std::vector<int> cs;
    for (const auto& l : s.faces[p].loops) cs.insert(cs.end(), l.corners.begin(), l.corners.end());
    for (int k = 0; k < 2; ++k) {
      const int u = (a + 1 + k) % 3;
      std::vector<int> lv;
      for (int c : cs) lv.push_back(sys.axes[u].corner_class[c]);
      std::sort(lv.begin(), lv.end());
      lv.erase(std::unique(lv.begin(), lv.end()), lv.end());
      for (int cls : lv) {
        from[p][k].push_back(sys.axes[u].coordinate[cls]);
        to[p][k].push_back(al.class_value[u][cls]);
      }
    }
  }
  for (std::size_t v = 0; v < pl.pos.size(); ++v)
    if (pl.vertex_charts[v].size() == 1 && s.vertex_corner[v] < 0) {
      const int p = pl.vertex_charts[v][0];
      const int a = s.charts[p].axis;
      for (int k = 0; k < 2; ++k)
        pl.pos[v][(a + 1 + k) % 3] = interpolate(from[p][k], to[p][k], pl.old_pos[v][(a + 1 + k) % 3]);
    }
}

//! Edge vertices: linear along the edge between its corners.
void place_edge_vertices(const structure::PolycubeStructure& s, const AlignResult& al, double scale, Placement& pl) {
  for (const auto& e : s.edges) {
    if (e.corners[0] < 0 || e.corners[1] < 0 || e.axis < 0) continue;
    const int a = e.axis;
    const double x0 = scale * s.corners[e.corners[0]].position[a], x1 = scale * s.corners[e.corners[1]].position[a];
    const double y0 = al.corners[e.corners[0]][a], y1 = al.corners[e.corners[1]][a];
    for (std::size_t k = 1; k + 1 < e.vertices.size(); ++k) {
      const int v = e.vertices[k];
      const double t = x1 != x0 ? (pl.old_pos[v][a] - x0) / (x1 - x0) : 0.5;
      pl.pos[v][a] = y0 + std::clamp(t, 0.0, 1.0) * (y1 - y0);
    }
  }
}

//! Interior vertices: harmonic extension of the boundary displacement (uniform graph Laplacian).
void place_interior(const core::PolycubeMap& map, Placement& pl) {
  const int nv = static_cast<int>(pl.pos.size());
  std::vector<int> interior_index(static_cast<std::size_t>(nv), -1);
  int ni = 0;
  for (int v = 0; v < nv; ++v)
    if (pl.vertex_charts[v].empty()) interior_index[v] = ni++;
  if (ni == 0) return;
  std::set<std::pair<int, int>> edges;
  for (const auto& t : map.tets)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) edges.insert({std::min(t[i], t[j]), std::max(t[i], t[j])});
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(ni, 3);
  for (const auto& [a, b] : edges) {
    const int ia = interior_index[a], ib = interior_index[b];
    for (auto [ix, y, iy] : {std::array<int, 3>{ia, b, ib}, std::array<int, 3>{ib, a, ia}}) {
      if (ix < 0) continue;
      trip.emplace_back(ix, ix, 1.0);
      if (iy >= 0) trip.emplace_back(ix, iy, -1.0);
      else rhs.row(ix) += (pl.pos[y] - pl.old_pos[y]).transpose();
    }
  }
  Eigen::SparseMatrix<double> L(ni, ni);
  L.setFromTriplets(trip.begin(), trip.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(L);
  if (ldlt.info() != Eigen::Success) throw core::SolverError("fit: harmonic extension factorization failed");
  const Eigen::MatrixXd d = ldlt.solve(rhs);
  for (int v = 0; v < nv; ++v)
    if (interior_index[v] >= 0) pl.pos[v] = pl.old_pos[v] + d.row(interior_index[v]).transpose();
}

Placement initial_placement(const core::PolycubeMap& map, const structure::PolycubeStructure& s, const AlignResult& al) {
  Placement pl;
  pl.old_pos.resize(map.polycube.size());
  for (std::size_t v = 0; v < map.polycube.size(); ++v) pl.old_pos[v] = al.scale * map.polycube[v];
  pl.pos = pl.old_pos;
  place_fixed_coordinates(s, al, pl);
  place_chart_vertices(s, al, pl);
  place_edge_vertices(s, al, al.scale, pl);
  place_interior(map, pl);
  return pl;
}

//! The input polycube's boundary as labeled triangles (label = the dominant axis of the
//! triangle's polycube normal) and the ghost height: half the mean boundary edge length in
//! input polycube units.
struct FitBoundary {
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  double h = 0.0;
};

FitBoundary fit_boundary(const core::PolycubeMap& map) {
  FitBoundary b;
  b.tris = core::boundary_triangles(core::boundary(map.polycube_mesh()));
  const auto nb = static_cast<int>(b.tris.size());
  b.labels.resize(b.tris.size());
  double edge_sum = 0.0;
  for (int f = 0; f < nb; ++f) {
    const auto& t = b.tris[f];
    const Vec3 n = (map.polycube[t[1]] - map.polycube[t[0]]).cross(map.polycube[t[2]] - map.polycube[t[0]]);
    int a = 0;
    n.cwiseAbs().maxCoeff(&a);
    b.labels[f] = 2 * a + (n[a] > 0 ? 0 : 1);
    for (int k = 0; k < 3; ++k) edge_sum += (map.polycube[t[(k + 1) % 3]] - map.polycube[t[k]]).norm();
  }
  b.h = nb > 0 ? 0.5 * edge_sum / (3.0 * nb) : 0.0;
  return b;
}

//! The untangling problem of the fit: the free coordinates, and one ghost tet per boundary
//! triangle (mapping/ghost_tets.h) with its label-axis coordinate fixed at h above the chart
//! plane and the two others free. The reference shape of every tet is its scaled input
//! polycube shape.
struct FitProblem {
  solve::TetElements elements;
  solve::LinearReduction reduction;
  std::vector<int> var;  //!< 3(#V + #B) variable of each coordinate, −1 when fixed
  int nv = 0;
};

FitProblem fit_problem(const core::PolycubeMap& map, const FitBoundary& b, const Placement& pl, double scale) {
  FitProblem fp;
  const int nv = map.num_vertices();
  const int nb = static_cast<int>(b.tris.size());
  const int np = nv + nb;
  fp.nv = nv;
  fp.var.assign(static_cast<std::size_t>(3 * np), -1);
  Eigen::VectorXd fixed_value(3 * np);
  int nvar = 0;
  for (int v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) {
      fixed_value[3 * v + a] = pl.pos[v][a];
      if (!pl.fixed[v][a]) fp.var[3 * v + a] = nvar++;
    }
  const mapping::GhostTets ghosts =
      mapping::ghost_tets(map.polycube, b.tris, b.labels, b.h, nv, mapping::GhostBase::Centroid,
                          mapping::GhostDirection::Label);
  std::vector<Vec3> ref_points = map.polycube;
  ref_points.insert(ref_points.end(), ghosts.reference.begin(), ghosts.reference.end());
  std::vector<std::array<int, 4>> tets(map.tets.begin(), map.tets.end());
  tets.insert(tets.end(), ghosts.tets.begin(), ghosts.tets.end());
  for (int f = 0; f < nb; ++f) {
    const Vec3 apex = mapping::ghost_apex(pl.pos, b.tris[f], b.labels[f], b.h * scale);
    for (int d = 0; d < 3; ++d) {
      const int i = 3 * (nv + f) + d;
      fixed_value[i] = apex[d];
      if (d != core::label_axis(b.labels[f])) fp.var[i] = nvar++;
    }
  }
  fp.reduction = solve::index_reduction(fp.var, nvar, fixed_value);
  fp.elements = solve::reference_elements(ref_points, tets, scale);
  return fp;
}

//! Variables from real positions P, each ghost above its triangle's centroid in P.
Eigen::VectorXd fit_variables(const FitProblem& fp, const FitBoundary& b, const std::vector<Vec3>& P) {
  Eigen::VectorXd y(fp.reduction.B.cols());
  for (int i = 0; i < 3 * fp.nv; ++i)
    if (fp.var[i] >= 0) y[fp.var[i]] = P[i / 3][i % 3];
  for (std::size_t f = 0; f < b.tris.size(); ++f) {
    const auto& t = b.tris[f];
    const Vec3 c = (P[t[0]] + P[t[1]] + P[t[2]]) / 3.0;
    for (int d = 0; d < 3; ++d) {
      const int i = 3 * (fp.nv + static_cast<int>(f)) + d;
      if (fp.var[i] >= 0) y[fp.var[i]] = c[d];
    }
  }
  return y;
}

//! One untangling of the fit problem from P; returns the real positions.
std::vector<Vec3> untangle_fit(const FitProblem& fp, const FitBoundary& b, const std::vector<Vec3>& P,
                               const solve::UntangleOptions& uo, int& iterations) {
  Eigen::VectorXd y = fit_variables(fp, b, P);
  const auto ur = solve::untangle(fp.elements, fp.reduction, y, uo);
  iterations += ur.iterations;
  const Eigen::VectorXd x = fp.reduction.apply(y);
  std::vector<Vec3> out(static_cast<std::size_t>(fp.nv));
  for (int v = 0; v < fp.nv; ++v) out[v] = x.segment<3>(3 * v);
  return out;
}

//! The boundary first (mapping/boundary_first.h): edge chains straight between their
//! (integer) corners, charts untangled in 2D, the interior with the boundary fixed; then the
//! free coordinates relax from that valid state (kept only if it stays valid).
void fit_boundary_first(const core::PolycubeMap& map, const FitBoundary& b, const FitProblem& fp, const Placement& pl,
                        double scale, const solve::UntangleOptions& uo, std::vector<Vec3>& pos, FitResult& res) {
  const int nv = fp.nv;
  std::vector<int> group(3 * static_cast<std::size_t>(nv), -1);
  for (int v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a)
      if (pl.fixed[v][a]) group[3 * static_cast<std::size_t>(v) + a] = 0;
  std::vector<core::Tet> real(map.tets.begin(), map.tets.end());
  std::vector<Vec3> placed = pos;
  const mapping::BoundaryFirstResult bf =
      mapping::place_boundary_first(pl.old_pos, real, b.tris, b.labels, group, placed, uo, b.h * scale,
                                    mapping::kFastPlacementSigma);
  core::logger().info("fit: {} tets stay inverted; boundary-first placement {}{}", count_nonpositive(map.tets, pos),
                      bf.valid ? "valid" : "failed: ", bf.reason);
  if (!bf.valid) return;
  const std::vector<Vec3> trial = untangle_fit(fp, b, placed, uo, res.untangle_iterations);
  pos = count_nonpositive(map.tets, trial) == 0 ? trial : placed;
}

//! Certify the fitted map: valid (exact predicates), the aligned structure embedded like the
//! input's, the same structure with every corner on its integer position.
void certify_fit(const core::PolycubeMap& map, const structure::PolycubeStructure& s, const AlignResult& al,
                 std::vector<Vec3> pos, FitResult& res) {
  res.map.tets = map.tets;
  res.map.model = map.model;
  res.map.polycube = std::move(pos);
  const auto diag = structure::diagnose_map(res.map);
  res.inverted_final = diag.inverted_polycube + diag.flat_polycube;
  res.failures = diag.failures;
  std::array<std::vector<double>, 3> values;
  for (int a = 0; a < 3; ++a) values[a].assign(al.class_value[a].begin(), al.class_value[a].end());
  for (auto& c : find_contacts(al.system, s, values)) res.failures.push_back("aligned structure not embedded: " + c);
  if (diag.valid()) {
    const auto after = structure::extract_structure(res.map);
    for (auto& d : compare_structures(s, after)) res.failures.push_back("structure changed: " + d);
    for (std::size_t c = 0; c < after.corners.size() && c < al.corners.size(); ++c)
      if ((after.corners[c].position - al.corners[c]).cwiseAbs().maxCoeff() != 0.0) {
        res.failures.push_back("corner " + std::to_string(c) + " is not at its aligned integer position");
        break;
      }
  }
  res.certified = res.failures.empty();
}

}  // namespace

std::vector<std::string> compare_structures(const structure::PolycubeStructure& a, const structure::PolycubeStructure& b) {
  std::vector<std::string> diff;
  if (a.corners.size() != b.corners.size())
    diff.push_back("corners " + std::to_string(a.corners.size()) + " -> " + std::to_string(b.corners.size()));
  if (a.edges.size() != b.edges.size())
    diff.push_back("edges " + std::to_string(a.edges.size()) + " -> " + std::to_string(b.edges.size()));
  if (a.charts.size() != b.charts.size())
    diff.push_back("charts " + std::to_string(a.charts.size()) + " -> " + std::to_string(b.charts.size()));
  if (!diff.empty()) return diff;
  for (std::size_t c = 0; c < a.corners.size(); ++c)
    if (a.corners[c].vertex != b.corners[c].vertex) {
      diff.push_back("corner " + std::to_string(c) + " is a different vertex");
      return diff;
    }
  auto edge_key = [](const structure::Edge& e) {
    return std::array<int, 4>{std::min(e.corners[0], e.corners[1]), std::max(e.corners[0], e.corners[1]), e.axis, e.convex ? 1 : 0};
  };
  std::multiset<std::array<int, 4>> ea, eb;
  for (const auto& e : a.edges) ea.insert(edge_key(e));
  for (const auto& e : b.edges) eb.insert(edge_key(e));
  if (ea != eb) diff.push_back("polycube edges differ (end corners, axis or convexity)");
  auto chart_keys = [](const structure::PolycubeStructure& s) {
    std::multiset<std::vector<int>> keys;
    for (std::size_t p = 0; p < s.charts.size(); ++p) {
      std::vector<int> k{s.charts[p].label, s.faces[p].num_holes()};
      std::vector<int> cs;
      for (const auto& l : s.faces[p].loops) cs.insert(cs.end(), l.corners.begin(), l.corners.end());
      std::sort(cs.begin(), cs.end());
      k.insert(k.end(), cs.begin(), cs.end());
      keys.insert(k);
    }
    return keys;
  };
  if (chart_keys(a) != chart_keys(b)) diff.push_back("charts differ (label, holes or corners)");
  return diff;
}

FitResult fit_polycube(const core::PolycubeMap& map, const structure::PolycubeStructure& s, const AlignResult& al,
                       const FitOptions& options) {
  core::check_map_indices(map);
  PC_REQUIRE(al.corners.size() == s.corners.size(), "alignment does not match the structure");
  FitResult res;
  core::Stopwatch clock;
  const Placement pl = initial_placement(map, s, al);
  std::vector<Vec3> pos = pl.pos;
  res.inverted_initial = count_nonpositive(map.tets, pos);
  res.seconds_place = clock.seconds();

  // Untangle the free coordinates; the boundary first when tets stay inverted.
  clock.restart();
  if (options.untangle) {
    const FitBoundary b = fit_boundary(map);
    const FitProblem fp = fit_problem(map, b, pl, al.scale);
    const solve::UntangleOptions& uo = options.untangling;
    pos = untangle_fit(fp, b, pos, uo, res.untangle_iterations);
    if (options.boundary_first && count_nonpositive(map.tets, pos) > 0)
      fit_boundary_first(map, b, fp, pl, al.scale, uo, pos, res);
  }
  res.seconds_untangle = clock.seconds();

  clock.restart();
  certify_fit(map, s, al, std::move(pos), res);
  res.seconds_certify = clock.seconds();
  return res;
}

}  // namespace polycube::simplify
