#include "simplify/corner_system.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace polycube::simplify {

namespace {

using structure::PolycubeStructure;

using core::DisjointSets;

//! Corners of a chart (all loops), sorted, unique.
std::vector<int> chart_corners(const PolycubeStructure& s, int chart) {
  std::vector<int> cs;
  for (const auto& loop : s.faces[chart].loops) cs.insert(cs.end(), loop.corners.begin(), loop.corners.end());
  std::sort(cs.begin(), cs.end());
  cs.erase(std::unique(cs.begin(), cs.end()), cs.end());
  return cs;
}

double bbox_diagonal(const PolycubeStructure& s) {
  core::Vec3 lo = s.corners.front().position, hi = lo;
  for (const auto& c : s.corners) {
    lo = lo.cwiseMin(c.position);
    hi = hi.cwiseMax(c.position);
  }
  return std::max((hi - lo).norm(), 1e-300);
}

//! Classes of one axis: union-find, consistency check, merge of coincident classes, ids in
//! coordinate order.
AxisSystem make_classes(const PolycubeStructure& s, int axis, double scale, double tol, double consistency) {
  const int nc = static_cast<int>(s.corners.size());
  DisjointSets ds(static_cast<std::size_t>(nc));
  for (const auto& e : s.edges)
    if (e.axis != axis) ds.unite(e.corners[0], e.corners[1]);
  for (std::size_t p = 0; p < s.charts.size(); ++p) {
    if (s.charts[p].axis != axis) continue;
    const auto cs = chart_corners(s, static_cast<int>(p));
    for (std::size_t k = 1; k < cs.size(); ++k) ds.unite(cs[0], cs[k]);
  }
  // raw classes (by root), their mean coordinate and spread
  std::vector<int> root_id(static_cast<std::size_t>(nc), -1);
  std::vector<double> sum, lo, hi;
  std::vector<int> count, first;
  std::vector<int> raw(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) {
    const int r = ds.find(c);
    if (root_id[r] < 0) {
      root_id[r] = static_cast<int>(sum.size());
      sum.push_back(0.0);
      lo.push_back(INFINITY);
      hi.push_back(-INFINITY);
      count.push_back(0);
      first.push_back(c);
    }
    const int k = root_id[r];
    raw[c] = k;
    const double x = s.corners[c].position[axis];
    sum[k] += x;
    lo[k] = std::min(lo[k], x);
    hi[k] = std::max(hi[k], x);
    ++count[k];
  }
  const int nraw = static_cast<int>(sum.size());
  for (int k = 0; k < nraw; ++k)
    if (hi[k] - lo[k] > consistency)
      throw core::GeometryError("polycube structure inconsistent: corners " + std::to_string(first[k]) +
                                " and others that must share their " + "xyz"[axis] +
                                " coordinate differ by " + std::to_string(hi[k] - lo[k]));
  // merge classes whose coordinates agree within tol; ids in coordinate order
  std::vector<int> order(static_cast<std::size_t>(nraw));
  std::iota(order.begin(), order.end(), 0);
  std::vector<double> mean(static_cast<std::size_t>(nraw));
  for (int k = 0; k < nraw; ++k) mean[k] = sum[k] / count[k];
  std::sort(order.begin(), order.end(), [&](int a, int b) { return mean[a] != mean[b] ? mean[a] < mean[b] : first[a] < first[b]; });
  std::vector<int> merged(static_cast<std::size_t>(nraw));
  AxisSystem sys;
  sys.axis = axis;
  std::vector<double> msum;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int k = order[i];
    if (i == 0 || mean[k] - mean[order[i - 1]] > tol) {
      msum.push_back(0.0);
      sys.class_size.push_back(0);
    }
    merged[k] = static_cast<int>(msum.size()) - 1;
    msum.back() += sum[k];
    sys.class_size.back() += count[k];
  }
  sys.coordinate.resize(msum.size());
  for (std::size_t m = 0; m < msum.size(); ++m) sys.coordinate[m] = scale * msum[m] / sys.class_size[m];
  sys.corner_class.resize(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) sys.corner_class[c] = merged[raw[c]];
  sys.chart_class.assign(s.charts.size(), -1);
  for (std::size_t p = 0; p < s.charts.size(); ++p)
    if (s.charts[p].axis == axis) {
      const auto cs = chart_corners(s, static_cast<int>(p));
      if (cs.empty()) throw core::GeometryError("chart " + std::to_string(p) + " has no corner");
      sys.chart_class[p] = sys.corner_class[cs[0]];
    }
  return sys;
}

