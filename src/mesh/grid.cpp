#include "mesh/grid.h"

#include "core/elements.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/polycube_map.h"
#include "core/progress.h"
#include "core/topology.h"
#include "mesh/arrangement.h"
#include "mesh/tet_locator.h"
#include "structure/structure.h"

#include <fmt/format.h>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <numeric>

namespace polycube::mesh {

namespace {

using core::Vec3;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string fmt_point(const Vec3& p) {
  return fmt::format("({:.6g}, {:.6g}, {:.6g})", p.x(), p.y(), p.z());
}

//! Rounded levels at scale s: nearest integer, halves away from zero.
std::array<std::vector<long long>, 3> snapped_levels(const Arrangement& arr, double s) {
  std::array<std::vector<long long>, 3> out;
  for (int a = 0; a < 3; ++a)
    for (double l : arr.level[a]) {
      const double x = std::round(l * s);
      if (!(std::abs(x) < 1e9))
        throw core::InputError(
            fmt::format("scale {:.6g} puts the polycube outside the integer lattice's range", s));
      out[a].push_back(static_cast<long long>(x));
    }
  return out;
}

//! Are all chart planes at integer coordinates (within tol)?
bool integer_levels(const Arrangement& arr, double tol) {
  for (const auto& levels : arr.level)
    for (double l : levels)
      if (std::abs(l - std::round(l)) > tol) return false;
  return true;
}

//! Model-space length per polycube unit of every interval between consecutive levels, per axis
//! (GridSizing::Map): the map's stretch along the axis, |d model / d u_a|, over the tets whose
//! centroid lies in the slab, 95th percentile weighted by polycube volume. A slab no tet's
//! centroid falls in takes its neighbours' (or 1).
std::array<std::vector<double>, 3> slab_stretch(const core::PolycubeMap& map, const Arrangement& arr) {
  struct Sample {
    double stretch;
    double weight;
  };
  std::array<std::vector<std::vector<Sample>>, 3> samples;
  for (int a = 0; a < 3; ++a) samples[a].resize(static_cast<std::size_t>(arr.boxes(a)));
  for (const auto& t : map.tets) {
    Eigen::Matrix3d P;
    Eigen::Matrix3d M;
    for (int k = 0; k < 3; ++k) {
      P.col(k) = map.polycube[t[k + 1]] - map.polycube[t[0]];
      M.col(k) = map.model[t[k + 1]] - map.model[t[0]];
    }
    const double vol = P.determinant();
    if (!(std::abs(vol) > 1e-14 * P.squaredNorm() * std::sqrt(P.squaredNorm()))) continue;  // flat
    const Eigen::Matrix3d J = M * P.inverse();  // d model / d polycube
    const Vec3 c = 0.25 * (map.polycube[t[0]] + map.polycube[t[1]] + map.polycube[t[2]] + map.polycube[t[3]]);
    for (int a = 0; a < 3; ++a) {
      const auto& l = arr.level[a];
      const auto it = std::upper_bound(l.begin(), l.end(), c[a]);
      if (it == l.begin() || it == l.end()) continue;
      samples[a][static_cast<std::size_t>(it - l.begin() - 1)].push_back({J.col(a).norm(), std::abs(vol)});
    }
  }
  std::array<std::vector<double>, 3> out;
  for (int a = 0; a < 3; ++a) {
    out[a].assign(samples[a].size(), -1.0);
    for (std::size_t i = 0; i < samples[a].size(); ++i) {
      auto& v = samples[a][i];
      if (v.empty()) continue;
      std::sort(v.begin(), v.end(), [](const Sample& x, const Sample& y) { return x.stretch < y.stretch; });
      double total = 0.0;
      for (const auto& x : v) total += x.weight;
      double acc = 0.0;
      out[a][i] = v.back().stretch;
      for (const auto& x : v)
        if ((acc += x.weight) >= 0.95 * total) {
          out[a][i] = x.stretch;
          break;
        }
    }
    // empty slabs: nearest measured neighbour
    for (std::size_t i = 0; i < out[a].size(); ++i)
      if (out[a][i] < 0)
        for (std::size_t d = 1; d < out[a].size() && out[a][i] < 0; ++d) {
          if (i >= d && out[a][i - d] > 0) out[a][i] = out[a][i - d];
          else if (i + d < out[a].size() && out[a][i + d] > 0) out[a][i] = out[a][i + d];
        }
    for (double& x : out[a])
      if (!(x > 0) || !std::isfinite(x)) x = 1.0;
  }
  return out;
}

//! Integer levels with round(length * stretch * s) cells per interval, at least 1 (Map sizing).
std::array<std::vector<long long>, 3> map_levels(const Arrangement& arr, const std::array<std::vector<double>, 3>& stretch,
                                                 double s) {
  std::array<std::vector<long long>, 3> out;
  for (int a = 0; a < 3; ++a) {
    out[a].push_back(0);
    for (int i = 0; i < arr.boxes(a); ++i) {
      const double cells = std::round((arr.level[a][i + 1] - arr.level[a][i]) * stretch[a][i] * s);
      if (!(cells < 1e8))
        throw core::InputError(fmt::format("scale {:.6g} puts the polycube outside the integer lattice's range", s));
      out[a].push_back(out[a].back() + std::max(1LL, static_cast<long long>(cells)));
    }
  }
  return out;
}

//! Hex and boundary quad counts of the lattice with these integer levels.
std::array<double, 2> counts_of(const Arrangement& arr, const std::array<std::vector<long long>, 3>& sn) {
  std::array<std::vector<double>, 3> len;
  for (int a = 0; a < 3; ++a)
    for (std::size_t i = 0; i + 1 < sn[a].size(); ++i)
      len[a].push_back(static_cast<double>(sn[a][i + 1] - sn[a][i]));
  double hexes = 0.0;
  double quads = 0.0;
  for (int k = -1; k < arr.boxes(2); ++k)
    for (int j = -1; j < arr.boxes(1); ++j)
      for (int i = -1; i < arr.boxes(0); ++i) {
        const bool in = arr.is_inside(i, j, k);
        if (in) hexes += len[0][i] * len[1][j] * len[2][k];
        // faces between this box and its +x, +y, +z neighbours
        if (j >= 0 && k >= 0 && in != arr.is_inside(i + 1, j, k)) quads += len[1][j] * len[2][k];
        if (i >= 0 && k >= 0 && in != arr.is_inside(i, j + 1, k)) quads += len[0][i] * len[2][k];
        if (i >= 0 && j >= 0 && in != arr.is_inside(i, j, k + 1)) quads += len[0][i] * len[1][j];
      }
  return {hexes, quads};
}

//! Scale whose count (0: hexes, 1: quads) is closest to target. `stretch` (may be null) weighs
//! each interval's length (Map sizing); levels(s) gives the integer levels at scale s.
template <class Levels>
double choose_scale(const Arrangement& arr, int which, double target, const std::array<std::vector<double>, 3>* stretch,
                    const Levels& levels) {
  double measure = 0.0;  // volume or area at scale 1 without rounding
  for (int k = -1; k < arr.boxes(2); ++k)
    for (int j = -1; j < arr.boxes(1); ++j)
      for (int i = -1; i < arr.boxes(0); ++i) {
        auto len = [&](int a, int x) {
          return (arr.level[a][x + 1] - arr.level[a][x]) * (stretch ? (*stretch)[a][x] : 1.0);
        };
        const bool in = arr.is_inside(i, j, k);
        if (which == 0) {
          if (in) measure += len(0, i) * len(1, j) * len(2, k);
        } else {
          if (j >= 0 && k >= 0 && in != arr.is_inside(i + 1, j, k))
            measure += len(1, j) * len(2, k);
          if (i >= 0 && k >= 0 && in != arr.is_inside(i, j + 1, k))
            measure += len(0, i) * len(2, k);
          if (i >= 0 && j >= 0 && in != arr.is_inside(i, j, k + 1))
            measure += len(0, i) * len(1, j);
        }
      }
  if (!(measure > 0.0)) throw core::GeometryError("the polycube has no volume");
  const double s0 = which == 0 ? std::cbrt(target / measure) : std::sqrt(target / measure);
  // bisection for the smallest scale reaching the target, then the closer of the two sides
  double lo = s0 / 4.0;
  double hi = s0 * 4.0;
  auto count = [&](double s) { return counts_of(arr, levels(s))[which]; };
  // Bounded relative to s0 (not absolutely): a model in micrometres or in kilometres needs scales
  // far from 1.
  while (count(lo) >= target && lo > s0 * 1e-12) lo /= 2.0;
  while (count(hi) < target && hi < s0 * 1e12) hi *= 2.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (count(mid) >= target ? hi : lo) = mid;
  }
  const double clo = count(lo);
  const double chi = count(hi);
  return (std::abs(clo - target) < std::abs(chi - target) && clo > 0) ? lo : hi;
}

// --- snapping defects (thesis fig. 3.2) -------------------------------------------------------

struct SnapContext {
  const structure::PolycubeStructure& s;
  const Arrangement& arr;
  const std::array<std::vector<long long>, 3>& sn;
  double scale;
};

//! Snapped (lattice) position of a polycube point: each coordinate on a level goes to the
//! level's integer, any other coordinate is rounded.
Vec3 snap_point(const SnapContext& c, const Vec3& p) {
  Vec3 q;
  for (int a = 0; a < 3; ++a) {
    const int l = c.arr.nearest_level(a, p[a]);
    q[a] = std::abs(p[a] - c.arr.level[a][l]) <= c.arr.tolerance ? static_cast<double>(c.sn[a][l])
                                                                 : std::round(p[a] * c.scale);
  }
  return q;
}

//! Is the 2D point (x, y) inside or on the border of the polygon with holes (loops of 2D points)?
bool in_polygon(const std::vector<std::vector<std::array<double, 2>>>& loops, double x, double y) {
  bool odd = false;
  for (const auto& l : loops) {
    const std::size_t n = l.size();
    for (std::size_t i = 0; i < n; ++i) {
      const auto& p = l[i];
      const auto& q = l[(i + 1) % n];
      // on the segment (integer coordinates: exact)
      const double cross = (q[0] - p[0]) * (y - p[1]) - (q[1] - p[1]) * (x - p[0]);
      if (cross == 0.0 && x >= std::min(p[0], q[0]) && x <= std::max(p[0], q[0]) &&
          y >= std::min(p[1], q[1]) && y <= std::max(p[1], q[1]))
        return true;
      if ((p[1] > y) != (q[1] > y)) {
        const double xi = p[0] + (y - p[1]) * (q[0] - p[0]) / (q[1] - p[1]);
        if (x < xi) odd = !odd;
      }
    }
  }
  return odd;
}

//! The corners of the polycube at their snapped (lattice) positions, shared by the defect tests.
struct SnappedCorners {
  const SnapContext& c;
  std::vector<Vec3> snapped;  //!< #corners lattice position of each corner

