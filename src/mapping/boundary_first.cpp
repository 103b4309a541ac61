//! Boundary-first placement of a polycube map (see boundary_first.h).
#include "mapping/boundary_first.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/polycube_map.h"
#include "mapping/ghost_tets.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <map>
#include <optional>

namespace polycube::mapping {

namespace {

using core::Tri;
using core::Vec3;

int axes_mask(const std::vector<int>& vertex_group, int v) {
  int m = 0;
  for (int d = 0; d < 3; ++d) m |= vertex_group[3 * static_cast<std::size_t>(v) + d] >= 0 ? 1 << d : 0;
  return m;
}

//! A chain of boundary vertices along a polycube edge, from corner to corner.
struct Chain {
  std::vector<int> vertices;
  int axis = -1;  //!< the axis the edge runs along
};

//! Every chain of boundary vertices along a polycube edge (boundary edges between two charts),
//! or nothing with `reason` set.
std::optional<std::vector<Chain>> find_chains(const std::vector<Tri>& tris, const std::vector<int>& labels,
                                              const std::vector<int>& vertex_group, std::string& reason) {
  std::map<std::pair<int, int>, std::array<int, 2>> edge_tris;  // edge -> (label, label)
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int a = tris[f][e], b = tris[f][(e + 1) % 3];
      auto [it, fresh] = edge_tris.try_emplace({std::min(a, b), std::max(a, b)}, std::array<int, 2>{labels[f], -1});
      if (!fresh) it->second[1] = labels[f];
    }
  std::map<int, std::vector<int>> feature;  // vertex -> neighbours along polycube edges
  std::map<std::pair<int, int>, int> edge_axis;
  for (const auto& [e, l] : edge_tris) {
    if (l[1] < 0) {
      reason = "the boundary is not closed";
      return std::nullopt;
    }
    if (l[0] == l[1]) continue;
    if (l[0] / 2 == l[1] / 2) {
      reason = fmt::format("charts {} and {} of one axis share an edge", core::label_name(l[0]), core::label_name(l[1]));
      return std::nullopt;
    }
    feature[e.first].push_back(e.second);
    feature[e.second].push_back(e.first);
    edge_axis[e] = 3 - l[0] / 2 - l[1] / 2;
  }
  std::map<std::pair<int, int>, bool> done;
  std::vector<Chain> chains;
  std::size_t walked = 0;
  for (const auto& [corner, nbrs] : feature) {
    if (axes_mask(vertex_group, corner) != 7) continue;
    for (int first : nbrs) {
      if (done[{std::min(corner, first), std::max(corner, first)}]) continue;
      Chain chain{{corner}, edge_axis[{std::min(corner, first), std::max(corner, first)}]};
      int prev = corner, cur = first;
      while (true) {
        done[{std::min(prev, cur), std::max(prev, cur)}] = true;
        ++walked;
        chain.vertices.push_back(cur);
        if (axes_mask(vertex_group, cur) == 7) break;
        const std::vector<int>& around = feature[cur];
        if (around.size() != 2) {
          reason = fmt::format("vertex {} on a polycube edge has {} polycube-edge neighbours", cur, around.size());
          return std::nullopt;
        }
        const int next = around[0] == prev ? around[1] : around[0];
        prev = cur;
        cur = next;
      }
      const int mask = 7 & ~(1 << chain.axis);
      for (std::size_t k = 1; k + 1 < chain.vertices.size(); ++k)
        if (axes_mask(vertex_group, chain.vertices[k]) != mask) {
          reason = fmt::format("vertex {} of a polycube edge is not on exactly two charts' planes", chain.vertices[k]);
          return std::nullopt;
        }
      chains.push_back(std::move(chain));
    }
  }
  std::size_t half_edges = 0;
  for (const auto& [v, nb] : feature) half_edges += nb.size();
  if (2 * walked != half_edges) {
    reason = "a polycube edge loop has no corner";
    return std::nullopt;
  }
  return chains;
}

//! A polycube edge shorter than this fraction of its length in the model is lengthened by step 0.
constexpr double kShortEdge = 0.1;

//! Step 0: a polycube edge that runs the other way than its chain does in the model (the
//! deformation put one corner's chart plane beyond the other's) makes the faces along it wind
//! the wrong way round or cross their neighbours, and no 2D or volume map can place them. Each
//! edge's coordinate along its axis is the difference of its two end corners' chart planes, so
//! the directions are difference constraints on the planes: x_end − x_start ≥ δ, with the
//! model's sign. Every reversed edge asks for a quarter of its length in the model, and so does
//! an edge squeezed below kShortEdge of it: the faces along such an edge are slivers, and the
//! tets between its two close chart planes end up flat (inverted by rounding) in the volume
//! step. Every other edge keeps at least what it has or a quarter, whichever is less, so the
//! planes move only as far as those edges need. Solved by cyclic projection (each violated
//! constraint moves its two planes apart by halves), which converges when the constraints can
//! be met; the planes are left as they were when they cannot. Returns the edges reversed.
int orient_chains(const std::vector<Vec3>& points, const std::vector<Chain>& chains,
                  const std::vector<int>& vertex_group, std::vector<Vec3>& P) {
  struct Constraint {
    int from, to;  // (vertex, axis) slots whose groups hold the two planes
    double delta;  // x_to − x_from ≥ delta
  };
  std::vector<Constraint> rows;
  int reversed = 0, squeezed = 0;
  for (const Chain& c : chains) {
    const int a = c.vertices.front(), b = c.vertices.back(), e = c.axis;
    const double model = points[b][e] - points[a][e];
    if (model == 0.0) continue;
    const double sign = model > 0 ? 1.0 : -1.0;
    const double along = sign * (P[b][e] - P[a][e]);
    const double delta = 0.25 * std::abs(model);
    reversed += along <= 0.0;
    const bool too_short = along < kShortEdge * std::abs(model);
    squeezed += too_short && along > 0.0;
    const int from = 3 * (sign > 0 ? a : b) + e, to = 3 * (sign > 0 ? b : a) + e;
    rows.push_back({from, to, too_short ? delta : std::min(along, delta)});
  }
  if (reversed == 0 && squeezed == 0) return 0;
  std::map<int, double> plane;  // group -> coordinate
  for (const Constraint& r : rows)
    for (const int slot : {r.from, r.to}) plane[vertex_group[slot]] = P[slot / 3][slot % 3];
  constexpr int kSweeps = 10000;
  bool met = false;
  for (int sweep = 0; sweep < kSweeps && !met; ++sweep) {
    met = true;
    for (const Constraint& r : rows) {
      double& x0 = plane[vertex_group[r.from]];
      double& x1 = plane[vertex_group[r.to]];
      const double short_by = r.delta - (x1 - x0);
      if (short_by <= 1e-12 * std::abs(r.delta)) continue;
      met = false;
      x0 -= 0.5 * short_by;
      x1 += 0.5 * short_by;
    }
  }
  core::logger().debug("boundary first: {} of {} polycube edges reversed, {} squeezed; their planes {}", reversed,
                       rows.size(), squeezed,
                       met ? "moved into the model's order" : "cannot be put in the model's order: left as they were");
  if (!met) return reversed;
  for (std::size_t v = 0; v < P.size(); ++v)
    for (int d = 0; d < 3; ++d) {
      const auto it = plane.find(vertex_group[3 * v + d]);
      if (vertex_group[3 * v + d] >= 0 && it != plane.end()) P[v][d] = it->second;
    }
  return reversed;
}

//! Step 1: every chain onto the segment between its end corners, at the model's arc-length
//! fractions. Returns false with `reason` set on a zero-length edge.
bool place_chains(const std::vector<Vec3>& points, const std::vector<Chain>& chains, std::vector<Vec3>& P,
                  std::string& reason) {
  for (const Chain& c : chains) {
    const std::vector<int>& chain = c.vertices;
    const int e = c.axis;
    if (chain.size() < 3) continue;
    const double pa = P[chain.front()][e], pb = P[chain.back()][e];
    if (!(std::abs(pb - pa) > 0)) {
      reason = fmt::format("polycube edge between corners {} and {} has zero length", chain.front(), chain.back());
      return false;
    }
    std::vector<double> s(chain.size(), 0.0);
    for (std::size_t k = 1; k < chain.size(); ++k) s[k] = s[k - 1] + (points[chain[k]] - points[chain[k - 1]]).norm();
    for (std::size_t k = 1; k + 1 < chain.size(); ++k) P[chain[k]][e] = pa + (pb - pa) * (s[k] / s.back());
  }
  return true;
}

solve::UntangleOptions fixed_boundary_options(const solve::UntangleOptions& base) {
  solve::UntangleOptions uo = base;
  uo.initial_epsilon = 1.0;  // the fixed boundary keeps the mesh from shrinking
  uo.attractions.clear();
  uo.on_iteration = nullptr;
  return uo;
}

//! Step 2: each chart inside its fixed rectilinear polygon by a fixed-boundary 2D untangling:
//! the in-plane coordinates of chart-interior vertices are free; each triangle is lifted to a
//! tet whose apex has its first vertex's in-plane coordinates and lies at h above the chart
//! plane. Returns false with res.reason set when a chart triangle stays facing away.
bool place_charts(const std::vector<Vec3>& points, const std::vector<Tri>& tris, const std::vector<int>& labels,
                  const std::vector<int>& vertex_group, const std::vector<char>& on_boundary, double h,
                  const solve::UntangleOptions& base, std::vector<Vec3>& Q, BoundaryFirstResult& res) {
  const int nv = static_cast<int>(points.size());
  const int nb = static_cast<int>(tris.size());
  std::vector<int> var(3 * static_cast<std::size_t>(nv + nb), -1);
  Eigen::VectorXd fixed(3 * (nv + nb));
  int n = 0;
  for (int v = 0; v < nv; ++v) {
    const int mask = on_boundary[v] ? axes_mask(vertex_group, v) : 7;
    for (int d = 0; d < 3; ++d) {
      fixed[3 * v + d] = Q[v][d];
      if (mask == (mask & -mask) && !(mask & (1 << d))) var[3 * static_cast<std::size_t>(v) + d] = n++;
    }
  }
  const GhostTets lifted = ghost_tets(points, tris, labels, h, nv, GhostBase::FirstVertex);
  std::vector<Vec3> ref = points;
  ref.insert(ref.end(), lifted.reference.begin(), lifted.reference.end());
  for (int f = 0; f < nb; ++f) {
    const Tri& t = tris[f];
    const int a = labels[f] / 2;
    const Vec3 apex = ghost_apex(Q, t, labels[f], h, GhostBase::FirstVertex);
    for (int d = 0; d < 3; ++d) {
      const std::size_t row = 3 * static_cast<std::size_t>(nv + f) + d;
      fixed[static_cast<Eigen::Index>(row)] = apex[d];
      if (d != a) var[row] = var[3 * static_cast<std::size_t>(t[0]) + d];
    }
    bool locked = true;
    for (int v : t) locked = locked && axes_mask(vertex_group, v) != (1 << a);
    if (locked && !core::faces_label(Q, t, labels[f])) {
      ++res.locked_inverted;
      res.locked_triangles.push_back(f);
    }
  }
  if (res.locked_inverted > 0) {
    res.reason = fmt::format("{} chart triangles with all vertices on polycube edges face away", res.locked_inverted);
    return false;
  }
  const solve::LinearReduction R = solve::index_reduction(var, n, fixed);
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < 3 * static_cast<std::size_t>(nv); ++i)
    if (var[i] >= 0) y[var[i]] = Q[i / 3][i % 3];
  res.chart_step = solve::untangle(solve::reference_elements(ref, lifted.tets), R, y, fixed_boundary_options(base));
  const Eigen::VectorXd x = R.apply(y);
  for (int v = 0; v < nv; ++v)
    if (on_boundary[v]) Q[v] = x.segment<3>(3 * v);
  for (int f = 0; f < nb; ++f) res.charts_inverted += !core::faces_label(Q, tris[f], labels[f]);
  if (res.charts_inverted > 0) {
    res.reason = fmt::format("{} chart triangles face away after the 2D untangling", res.charts_inverted);
    return false;
  }
  return true;
}