//! Rectangles of a chart: rows of the grid of its own corner coordinates, merged into runs.
void chart_rectangles(const PolycubeStructure& s, const std::array<AxisSystem, 3>& ax, int chart,
                      std::vector<SurfaceBox>& out,
                      std::array<std::vector<std::array<int, 2>>, 3>& weak) {
  const int a = s.charts[chart].axis;
  const int u = (a + 1) % 3;
  const int v = (a + 2) % 3;
  const auto cs = chart_corners(s, chart);
  auto levels = [&](int axis) {
    std::vector<int> l;
    for (int c : cs) l.push_back(ax[axis].corner_class[c]);
    std::sort(l.begin(), l.end());  // class ids are in coordinate order
    l.erase(std::unique(l.begin(), l.end()), l.end());
    return l;
  };
  const auto ul = levels(u);
  const auto vl = levels(v);
  for (std::size_t i = 0; i + 1 < ul.size(); ++i) weak[u].push_back({ul[i], ul[i + 1]});
  for (std::size_t j = 0; j + 1 < vl.size(); ++j) weak[v].push_back({vl[j], vl[j + 1]});
  // polygon segments along v (for ray casting along +u)
  struct Seg {
    double u, v0, v1;
  };
  std::vector<Seg> segs;
  for (const auto& loop : s.faces[chart].loops) {
    const auto& lc = loop.corners;
    for (std::size_t k = 0; k < lc.size(); ++k) {
      const int c0 = lc[k];
      const int c1 = lc[(k + 1) % lc.size()];
      const int cu0 = ax[u].corner_class[c0];
      const int cu1 = ax[u].corner_class[c1];
      if (cu0 != cu1) continue;  // a segment along u (or degenerate)
      const double v0 = ax[v].coordinate[ax[v].corner_class[c0]];
      const double v1 = ax[v].coordinate[ax[v].corner_class[c1]];
      if (v0 == v1) continue;
      segs.push_back({ax[u].coordinate[cu0], std::min(v0, v1), std::max(v0, v1)});
    }
  }
  const int cls = ax[a].chart_class[chart];
  for (std::size_t j = 0; j + 1 < vl.size(); ++j) {
    const double cv = 0.5 * (ax[v].coordinate[vl[j]] + ax[v].coordinate[vl[j + 1]]);
    int run_start = -1;
    for (std::size_t i = 0; i + 1 <= ul.size(); ++i) {
      bool in = false;
      if (i + 1 < ul.size()) {
        const double cu = 0.5 * (ax[u].coordinate[ul[i]] + ax[u].coordinate[ul[i + 1]]);
        for (const Seg& sg : segs)
          if (sg.u > cu && sg.v0 < cv && cv < sg.v1) in = !in;
      }
      if (in && run_start < 0) run_start = static_cast<int>(i);
      if (!in && run_start >= 0) {
        SurfaceBox b;
        b.kind = SurfaceBox::Kind::Rectangle;
        b.id = chart;
        b.lo[a] = b.hi[a] = cls;
        b.lo[u] = ul[run_start];
        b.hi[u] = ul[i];
        b.lo[v] = vl[j];
        b.hi[v] = vl[j + 1];
        out.push_back(b);
        run_start = -1;
      }
    }
  }
}