  explicit SnappedCorners(const SnapContext& context) : c(context), snapped(context.s.corners.size()) {
    for (std::size_t i = 0; i < c.s.corners.size(); ++i) snapped[i] = snap_point(c, c.s.corners[i].position);
  }
  //! Scaled polycube position of a corner (before snapping).
  [[nodiscard]] Vec3 scaled(int corner) const {
    return c.s.corners[static_cast<std::size_t>(corner)].position * c.scale;
  }
};

//! Defects of corners merged into one lattice point.
void merged_corners(const SnappedCorners& sc, std::vector<SnapDefect>& out) {
  const auto& snapped = sc.snapped;
  std::vector<int> order(sc.c.s.corners.size());
  std::iota(order.begin(), order.end(), 0);
  auto key = [&](int i) {
    return std::array<double, 3>{snapped[i].x(), snapped[i].y(), snapped[i].z()};
  };
  std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return key(x) < key(y); });
  for (std::size_t i = 0; i < order.size();) {
    std::size_t j = i + 1;
    while (j < order.size() && key(order[j]) == key(order[i])) ++j;
    if (j - i > 1) {
      SnapDefect d;
      d.kind = DefectKind::CornersMerged;
      d.lattice = snapped[order[i]];
      std::string names;
      for (std::size_t k = i; k < j; ++k) {
        d.corners.push_back(order[k]);
        std::sort(d.corners.begin(), d.corners.end());
      }
      for (int cid : d.corners) {
        d.positions.push_back(sc.scaled(cid));
        names += (names.empty() ? "" : ", ") + fmt::format("{} {}", cid, fmt_point(sc.scaled(cid)));
      }
      d.description =
          fmt::format("corners {} merge at lattice point {}", names, fmt_point(d.lattice));
      out.push_back(std::move(d));
    }
    i = j;
  }
}

