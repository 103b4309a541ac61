#include "simplify/fit.h"
#include "construct/boundary_first.h"
#include "core/log.h"

#include "core/errors.h"
#include "core/topology.h"
#include "solve/untangle.h"
#include "structure/validate.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>

#include <algorithm>
#include <array>
#include <chrono>
#include <map>
#include <set>
#include <string>

namespace polycube::simplify {

namespace {

using core::Vec3;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

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
  const auto t_place = Clock::now();
  const int nv = map.num_vertices();
  const double scale = al.scale;
  const CornerSystem& sys = al.system;
  PC_REQUIRE(al.corners.size() == s.corners.size(), "alignment does not match the structure");

  std::vector<Vec3> old_pos(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) old_pos[v] = scale * map.polycube[v];
  std::vector<Vec3> pos = old_pos;
  std::vector<std::array<char, 3>> fixed(static_cast<std::size_t>(nv), {0, 0, 0});

  // charts of every boundary vertex
  std::vector<std::vector<int>> vcharts(static_cast<std::size_t>(nv));
  for (std::size_t f = 0; f < s.triangles.size(); ++f)
    for (int v : s.triangles[f]) vcharts[v].push_back(s.triangle_chart[f]);
  for (auto& c : vcharts) {
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
  }
  // fixed coordinates: chart planes, corners
  for (int v = 0; v < nv; ++v)
    for (int p : vcharts[v]) {
      const int a = s.charts[p].axis;
      pos[v][a] = al.class_value[a][sys.axes[a].chart_class[p]];
      fixed[v][a] = 1;
    }
  for (std::size_t c = 0; c < s.corners.size(); ++c) {
    pos[s.corners[c].vertex] = al.corners[c];
    fixed[s.corners[c].vertex] = {1, 1, 1};
  }
  // chart vertices: the chart's monotone in-plane maps
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
  for (int v = 0; v < nv; ++v)
    if (vcharts[v].size() == 1 && s.vertex_corner[v] < 0) {
      const int p = vcharts[v][0];
      const int a = s.charts[p].axis;
      for (int k = 0; k < 2; ++k) pos[v][(a + 1 + k) % 3] = interpolate(from[p][k], to[p][k], old_pos[v][(a + 1 + k) % 3]);
    }
  // edge vertices: linear along the edge
  for (const auto& e : s.edges) {
    if (e.corners[0] < 0 || e.corners[1] < 0 || e.axis < 0) continue;
    const int a = e.axis;
    const double x0 = scale * s.corners[e.corners[0]].position[a], x1 = scale * s.corners[e.corners[1]].position[a];
    const double y0 = al.corners[e.corners[0]][a], y1 = al.corners[e.corners[1]][a];
    for (std::size_t k = 1; k + 1 < e.vertices.size(); ++k) {
      const int v = e.vertices[k];
      const double t = x1 != x0 ? (old_pos[v][a] - x0) / (x1 - x0) : 0.5;
      pos[v][a] = y0 + std::clamp(t, 0.0, 1.0) * (y1 - y0);
    }
  }
  // interior: harmonic extension of the boundary displacement (uniform graph Laplacian)
  std::vector<int> interior_index(static_cast<std::size_t>(nv), -1);
  int ni = 0;
  for (int v = 0; v < nv; ++v)
    if (vcharts[v].empty()) interior_index[v] = ni++;
  if (ni > 0) {
    std::set<std::pair<int, int>> edges;
    for (const auto& t : map.tets)
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) edges.insert({std::min(t[i], t[j]), std::max(t[i], t[j])});
    std::vector<Eigen::Triplet<double>> trip;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(ni, 3);
    for (const auto& [a, b] : edges) {
      const int ia = interior_index[a], ib = interior_index[b];
      for (auto [x, ix, y, iy] : {std::array<int, 4>{a, ia, b, ib}, std::array<int, 4>{b, ib, a, ia}}) {
        if (ix < 0) continue;
        trip.emplace_back(ix, ix, 1.0);
        if (iy >= 0) trip.emplace_back(ix, iy, -1.0);
        else rhs.row(ix) += (pos[y] - old_pos[y]).transpose();
        (void)x;
      }
    }
    Eigen::SparseMatrix<double> L(ni, ni);
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(L);
    if (ldlt.info() != Eigen::Success) throw core::SolverError("fit: harmonic extension factorization failed");
    const Eigen::MatrixXd d = ldlt.solve(rhs);
    for (int v = 0; v < nv; ++v)
      if (interior_index[v] >= 0) pos[v] = old_pos[v] + d.row(interior_index[v]).transpose();
  }
  FitResult res;
  res.inverted_initial = count_nonpositive(map.tets, pos);
  res.seconds_place = since(t_place);