//! Transitive reduction of a DAG whose arcs go from lower to higher ids.
std::vector<AxisConstraint> reduce(int n, const std::vector<std::uint8_t>& w /* n*n: 0 none, 1 weak, 2 strict */) {
  const std::size_t words = (static_cast<std::size_t>(n) + 63) / 64;
  std::vector<std::uint64_t> r0(static_cast<std::size_t>(n) * words, 0), r1(r0.size(), 0);
  auto set = [&](std::vector<std::uint64_t>& r, int i, int j) { r[i * words + j / 64] |= std::uint64_t{1} << (j % 64); };
  auto get = [&](const std::vector<std::uint64_t>& r, int i, int j) {
    return ((r[i * words + j / 64] >> (j % 64)) & 1U) != 0;
  };
  auto merge = [&](std::vector<std::uint64_t>& dst, int i, const std::vector<std::uint64_t>& src, int k) {
    for (std::size_t q = 0; q < words; ++q) dst[i * words + q] |= src[k * words + q];
  };
  for (int i = n - 1; i >= 0; --i)
    for (int k = i + 1; k < n; ++k) {
      const auto wk = w[static_cast<std::size_t>(i) * n + k];
      if (wk == 0) continue;
      set(r0, i, k);
      merge(r0, i, r0, k);
      if (wk == 2) {
        set(r1, i, k);
        merge(r1, i, r0, k);
      } else {
        merge(r1, i, r1, k);
      }
    }
  std::vector<AxisConstraint> out;
  std::vector<int> succ;
  for (int i = 0; i < n; ++i) {
    succ.clear();
    for (int k = i + 1; k < n; ++k)
      if (w[static_cast<std::size_t>(i) * n + k] != 0) succ.push_back(k);
    for (int j : succ) {
      const auto wj = w[static_cast<std::size_t>(i) * n + j];
      bool redundant = false;
      for (int k : succ) {
        if (k == j) continue;
        const auto wk = w[static_cast<std::size_t>(i) * n + k];
        redundant = wj == 2 ? ((wk == 2 && get(r0, k, j)) || get(r1, k, j)) : get(r0, k, j);
        if (redundant) break;
      }
      if (!redundant) out.push_back({i, j, wj == 2 ? 1 : 0});
    }
  }
  return out;
}

}  // namespace