//! Defects of polycube edges collapsed to zero length.
void collapsed_edges(const SnappedCorners& sc, std::vector<SnapDefect>& out) {
  const auto& s = sc.c.s;
  const auto& snapped = sc.snapped;
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const auto& pe = s.edges[e];
    if (pe.corners[0] < 0 || pe.corners[1] < 0) continue;
    if (snapped[pe.corners[0]] != snapped[pe.corners[1]]) continue;
    SnapDefect d;
    d.kind = DefectKind::EdgeCollapsed;
    d.edge = static_cast<int>(e);
    d.corners = {pe.corners[0], pe.corners[1]};
    d.positions = {sc.scaled(pe.corners[0]), sc.scaled(pe.corners[1])};
    d.lattice = snapped[pe.corners[0]];
    d.description =
        fmt::format("edge {} (corners {}-{}, along {}, length {:.6g}) collapses to zero length", e,
                    pe.corners[0], pe.corners[1], core::axis_name(pe.axis), pe.length * sc.c.scale);
    out.push_back(std::move(d));
  }
}

//! Loops of 2D points (in the chart's plane) of every chart, per chart.
using ChartPolygons = std::vector<std::vector<std::vector<std::array<double, 2>>>>;

//! Defects of charts collapsed to zero area. Returns the snapped polygon of every chart (empty
//! for a chart with a loop of fewer than 3 corners), which the corner-on-facet test needs too.
ChartPolygons collapsed_charts(const SnappedCorners& sc, std::vector<SnapDefect>& out) {
  const auto& s = sc.c.s;
  const auto& snapped = sc.snapped;
  ChartPolygons polys(s.charts.size());
  for (std::size_t ci = 0; ci < s.charts.size(); ++ci) {
    const auto& ch = s.charts[ci];
    const int u = (ch.axis + 1) % 3;
    const int v = (ch.axis + 2) % 3;
    double area = 0.0;
    bool usable = true;
    for (const auto& loop : s.faces[ci].loops) {
      if (loop.corners.size() < 3) {
        usable = false;
        break;
      }
      std::vector<std::array<double, 2>> pts;
      for (int cid : loop.corners) pts.push_back({snapped[cid][u], snapped[cid][v]});
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const auto& p = pts[i];
        const auto& q = pts[(i + 1) % pts.size()];
        area += p[0] * q[1] - p[1] * q[0];
      }
      polys[ci].push_back(std::move(pts));
    }
    if (!usable) {
      polys[ci].clear();
      continue;
    }
    if (area == 0.0 && ch.area > 0.0) {
      SnapDefect d;
      d.kind = DefectKind::ChartCollapsed;
      d.chart = static_cast<int>(ci);
      for (int cid : s.faces[ci].loops[0].corners) {
        d.corners.push_back(cid);
        d.positions.push_back(sc.scaled(cid));
      }
      d.lattice = snapped[s.faces[ci].loops[0].corners[0]];
      d.description =
          fmt::format("chart {} ({} at {} = {:.6g}, area {:.6g}) collapses to zero area", ci,
                      core::label_name(ch.label), core::axis_name(ch.axis),
                      ch.coordinate * sc.c.scale, ch.area * sc.c.scale * sc.c.scale);
      out.push_back(std::move(d));
    }
  }
  return polys;
}