  // untangle the free coordinates
  const auto t_unt = Clock::now();
  if (options.untangle) {
    // Ghost tets, one per boundary triangle: the triangle and a ghost vertex at height h above
    // its chart plane (that coordinate fixed, the two others free). A ghost tet is positive
    // exactly when its triangle faces its chart's direction, so the barrier also keeps the
    // boundary from folding over itself where every real tet is positive (such a fold would
    // split a chart and change the structure).
    const core::TetBoundary bnd = core::boundary(map.polycube_mesh());
    const auto nb = static_cast<int>(bnd.surface.cells.size());
    std::vector<core::Tri> btris(static_cast<std::size_t>(nb));
    std::vector<int> baxis(static_cast<std::size_t>(nb));
    std::vector<double> bsign(static_cast<std::size_t>(nb));
    double edge_sum = 0.0;
    for (int f = 0; f < nb; ++f) {
      for (int k = 0; k < 3; ++k) btris[f][k] = bnd.vertex_map[bnd.surface.cells[f][k]];
      const auto& t = btris[f];
      const Vec3 n = (map.polycube[t[1]] - map.polycube[t[0]]).cross(map.polycube[t[2]] - map.polycube[t[0]]);
      int a = 0;
      n.cwiseAbs().maxCoeff(&a);
      baxis[f] = a;
      bsign[f] = n[a] > 0 ? 1.0 : -1.0;
      for (int k = 0; k < 3; ++k) edge_sum += (map.polycube[t[(k + 1) % 3]] - map.polycube[t[k]]).norm();
    }
    const double h_ref = nb > 0 ? 0.5 * edge_sum / (3.0 * nb) : 0.0;  // input polycube units
    const int np = nv + nb;
    std::vector<int> var(static_cast<std::size_t>(3 * np), -1);
    Eigen::VectorXd fixed_value(3 * np);
    int nvar = 0;
    for (int v = 0; v < nv; ++v)
      for (int a = 0; a < 3; ++a) {
        fixed_value[3 * v + a] = pos[v][a];
        if (!fixed[v][a]) var[3 * v + a] = nvar++;
      }
    std::vector<Vec3> ref_points = map.polycube;
    std::vector<std::array<int, 4>> tets(map.tets.begin(), map.tets.end());
    Eigen::VectorXd y_ghost(2 * nb);
    int ng = 0;
    for (int f = 0; f < nb; ++f) {
      const auto& t = btris[f];
      const int a = baxis[f];
      const Vec3 c_ref = (map.polycube[t[0]] + map.polycube[t[1]] + map.polycube[t[2]]) / 3.0;
      Vec3 up = Vec3::Zero();
      up[a] = bsign[f];
      ref_points.push_back(c_ref + h_ref * up);
      tets.push_back({t[0], t[1], t[2], nv + f});
      const Vec3 c = (pos[t[0]] + pos[t[1]] + pos[t[2]]) / 3.0;
      for (int d = 0; d < 3; ++d) {
        const int i = 3 * (nv + f) + d;
        fixed_value[i] = d == a ? pos[t[0]][a] + bsign[f] * h_ref * scale : c[d];
        if (d != a) {
          var[i] = nvar++;
          y_ghost[ng++] = c[d];
        }
      }
    }
    const auto red = solve::index_reduction(var, nvar, fixed_value);
    Eigen::VectorXd y(nvar);
    for (int i = 0; i < 3 * nv; ++i)
      if (var[i] >= 0) y[var[i]] = pos[i / 3][i % 3];
    for (int i = 3 * nv, k = 0; i < 3 * np; ++i)
      if (var[i] >= 0) y[var[i]] = y_ghost[k++];
    const auto elements = solve::reference_elements(ref_points, tets, scale);
    solve::UntangleOptions uo;
    uo.max_iterations = options.max_iterations;
    const auto ur = solve::untangle(elements, red, y, uo);
    res.untangle_iterations = ur.iterations;
    const Eigen::VectorXd x = red.apply(y);
    for (int v = 0; v < nv; ++v) pos[v] = x.segment<3>(3 * v);
    if (options.boundary_first && count_nonpositive(map.tets, pos) > 0) {
      // The boundary first (construct/boundary_first.h): edge chains straight between their
      // (integer) corners, charts untangled in 2D, the interior with the boundary fixed; then
      // the free coordinates relax from that valid state (kept only if it stays valid).
      std::vector<int> group(3 * static_cast<std::size_t>(nv), -1);
      for (int v = 0; v < nv; ++v)
        for (int a = 0; a < 3; ++a)
          if (fixed[v][a]) group[3 * static_cast<std::size_t>(v) + a] = 0;
      std::vector<int> blabels(static_cast<std::size_t>(nb));
      for (int f = 0; f < nb; ++f) blabels[f] = 2 * baxis[f] + (bsign[f] > 0 ? 0 : 1);
      std::vector<core::Tet> real(map.tets.begin(), map.tets.end());
      std::vector<Vec3> placed = pos;
      const construct::BoundaryFirstResult bf =
          construct::place_boundary_first(old_pos, real, btris, blabels, group, placed, uo, h_ref * scale);
      core::logger().info("fit: {} tets stay inverted; boundary-first placement {}{}", count_nonpositive(map.tets, pos),
                          bf.valid ? "valid" : "failed: ", bf.reason);
      if (bf.valid) {
        for (int i = 0; i < 3 * nv; ++i)
          if (var[i] >= 0) y[var[i]] = placed[i / 3][i % 3];
        for (int f = 0; f < nb; ++f) {  // ghosts above their triangles' new centroids
          const auto& t = btris[f];
          const Vec3 c = (placed[t[0]] + placed[t[1]] + placed[t[2]]) / 3.0;
          for (int d = 0; d < 3; ++d)
            if (var[3 * (nv + f) + d] >= 0) y[var[3 * (nv + f) + d]] = c[d];
        }
        const auto relaxed = solve::untangle(elements, red, y, uo);
        res.untangle_iterations += relaxed.iterations;
        const Eigen::VectorXd xr = red.apply(y);
        std::vector<Vec3> trial(static_cast<std::size_t>(nv));
        for (int v = 0; v < nv; ++v) trial[v] = xr.segment<3>(3 * v);
        pos = count_nonpositive(map.tets, trial) == 0 ? trial : placed;
      }
    }
  }
  res.seconds_untangle = since(t_unt);

  // certify
  const auto t_cert = Clock::now();
  res.map.tets = map.tets;
  res.map.model = map.model;
  res.map.polycube = pos;
  const auto diag = structure::diagnose_map(res.map);
  res.inverted_final = diag.inverted_polycube + diag.flat_polycube;
  res.failures = diag.failures;
  {
    std::array<std::vector<double>, 3> values;
    for (int a = 0; a < 3; ++a) values[a].assign(al.class_value[a].begin(), al.class_value[a].end());
    for (auto& c : find_contacts(sys, s, values)) res.failures.push_back("aligned structure not embedded: " + c);
  }
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
  res.seconds_certify = since(t_cert);
  return res;
}

}  // namespace polycube::simplify