CornerSystem build_corner_system(const PolycubeStructure& s, double scale, const CornerSystemOptions& options) {
  if (!(scale > 0.0) || !std::isfinite(scale)) throw core::InputError("simplify: scale must be positive");
  if (s.corners.empty()) throw core::GeometryError("polycube structure has no corner");
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const auto& ed = s.edges[e];
    if (ed.corners[0] < 0 || ed.corners[1] < 0)
      throw core::GeometryError("polycube edge " + std::to_string(e) + " is a closed loop without corners");
    if (ed.axis < 0) throw core::GeometryError("polycube edge " + std::to_string(e) + " joins two charts of one axis");
  }
  const double diag = bbox_diagonal(s);
  const double tol = options.tolerance * diag;
  CornerSystem sys;
  sys.scale = scale;
  for (int a = 0; a < 3; ++a) sys.axes[a] = make_classes(s, a, scale, tol, options.consistency_tolerance * diag);
  auto& ax = sys.axes;

  // boxes: corners, edges, chart rectangles
  for (std::size_t c = 0; c < s.corners.size(); ++c) {
    SurfaceBox b;
    b.kind = SurfaceBox::Kind::Corner;
    b.id = static_cast<int>(c);
    for (int a = 0; a < 3; ++a) b.lo[a] = b.hi[a] = ax[a].corner_class[c];
    sys.boxes.push_back(b);
  }
  // dense constraint weights per axis: 0 none, 1 weak, 2 strict (from lower to higher class id)
  std::array<std::vector<std::uint8_t>, 3> w;
  for (int a = 0; a < 3; ++a)
    w[a].assign(static_cast<std::size_t>(ax[a].num_classes()) * static_cast<std::size_t>(ax[a].num_classes()), 0);
  auto strict = [&](int a, int from, int to) {
    PC_REQUIRE(from < to, "strict constraint against coordinate order");
    w[a][static_cast<std::size_t>(from) * static_cast<std::size_t>(ax[a].num_classes()) + static_cast<std::size_t>(to)] = 2;
  };
  std::array<std::vector<std::array<int, 2>>, 3> weak_pairs;
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const auto& ed = s.edges[e];
    SurfaceBox b;
    b.kind = SurfaceBox::Kind::Edge;
    b.id = static_cast<int>(e);
    for (int a = 0; a < 3; ++a) {
      const int k0 = ax[a].corner_class[ed.corners[0]];
      const int k1 = ax[a].corner_class[ed.corners[1]];
      b.lo[a] = std::min(k0, k1);
      b.hi[a] = std::max(k0, k1);
    }
    if (b.lo[ed.axis] == b.hi[ed.axis])
      throw core::GeometryError("polycube edge " + std::to_string(e) + " has zero length");
    strict(ed.axis, b.lo[ed.axis], b.hi[ed.axis]);  // thesis eq. 3.3
    sys.boxes.push_back(b);
  }
  for (std::size_t p = 0; p < s.charts.size(); ++p) chart_rectangles(s, ax, static_cast<int>(p), sys.boxes, weak_pairs);
  for (std::size_t i = 0; i < sys.boxes.size(); ++i)
    if (sys.boxes[i].kind == SurfaceBox::Kind::Rectangle && s.charts[sys.boxes[i].id].axis == 0)
      sys.x_rectangles.push_back(static_cast<int>(i));

  // Separation (see the header): pairs of corners/edges as boxes, and corner/edge vs chart.
  const std::size_t nce = s.corners.size() + s.edges.size();  // boxes [0, nce) are corners and edges
  std::array<std::vector<double>, 3> lo_c, hi_c;
  for (int a = 0; a < 3; ++a) {
    lo_c[a].resize(nce);
    hi_c[a].resize(nce);
    for (std::size_t i = 0; i < nce; ++i) {
      lo_c[a][i] = ax[a].coordinate[sys.boxes[i].lo[a]];
      hi_c[a][i] = ax[a].coordinate[sys.boxes[i].hi[a]];
    }
  }
  // gap of box i below box j along a (> 0: separated), both orientations
  auto gap = [&](int a, std::size_t i, std::size_t j) { return lo_c[a][j] - hi_c[a][i]; };
  auto separate = [&](int a, std::size_t i, std::size_t j) {  // i below j along a
    strict(a, sys.boxes[i].hi[a], sys.boxes[j].lo[a]);
  };
  // 1. corner/edge vs corner/edge
  for (std::size_t i = 0; i < (options.separation ? nce : 0); ++i)
    for (std::size_t j = i + 1; j < nce; ++j) {
      int best = -1;
      double g = 0.0;
      bool i_low = true;
      for (int a = 0; a < 3; ++a) {
        const double g1 = gap(a, i, j), g2 = gap(a, j, i);
        if (std::max(g1, g2) > g) {
          g = std::max(g1, g2);
          best = a;
          i_low = g1 >= g2;
        }
      }
      if (best < 0) continue;  // touching in the input: incident
      ++sys.separation_pairs;
      if (i_low) separate(best, i, j);
      else separate(best, j, i);
    }
  // 2. corner/edge vs chart polygon
  std::vector<std::vector<int>> chart_edges(s.charts.size());
  for (std::size_t e = 0; e < s.edges.size(); ++e)
    for (int p : s.edges[e].charts) chart_edges[p].push_back(static_cast<int>(e));
  std::vector<std::vector<int>> chart_corner_lists(s.charts.size());
  for (std::size_t p = 0; p < s.charts.size(); ++p) chart_corner_lists[p] = chart_corners(s, static_cast<int>(p));
  auto touches = [&](std::size_t i, int p) {  // box i shares a corner with chart p
    const auto& cc = chart_corner_lists[p];
    if (i < s.corners.size()) return std::binary_search(cc.begin(), cc.end(), static_cast<int>(i));
    const auto& ed = s.edges[i - s.corners.size()];
    return ed.charts[0] == p || ed.charts[1] == p || std::binary_search(cc.begin(), cc.end(), ed.corners[0]) ||
           std::binary_search(cc.begin(), cc.end(), ed.corners[1]);
  };
  for (std::size_t p = 0; p < (options.separation ? s.charts.size() : 0); ++p) {
    const int a = s.charts[p].axis;
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    const int lvl = ax[a].chart_class[p];
    const double L = ax[a].coordinate[lvl];
    const auto& pe = chart_edges[p];
    for (std::size_t i = 0; i < nce; ++i) {
      if (touches(i, static_cast<int>(p))) continue;
      // in-plane: the box's projection against every edge of the polygon
      double inplane = INFINITY;
      for (int e : pe) {
        const std::size_t j = s.corners.size() + static_cast<std::size_t>(e);
        const double g = std::max({gap(u, i, j), gap(u, j, i), gap(v, i, j), gap(v, j, i)});
        inplane = std::min(inplane, g);
        if (!(inplane > 0.0)) break;
      }
      bool outside = inplane > 0.0;
      if (outside) {  // projection disjoint from the boundary: inside or outside the polygon?
        const double pu = lo_c[u][i], pv = lo_c[v][i];
        bool in = false;
        for (int e : pe) {
          const std::size_t j = s.corners.size() + static_cast<std::size_t>(e);
          if (sys.boxes[j].lo[u] != sys.boxes[j].hi[u]) continue;  // crossings of +u ray with v segments
          if (lo_c[u][j] > pu && lo_c[v][j] <= pv && pv < hi_c[v][j]) in = !in;
        }
        outside = !in;
      }
      const bool straddles = lo_c[a][i] <= L && L <= hi_c[a][i];
      const double normal = straddles ? 0.0 : std::max(lo_c[a][i] - L, L - hi_c[a][i]);
      if (!outside && normal <= 0.0) continue;  // touching in the input: incident
      ++sys.separation_pairs;
      if (!outside || normal >= inplane) {
        if (lo_c[a][i] > L) strict(a, lvl, sys.boxes[i].lo[a]);
        else strict(a, sys.boxes[i].hi[a], lvl);
        continue;
      }
      for (int e : pe) {
        const std::size_t j = s.corners.size() + static_cast<std::size_t>(e);
        int best = -1;
        double g = 0.0;
        bool i_low = true;
        for (int b : {u, v}) {
          const double g1 = gap(b, i, j), g2 = gap(b, j, i);
          if (std::max(g1, g2) > g) {
            g = std::max(g1, g2);
            best = b;
            i_low = g1 >= g2;
          }
        }
        if (i_low) separate(best, i, j);
        else separate(best, j, i);
      }
    }
  }

  // per axis: weak constraints, transitive reduction
  for (int a = 0; a < 3; ++a) {
    const int n = ax[a].num_classes();
    for (const auto& [f, t] : weak_pairs[a]) {
      PC_REQUIRE(f < t, "weak constraint against coordinate order");
      auto& x = w[a][static_cast<std::size_t>(f) * n + t];
      x = std::max<std::uint8_t>(x, 1);
    }
    ax[a].constraints_before_reduction = static_cast<int>(std::count_if(w[a].begin(), w[a].end(), [](auto x) { return x != 0; }));
    ax[a].constraints = reduce(n, w[a]);
  }
  return sys;
}