//! Defects of corners pushed onto (the inside or border of) charts they do not belong to.
void corners_on_facets(const SnappedCorners& sc, const ChartPolygons& polys, std::vector<SnapDefect>& out) {
  const auto& s = sc.c.s;
  const auto& snapped = sc.snapped;
  // charts by (axis, snapped level)
  std::map<std::pair<int, long long>, std::vector<int>> by_plane;
  for (std::size_t ci = 0; ci < s.charts.size(); ++ci) {
    const int l = sc.c.arr.chart_level[ci];
    if (l >= 0 && !polys[ci].empty())
      by_plane[{s.charts[ci].axis, sc.c.sn[s.charts[ci].axis][l]}].push_back(static_cast<int>(ci));
  }
  for (std::size_t cid = 0; cid < s.corners.size(); ++cid) {
    const Vec3& q = snapped[cid];
    for (int a = 0; a < 3; ++a) {
      auto it = by_plane.find({a, static_cast<long long>(q[a])});
      if (it == by_plane.end()) continue;
      for (int ci : it->second) {
        const auto& own = s.corners[cid].charts;
        if (std::binary_search(own.begin(), own.end(), ci)) continue;
        // a corner landing on one of the chart's corners is already a merge
        bool on_corner = false;
        for (const auto& loop : s.faces[static_cast<std::size_t>(ci)].loops)
          for (int other : loop.corners) on_corner = on_corner || snapped[other] == q;
        if (on_corner) continue;
        const int u = (a + 1) % 3;
        const int v = (a + 2) % 3;
        if (!in_polygon(polys[static_cast<std::size_t>(ci)], q[u], q[v])) continue;
        const auto& ch = s.charts[static_cast<std::size_t>(ci)];
        SnapDefect d;
        d.kind = DefectKind::CornerOnFacet;
        d.chart = ci;
        d.corners = {static_cast<int>(cid)};
        d.positions = {sc.scaled(static_cast<int>(cid))};
        d.lattice = q;
        d.description = fmt::format(
            "corner {} {} is pushed onto chart {} ({} at {} = {:.6g}) at lattice point {}", cid,
            fmt_point(sc.scaled(static_cast<int>(cid))), ci, core::label_name(ch.label),
            core::axis_name(a), ch.coordinate * sc.c.scale, fmt_point(q));
        out.push_back(std::move(d));
      }
    }
  }
}

//! The topological defects of snapping the corners (thesis fig. 3.2), in this order: corners
//! merged, edges collapsed, charts collapsed, corners pushed onto facets.
std::vector<SnapDefect> detect_defects(const SnapContext& c) {
  const SnappedCorners sc(c);
  std::vector<SnapDefect> out;
  merged_corners(sc, out);
  collapsed_edges(sc, out);
  const ChartPolygons polys = collapsed_charts(sc, out);
  corners_on_facets(sc, polys, out);
  return out;
}

// --- the snapped polycube when levels collapse ------------------------------------------------

//! Scaled polycube positions with every chart moved to its rounded plane and the displacement
//! extended harmonically (uniform graph Laplacian of the tet mesh) to the other vertices.
std::vector<Vec3> deform_to_snapped(const core::PolycubeMap& map,
                                    const structure::PolycubeStructure& s, const Arrangement& arr,
                                    const std::array<std::vector<long long>, 3>& sn, double scale) {
  const int nv = map.num_vertices();
  std::vector<Vec3> out(static_cast<std::size_t>(nv));
  for (int v = 0; v < nv; ++v) out[v] = map.polycube[v] * scale;
  const auto et = core::unique_edges(map.polycube_mesh());
  for (int a = 0; a < 3; ++a) {
    std::vector<char> fixed(static_cast<std::size_t>(nv), 0);
    std::vector<double> disp(static_cast<std::size_t>(nv), 0.0);
    for (std::size_t f = 0; f < s.triangles.size(); ++f) {
      const int ci = s.triangle_chart[f];
      if (s.charts[ci].axis != a) continue;
      const double target = static_cast<double>(sn[a][arr.chart_level[ci]]);
      for (int v : s.triangles[f]) {
        if (fixed[v]) continue;
        fixed[v] = 1;
        disp[v] = target - out[v][a];
      }
    }
    std::vector<int> free_id(static_cast<std::size_t>(nv), -1);
    int nfree = 0;
    for (int v = 0; v < nv; ++v)
      if (!fixed[v]) free_id[v] = nfree++;
    if (nfree > 0) {
      std::vector<Eigen::Triplet<double>> trip;
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nfree);
      std::vector<double> degree(static_cast<std::size_t>(nfree), 0.0);
      for (const auto& e : et.edges) {
        if (e[0] == e[1]) continue;
        const int i = free_id[e[0]];
        const int j = free_id[e[1]];
        if (i >= 0) degree[i] += 1.0;
        if (j >= 0) degree[j] += 1.0;
        if (i >= 0 && j >= 0) {
          trip.emplace_back(i, j, -1.0);
          trip.emplace_back(j, i, -1.0);
        } else if (i >= 0) {
          rhs[i] += disp[e[1]];
        } else if (j >= 0) {
          rhs[j] += disp[e[0]];
        }
      }
      for (int i = 0; i < nfree; ++i) trip.emplace_back(i, i, degree[i] > 0.0 ? degree[i] : 1.0);
      Eigen::SparseMatrix<double> L(nfree, nfree);
      L.setFromTriplets(trip.begin(), trip.end());
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
      if (solver.info() != Eigen::Success)
        throw core::SolverError("snapping: the harmonic extension failed");
      const Eigen::VectorXd x = solver.solve(rhs);
      for (int v = 0; v < nv; ++v)
        if (free_id[v] >= 0) disp[v] = x[free_id[v]];
    }
    for (int v = 0; v < nv; ++v) out[v][a] += disp[v];
  }
  return out;
}

//! Tets whose orientation is not positive (with a relative flatness threshold).
std::vector<int> degenerate_tets(const std::vector<core::Tet>& tets, const std::vector<Vec3>& pos) {
  std::vector<int> bad;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& c = tets[t];
    const Vec3 e1 = pos[c[1]] - pos[c[0]];
    const Vec3 e2 = pos[c[2]] - pos[c[0]];
    const Vec3 e3 = pos[c[3]] - pos[c[0]];
    const double l = std::max({e1.norm(), e2.norm(), e3.norm()});
    if (!(e1.dot(e2.cross(e3)) > 1e-12 * l * l * l)) bad.push_back(static_cast<int>(t));
  }
  return bad;
}

int count_inverted_hexes(const core::HexMesh& m) {
  int n = 0;
  for (const auto& h : m.cells) {
    bool bad = false;
    for (int i = 0; i < 8 && !bad; ++i) {
      const auto& nb = core::kHexCornerNeighbors[static_cast<std::size_t>(i)];
      const Vec3& p = m.points[h[i]];
      const double j =
          (m.points[h[nb[0]]] - p).dot((m.points[h[nb[1]]] - p).cross(m.points[h[nb[2]]] - p));
      bad = !(j > 0.0);
    }
    n += bad ? 1 : 0;
  }
  return n;
}