//! Step 3: the interior untangled with the whole boundary fixed. Returns false with
//! res.reason set (and res.placement when only tets stay inverted) on failure.
bool place_volume(const std::vector<Vec3>& points, const std::vector<core::Tet>& tets,
                  const std::vector<int>& vertex_group, const std::vector<char>& on_boundary,
                  const solve::UntangleOptions& base, double fast_sigma, std::vector<Vec3>& Q,
                  BoundaryFirstResult& res) {
  const int nv = static_cast<int>(points.size());
  std::vector<int> var(3 * static_cast<std::size_t>(nv), -1);
  int n = 0;
  for (int v = 0; v < nv; ++v)
    if (!on_boundary[v])
      for (int d = 0; d < 3; ++d) var[3 * static_cast<std::size_t>(v) + d] = n++;
  for (const auto& c : tets)
    if (on_boundary[c[0]] && on_boundary[c[1]] && on_boundary[c[2]] && on_boundary[c[3]] && !core::positive_tet(Q, c))
      ++res.locked_inverted;
  if (res.locked_inverted > 0) {
    res.reason = fmt::format("{} tets with all vertices on the boundary are inverted", res.locked_inverted);
    return false;
  }
  const solve::LinearReduction R = solve::index_reduction(var, n, solve::flatten(Q));
  Eigen::VectorXd y(n);
  for (std::size_t i = 0; i < var.size(); ++i)
    if (var[i] >= 0) y[var[i]] = Q[i / 3][i % 3];
  res.volume_step = solve::untangle_fast_first(solve::reference_elements(points, tets), R, y,
                                               fixed_boundary_options(base), fast_sigma);
  const Eigen::VectorXd x = R.apply(y);
  for (int v = 0; v < nv; ++v)
    if (!on_boundary[v]) Q[v] = x.segment<3>(3 * v);
  for (const auto& c : tets) {
    if (core::positive_tet(Q, c)) continue;
    ++res.tets_inverted;
    if (res.tets_inverted <= 10) {
      int nb_v = 0;
      std::string masks;
      for (int v : c) {
        nb_v += on_boundary[v];
        masks += fmt::format(" {}:{}", v, on_boundary[v] ? axes_mask(vertex_group, v) : 0);
      }
      const double vol = (Q[c[1]] - Q[c[0]]).dot((Q[c[2]] - Q[c[0]]).cross(Q[c[3]] - Q[c[0]])) / 6.0;
      core::logger().debug("boundary first: tet inverted, volume {:.3g}, {} boundary vertices (vertex:axes{})", vol,
                           nb_v, masks);
    }
  }
  if (res.tets_inverted > 0) {
    res.reason = fmt::format("{} tets stay inverted after the volume untangling", res.tets_inverted);
    res.placement = std::move(Q);
    return false;
  }
  return true;
}

}  // namespace