std::vector<std::string> find_contacts(const CornerSystem& sys, const PolycubeStructure& s,
                                       const std::array<std::vector<double>, 3>& values, int max_reported) {
  std::vector<std::string> out;
  const auto& ax = sys.axes;
  const std::size_t nc = s.corners.size();
  const std::size_t nce = nc + s.edges.size();
  auto name = [&](std::size_t i) {
    return i < nc ? "corner " + std::to_string(i) : "edge " + std::to_string(i - nc);
  };
  // bounds of box i along a, in the input (o) and at the new values (n)
  auto lo = [&](const std::array<std::vector<double>, 3>& val, int a, std::size_t i) {
    return std::min(val[a][sys.boxes[i].lo[a]], val[a][sys.boxes[i].hi[a]]);
  };
  auto hi = [&](const std::array<std::vector<double>, 3>& val, int a, std::size_t i) {
    return std::max(val[a][sys.boxes[i].lo[a]], val[a][sys.boxes[i].hi[a]]);
  };
  std::array<std::vector<double>, 3> orig;
  for (int a = 0; a < 3; ++a) orig[a] = ax[a].coordinate;
  auto disjoint = [&](const std::array<std::vector<double>, 3>& val, std::size_t i, std::size_t j, std::initializer_list<int> axes) {
    for (int a : axes)
      if (lo(val, a, j) > hi(val, a, i) || lo(val, a, i) > hi(val, a, j)) return true;
    return false;
  };
  auto report = [&](std::string m) {
    if (static_cast<int>(out.size()) < max_reported) out.push_back(std::move(m));
  };
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const int a = s.edges[e].axis;
    if (!(hi(values, a, nc + e) > lo(values, a, nc + e))) report("edge " + std::to_string(e) + " collapsed");
  }
  for (std::size_t i = 0; i < nce; ++i)
    for (std::size_t j = i + 1; j < nce; ++j)
      if (disjoint(orig, i, j, {0, 1, 2}) && !disjoint(values, i, j, {0, 1, 2}))
        report(name(i) + " touches " + name(j));
  std::vector<std::vector<int>> chart_edges(s.charts.size());
  for (std::size_t e = 0; e < s.edges.size(); ++e)
    for (int p : s.edges[e].charts) chart_edges[p].push_back(static_cast<int>(e));
  // does box i meet the closed polygon of chart p (at the given values)?
  auto meets = [&](const std::array<std::vector<double>, 3>& val, std::size_t i, std::size_t p) {
    const int a = s.charts[p].axis, u = (a + 1) % 3, v = (a + 2) % 3;
    const double L = val[a][ax[a].chart_class[p]];
    if (lo(val, a, i) > L || hi(val, a, i) < L) return false;
    for (int e : chart_edges[p])
      if (!disjoint(val, i, nc + static_cast<std::size_t>(e), {u, v})) return true;
    bool in = false;  // projection disjoint from the boundary: one point decides
    const double pu = lo(val, u, i), pv = lo(val, v, i);
    for (int e : chart_edges[p]) {
      const std::size_t j = nc + static_cast<std::size_t>(e);
      if (s.edges[e].axis != v) continue;
      if (lo(val, u, j) > pu && lo(val, v, j) <= pv && pv < hi(val, v, j)) in = !in;
    }
    return in;
  };
  for (std::size_t p = 0; p < s.charts.size(); ++p)
    for (std::size_t i = 0; i < nce; ++i)
      if (!meets(orig, i, p) && meets(values, i, p)) report(name(i) + " touches chart " + std::to_string(p));
  return out;
}

bool inside_polycube(const CornerSystem& sys, const PolycubeStructure& s,
                     const std::array<std::vector<double>, 3>& values, const core::Vec3& p) {
  bool in = false;
  (void)s;
  for (int r : sys.x_rectangles) {
    const SurfaceBox& b = sys.boxes[r];
    if (!(values[0][b.lo[0]] >= p.x())) continue;  // chart at or beyond the point: ray from p − δ·e_x
    const double y0 = values[1][b.lo[1]], y1 = values[1][b.hi[1]];
    const double z0 = values[2][b.lo[2]], z1 = values[2][b.hi[2]];
    // half-open [lo, hi) = the ray displaced by (+δ, +δ) in y and z
    if (y0 <= p.y() && p.y() < y1 && z0 <= p.z() && p.z() < z1) in = !in;
  }
  return in;
}

}  // namespace polycube::simplify