// --- the steps of grid_polycube ---------------------------------------------------------------

void check_options(const core::PolycubeMap& map, const GridOptions& options) {
  core::check_map_indices(map);
  if (!(options.scale >= 0.0) || !std::isfinite(options.scale))
    throw core::InputError(fmt::format("scale must be a positive number (got {})", options.scale));
  if (options.target_hexes < 0 || options.target_quads < 0)
    throw core::InputError("the target number of hexes or quads must be positive");
  if (!(options.tolerance >= 0.0)) throw core::InputError("the tolerance must be >= 0");
  if (options.refine_factor < 1 || options.refine_factor > 64)
    throw core::InputError(fmt::format("the refinement factor must be from 1 to 64 (got {})", options.refine_factor));
  for (const Vec3& p : options.refine_near)
    if (!p.allFinite()) throw core::InputError("a point to refine the lattice near has a non-finite coordinate");
}

//! The integer lattice coordinate of every level and the scale that gives them.
struct Levels {
  bool by_map = false;                       //!< GridSizing::Map: per-interval cell counts
  bool refined = false;                      //!< some intervals' cells multiplied (refine_near)
  double scale = 1.0;                        //!< GridSizing::Map: cells per model length
  std::array<std::vector<long long>, 3> sn;  //!< integer of each level, per axis
};

//! Multiply the cells of the intervals (per axis) holding a coordinate of a point of `near` by
//! `factor`, shifting the integers of the levels above them. Every level keeps its own integer
//! and the lattice points are located per interval (inverse_snapping), as with Map sizing.
//! Returns whether some interval was refined. Levels that collapsed (sn not increasing) are
//! left as they are: the deformation that snaps them works with the rounded levels.
bool refine_intervals(const Arrangement& arr, const std::vector<Vec3>& near, int factor, double tol,
                      std::array<std::vector<long long>, 3>& sn) {
  if (near.empty() || factor <= 1) return false;
  for (int a = 0; a < 3; ++a)
    for (std::size_t i = 0; i + 1 < sn[a].size(); ++i)
      if (sn[a][i + 1] <= sn[a][i]) return false;
  bool refined = false;
  for (int a = 0; a < 3; ++a) {
    const auto& l = arr.level[a];
    std::vector<char> fine(static_cast<std::size_t>(arr.boxes(a)), 0);
    for (const Vec3& p : near)
      for (int i = 0; i < arr.boxes(a); ++i)
        if (p[a] >= l[i] - tol && p[a] <= l[i + 1] + tol) fine[static_cast<std::size_t>(i)] = 1;
    std::vector<long long> out{sn[a][0]};
    for (int i = 0; i < arr.boxes(a); ++i) {
      const long long cells = sn[a][i + 1] - sn[a][i];
      out.push_back(out.back() + (fine[static_cast<std::size_t>(i)] ? factor * cells : cells));
      refined = refined || fine[static_cast<std::size_t>(i)];
    }
    sn[a] = std::move(out);
  }
  return refined;
}

//! The scale (and, with Map sizing, the cells of every interval) and the levels' integers.
Levels choose_levels(const core::PolycubeMap& map, const Arrangement& arr, const GridOptions& options,
                     double tol) {
  Levels lv;
  lv.by_map = options.sizing == GridSizing::Map;
  const bool by_map = lv.by_map;
  std::array<std::vector<double>, 3> stretch;
  if (by_map) stretch = slab_stretch(map, arr);
  auto levels_at = [&](double sc) { return by_map ? map_levels(arr, stretch, sc) : snapped_levels(arr, sc); };
  double scale = 1.0;
  if (options.scale > 0.0)
    scale = options.scale;
  else if (options.target_hexes > 0)
    scale = choose_scale(arr, 0, options.target_hexes, by_map ? &stretch : nullptr, levels_at);
  else if (options.target_quads > 0)
    scale = choose_scale(arr, 1, options.target_quads, by_map ? &stretch : nullptr, levels_at);
  // An integer polycube (simplified) keeps every plane distinct and every alignment at any scale
  // >= 1 (rounding is monotone and round(x + 1) = round(x) + 1): never go below 1 for it.
  if (!by_map && options.scale <= 0.0 && (options.target_hexes > 0 || options.target_quads > 0) &&
      integer_levels(arr, tol))
    scale = std::max(scale, 1.0);
  lv.scale = scale;
  lv.sn = levels_at(scale);
  lv.refined = refine_intervals(arr, options.refine_near, options.refine_factor, tol, lv.sn);
  core::logger().info("gridding: {} {:.6g}, {} x {} x {} chart planes", by_map ? "cells per model length" : "scale",
                      scale, arr.level[0].size(), arr.level[1].size(), arr.level[2].size());
  return lv;
}

//! How far snapping moves the levels and corners and whether some levels collapse (the defects
//! are left to detect_defects). With Map sizing none do: the per-interval counts place every
//! level, the polycube is not scaled but mapped per axis.
SnapReport snap_report(const SnapContext& ctx, bool by_map, double tol_lattice) {
  const Arrangement& arr = ctx.arr;
  const auto& sn = ctx.sn;
  const double scale = ctx.scale;
  SnapReport rep;
  for (int a = 0; a < 3; ++a) {
    rep.levels[a] = static_cast<int>(arr.level[a].size());
    for (std::size_t i = 0; i < sn[a].size() && !by_map; ++i) {
      rep.max_displacement = std::max(
          rep.max_displacement, std::abs(static_cast<double>(sn[a][i]) - arr.level[a][i] * scale));
      if (i > 0 && sn[a][i] <= sn[a][i - 1]) ++rep.collapsed_levels;
    }
  }
  rep.needed = rep.max_displacement > tol_lattice;
  for (const auto& c : ctx.s.corners)
    if (!by_map && (snap_point(ctx, c.position) - c.position * scale).cwiseAbs().maxCoeff() > tol_lattice)
      ++rep.corners_moved;
  rep.deformed = rep.collapsed_levels > 0;
  return rep;
}