BoundaryFirstResult place_boundary_first(const std::vector<Vec3>& points, const std::vector<core::Tet>& tets,
                                         const std::vector<Tri>& tris, const std::vector<int>& labels,
                                         const std::vector<int>& vertex_group, std::vector<Vec3>& P,
                                         const solve::UntangleOptions& base, double h, double fast_sigma) {
  BoundaryFirstResult res;
  const int nv = static_cast<int>(points.size());
  PC_REQUIRE(P.size() == points.size() && vertex_group.size() == 3 * points.size() && labels.size() == tris.size(),
             "place_boundary_first: inconsistent sizes");
  PC_REQUIRE(h > 0, "place_boundary_first: the apex height must be positive");
  std::vector<Vec3> Q = P;
  const std::optional<std::vector<Chain>> chains = find_chains(tris, labels, vertex_group, res.reason);
  if (!chains) {
    res.chains = -1;
    return res;
  }
  res.chains = static_cast<int>(chains->size());
  res.reversed_chains = orient_chains(points, *chains, vertex_group, Q);
  if (!place_chains(points, *chains, Q, res.reason)) return res;

  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (const Tri& t : tris)
    for (int v : t) on_boundary[v] = 1;
  if (!place_charts(points, tris, labels, vertex_group, on_boundary, h, base, Q, res)) return res;
  if (!place_volume(points, tets, vertex_group, on_boundary, base, fast_sigma, Q, res)) return res;
  res.valid = true;
  P.swap(Q);
  return res;
}

}  // namespace polycube::mapping