//! The lattice: the integer cells inside the snapped arrangement boxes, as hexes.
struct Lattice {
  std::array<long long, 3> lo{};           //!< integer of the lowest level, per axis
  std::array<long long, 3> n{};            //!< cells of the bounding box, per axis
  std::vector<std::array<int, 3>> points;  //!< the hexes' lattice points, relative to lo
  core::HexMesh hexes;                     //!< lattice positions (points in the order of `points`)
};

//! Arrangement interval of every lattice cell, per axis.
std::array<std::vector<int>, 3> cell_boxes(const std::array<std::vector<long long>, 3>& sn, const Lattice& lat) {
  std::array<std::vector<int>, 3> cell_box;
  for (int a = 0; a < 3; ++a) {
    cell_box[a].assign(static_cast<std::size_t>(lat.n[a]), -1);
    for (std::size_t i = 0; i + 1 < sn[a].size(); ++i)
      for (long long c = sn[a][i]; c < sn[a][i + 1]; ++c)
        cell_box[a][static_cast<std::size_t>(c - lat.lo[a])] = static_cast<int>(i);
  }
  return cell_box;
}

Lattice build_lattice(const Arrangement& arr, const Levels& lv, long long max_lattice_points) {
  const auto& sn = lv.sn;
  Lattice lat;
  const auto& lo = lat.lo;
  const auto& n = lat.n;
  for (int a = 0; a < 3; ++a) {
    lat.lo[a] = sn[a].front();
    lat.n[a] = sn[a].back() - sn[a].front();
  }
  const long long npoints_box = (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
  if (npoints_box > max_lattice_points || npoints_box > INT_MAX)
    throw core::InputError(fmt::format(
        "the lattice at scale {:.6g} has {} x {} x {} cells: too large (choose a smaller "
        "scale or fewer hexes)",
        lv.scale, n[0], n[1], n[2]));
  const std::array<std::vector<int>, 3> cell_box = cell_boxes(sn, lat);
  const int nx = static_cast<int>(n[0]);
  const int ny = static_cast<int>(n[1]);
  const int nz = static_cast<int>(n[2]);
  auto pidx = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * (ny + 1) + j) * (nx + 1) + i;
  };
  std::vector<int> point_id(static_cast<std::size_t>(npoints_box), -1);
  std::vector<std::array<int, 3>> cells;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (arr.is_inside(cell_box[0][i], cell_box[1][j], cell_box[2][k])) {
          cells.push_back({i, j, k});
          for (int c = 0; c < 8; ++c)
            point_id[pidx(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] = 0;
        }
  if (cells.empty())
    throw core::GeometryError(
        fmt::format("no lattice cell lies inside the polycube at scale {:.6g}", lv.scale));
  std::vector<std::array<int, 3>>& lattice_points = lat.points;
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        if (point_id[pidx(i, j, k)] == 0) {
          point_id[pidx(i, j, k)] = static_cast<int>(lattice_points.size());
          lattice_points.push_back({i, j, k});
        }
  // hexes in the order of elements.h: 0-1-2-3 bottom ring ccw from above, 4-7 above
  constexpr std::array<std::array<int, 3>, 8> kCorner{
      {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}}};
  core::HexMesh& hp = lat.hexes;
  hp.cells.reserve(cells.size());
  for (const auto& c : cells) {
    core::Hex h{};
    for (int v = 0; v < 8; ++v)
      h[v] = point_id[pidx(c[0] + kCorner[v][0], c[1] + kCorner[v][1], c[2] + kCorner[v][2])];
    hp.cells.push_back(h);
  }
  hp.points.reserve(lattice_points.size());
  for (const auto& p : lattice_points)
    hp.points.emplace_back(static_cast<double>(p[0] + lo[0]), static_cast<double>(p[1] + lo[1]),
                           static_cast<double>(p[2] + lo[2]));
  return lat;
}

//! Where the lattice points are located and how their positions there are found.
struct LocationSpace {
  //! Levels collapsed: the lattice points are located in the snapped polycube at their lattice
  //! positions; else in the polycube through the inverse of the per-axis snapping map.
  bool deformed = false;
  double scale = 1.0;                          //!< lattice units per polycube unit
  double tolerance = 0.0;                      //!< of the snapped polycube's locator (lattice units)
  std::vector<Vec3> snapped;                   //!< deformed: #V snapped polycube positions
  std::array<std::vector<double>, 3> inverse;  //!< else: lattice coordinate -> polycube coordinate
};

//! Levels collapsed: the snapping defects (into rep.defects) and the snapped polycube.
std::vector<Vec3> deform_and_detect(const core::PolycubeMap& map, const SnapContext& ctx, SnapReport& rep) {
  rep.defects = detect_defects(ctx);
  std::vector<Vec3> deformed = deform_to_snapped(map, ctx.s, ctx.arr, ctx.sn, ctx.scale);
  const std::vector<int> bad = degenerate_tets(map.tets, deformed);
  if (!bad.empty()) {
    SnapDefect d;
    d.kind = DefectKind::TetsDegenerated;
    d.count = static_cast<int>(bad.size());
    d.description = fmt::format(
        "the snapped polycube has {} flat or inverted tets (first: tet {})", bad.size(), bad[0]);
    rep.defects.push_back(std::move(d));
  }
  core::logger().warn("snapping at scale {:.6g} collapses {} coordinate level(s): {}", ctx.scale,
                      rep.collapsed_levels, rep.summary());
  return deformed;
}

//! Inverse of the per-axis snapping map, lattice coordinate (relative to lat.lo) -> polycube
//! coordinate: exact when no level collapses, every interval maps linearly onto its cells.
std::array<std::vector<double>, 3> inverse_snapping(const Arrangement& arr,
                                                    const std::array<std::vector<long long>, 3>& sn,
                                                    const Lattice& lat) {
  std::array<std::vector<double>, 3> inverse;
  for (int a = 0; a < 3; ++a) {
    inverse[a].resize(static_cast<std::size_t>(lat.n[a] + 1));
    for (std::size_t i = 0; i + 1 < sn[a].size(); ++i) {
      const double l0 = arr.level[a][i];
      const double l1 = arr.level[a][i + 1];
      const double len = static_cast<double>(sn[a][i + 1] - sn[a][i]);
      for (long long c = sn[a][i]; c <= sn[a][i + 1]; ++c) {
        const double t = static_cast<double>(c - sn[a][i]) / len;
        inverse[a][static_cast<std::size_t>(c - lat.lo[a])] =
            c == sn[a][i + 1] ? l1 : l0 + t * (l1 - l0);
      }
    }
  }
  return inverse;
}

//! Every lattice point, or only the boundary ones (quad meshes only).
std::vector<int> points_to_locate(const core::HexBoundary& hb, std::size_t num_points, bool volume) {
  std::vector<int> to_locate;
  if (volume) {
    to_locate.resize(num_points);
    std::iota(to_locate.begin(), to_locate.end(), 0);
  } else {
    to_locate = hb.vertex_map;
  }
  return to_locate;
}

//! Model positions of the lattice points to_locate (NaN for the others): each is located in a
//! tet of the (snapped) polycube and mapped with its barycentric coordinates. Counts the points
//! located and failed into res.
std::vector<Vec3> map_lattice_points(const core::PolycubeMap& map, const TetLocator& base_locator,
                                     const LocationSpace& space, const Lattice& lat,
                                     const std::vector<int>& to_locate, GridResult& res) {
  std::vector<Vec3> model_pos(lat.points.size(), Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  const TetLocator* locator = &base_locator;
  std::unique_ptr<TetLocator> deformed_locator;
  if (space.deformed) {
    deformed_locator = std::make_unique<TetLocator>(map.tets, space.snapped, space.tolerance);
    locator = deformed_locator.get();
  }
  core::ProgressTask task("map lattice points", static_cast<std::int64_t>(to_locate.size()));
  std::size_t done = 0;
  for (int pid : to_locate) {
    const auto& lp = lat.points[static_cast<std::size_t>(pid)];
    Vec3 q;
    if (space.deformed)
      q = lat.hexes.points[static_cast<std::size_t>(pid)];
    else
      q = Vec3(space.inverse[0][lp[0]], space.inverse[1][lp[1]], space.inverse[2][lp[2]]);
    bool located = false;
    const TetLocator::Hit hit = locate_or_nearest(*locator, q, located);
    if (located) {
      ++res.points_located;
    } else {
      ++res.points_failed;
      res.max_failed_distance =
          std::max(res.max_failed_distance, -hit.score / (space.deformed ? space.scale : 1.0));
    }
    if (hit.tet < 0) throw core::GeometryError("gridding: the polycube has no usable tet");
    // clamped to the tet (points on the boundary may be outside by rounding) and mapped
    model_pos[static_cast<std::size_t>(pid)] = map_through(map.tets, map.model, hit);
    if ((++done & 0xFFFF) == 0) task.set(static_cast<std::int64_t>(done));
  }
  task.finish();
  return model_pos;
}

//! The result meshes: the lattice hexes, their boundary quads, both in lattice and model space.
void assemble_meshes(GridResult& res, core::HexMesh hexes, const core::HexBoundary& hb,
                     const std::vector<Vec3>& model_pos, bool volume) {
  res.hex_polycube = std::move(hexes);
  if (volume) {
    res.hex_model.cells = res.hex_polycube.cells;
    res.hex_model.points = model_pos;
    res.inverted_model_hexes = count_inverted_hexes(res.hex_model);
  }
  res.quad_polycube = hb.surface;
  res.quad_model.cells = hb.surface.cells;
  res.quad_model.points.reserve(hb.vertex_map.size());
  for (int v : hb.vertex_map)
    res.quad_model.points.push_back(model_pos[static_cast<std::size_t>(v)]);
  res.quad_polycube.labels.clear();
  res.quad_model.labels.clear();
}

}  // namespace

const char* defect_name(DefectKind k) {
  switch (k) {
    case DefectKind::CornersMerged:
      return "corners merged";
    case DefectKind::CornerOnFacet:
      return "corner pushed onto a facet";
    case DefectKind::EdgeCollapsed:
      return "edge collapsed";
    case DefectKind::ChartCollapsed:
      return "chart collapsed";
    case DefectKind::TetsDegenerated:
      return "tets flattened or inverted";
  }
  return "?";
}

std::string SnapReport::summary(int max_items) const {
  if (defects.empty()) return "no defect";
  std::string out;
  for (DefectKind k :
       {DefectKind::CornersMerged, DefectKind::CornerOnFacet, DefectKind::EdgeCollapsed,
        DefectKind::ChartCollapsed, DefectKind::TetsDegenerated}) {
    int n = 0;
    std::string items;
    for (const SnapDefect& d : defects)
      if (d.kind == k) {
        if (n < max_items) items += (items.empty() ? "" : "; ") + d.description;
        ++n;
      }
    if (n == 0) continue;
    if (!out.empty()) out += " | ";
    out += fmt::format("{}: {}{}", defect_name(k), items,
                       n > max_items ? fmt::format("; ... ({} in all)", n) : "");
  }
  return out;
}

//! Planes of no chart around the points of GridOptions::refine_near, for the arrangement. On an
//! integer polycube (a simplified one) the integer planes on either side of each coordinate (on
//! both sides of one on a plane), so that the refined cells fill the unit slab that holds it, not
//! the whole interval between chart planes: at any scale an integer plane keeps its own lattice
//! plane, and the cells of the interval it splits are the same in all. Otherwise none.
std::array<std::vector<double>, 3> refine_planes(const structure::PolycubeStructure& s, const std::vector<Vec3>& near,
                                                 double tol) {
  std::array<std::vector<double>, 3> out;
  for (const auto& c : s.charts)
    if (std::abs(c.coordinate - std::round(c.coordinate)) > tol) return out;
  for (const Vec3& p : near)
    for (int a = 0; a < 3; ++a) {
      const double x = p[a];
      const double below = std::abs(x - std::round(x)) <= tol ? std::round(x) - 1 : std::floor(x);
      const double above = std::abs(x - std::round(x)) <= tol ? std::round(x) + 1 : std::floor(x) + 1;
      out[static_cast<std::size_t>(a)].push_back(below);
      out[static_cast<std::size_t>(a)].push_back(above);
    }
  return out;
}

std::vector<Vec3> polycube_points(const core::PolycubeMap& map, const std::vector<Vec3>& model_points) {
  core::check_map_indices(map);
  const double tol = 1e-9 * core::bounding_box(map.model).diagonal();
  const TetLocator locator(map.tets, map.model, tol);
  std::vector<Vec3> out;
  out.reserve(model_points.size());
  for (const Vec3& p : model_points) {
    TetLocator::Hit hit = locator.locate(p);
    if (hit.tet < 0) hit = locator.nearest(p, 2);
    if (hit.tet < 0) hit = locator.nearest_brute_force(p);
    if (hit.tet < 0) throw core::GeometryError("the map has no tet to locate a point in");
    Vec3 q = Vec3::Zero();
    for (int k = 0; k < 4; ++k) {
      const double b = std::clamp(hit.bary[static_cast<std::size_t>(k)], 0.0, 1.0);
      q += b * map.polycube[static_cast<std::size_t>(map.tets[static_cast<std::size_t>(hit.tet)][k])];
    }
    double sum = 0.0;
    for (double b : hit.bary) sum += std::clamp(b, 0.0, 1.0);
    out.push_back(sum > 0.0 ? Vec3(q / sum) : map.polycube[static_cast<std::size_t>(map.tets[static_cast<std::size_t>(hit.tet)][0])]);
  }
  return out;
}

GridResult grid_polycube(const core::PolycubeMap& map, const GridOptions& options) {
  const auto t_start = Clock::now();
  check_options(map, options);

  GridResult res;
  const structure::PolycubeStructure s = structure::extract_structure(map);
  const double diag = core::bounding_box(map.polycube).diagonal();
  const double tol = options.tolerance * diag;
  const TetLocator base_locator(map.tets, map.polycube, tol);
  const Arrangement arr = build_arrangement(s, base_locator, tol, options.max_lattice_points,
                                            refine_planes(s, options.refine_near, tol));
  core::logger().debug("gridding: structure, locator and arrangement {:.3f} s",
                       seconds_since(t_start));

  // 1. the scale and the integer of every level
  const Levels lv = choose_levels(map, arr, options, tol);
  res.scale = lv.scale;

  // 2. snapping: how far the levels move, whether some collapse
  const SnapContext ctx{s, arr, lv.sn, lv.scale};
  const double tol_lattice = tol * lv.scale;
  res.snapping = snap_report(ctx, lv.by_map || lv.refined, tol_lattice);
  SnapReport& rep = res.snapping;

  // 3. the lattice: integer cells inside the snapped arrangement boxes
  for (int a = 0; a < 3; ++a) {
    res.lattice_min[a] = static_cast<int>(lv.sn[a].front());
    res.lattice_max[a] = static_cast<int>(lv.sn[a].back());
  }
  Lattice lat = build_lattice(arr, lv, options.max_lattice_points);

  // 4. defects (only possible when levels collapse) and the space the points are located in
  LocationSpace space;
  space.deformed = rep.deformed;
  space.scale = lv.scale;
  space.tolerance = tol_lattice;
  if (rep.deformed)
    space.snapped = deform_and_detect(map, ctx, rep);
  else
    space.inverse = inverse_snapping(arr, lv.sn, lat);
  core::logger().debug("gridding: lattice of {} hexes {:.3f} s", lat.hexes.cells.size(),
                       seconds_since(t_start));

  // 5. which points to locate
  const core::HexBoundary hb = core::boundary(lat.hexes);
  core::logger().debug("gridding: boundary {:.3f} s", seconds_since(t_start));
  const std::vector<int> to_locate = points_to_locate(hb, lat.points.size(), options.volume);

  // 6. locate and map
  const auto t_locate = Clock::now();
  const std::vector<Vec3> model_pos = map_lattice_points(map, base_locator, space, lat, to_locate, res);
  res.seconds_locate = seconds_since(t_locate);
  if (res.points_failed > 0)
    core::logger().warn(
        "{} lattice point(s) lie outside the polycube by up to {:.3g}: mapped to the nearest tet",
        res.points_failed, res.max_failed_distance);

  // 7. assemble the meshes
  assemble_meshes(res, std::move(lat.hexes), hb, model_pos, options.volume);
  res.seconds_total = seconds_since(t_start);
  return res;
}

}  // namespace polycube::mesh
