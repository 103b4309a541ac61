#include "structure/structure.h"

#include "core/charts.h"
#include "core/errors.h"
#include "core/topology.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace polycube::structure {

namespace {

using core::Vec3;


//! In-plane axes (u, v) of a chart so that e_u x e_v is its outward normal.
std::pair<int, int> plane_axes(int axis, int sign) {
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  return sign > 0 ? std::pair{u, v} : std::pair{v, u};
}

//! Signed area of a closed polygon of map vertices in a chart's plane, seen from outside.
double loop_area(const std::vector<int>& verts, const std::vector<Vec3>& pos, int axis, int sign) {
  const auto [u, v] = plane_axes(axis, sign);
  double a = 0.0;
  const Vec3& o = pos[verts[0]];
  for (std::size_t i = 1; i + 1 < verts.size(); ++i) {
    const Vec3 p = pos[verts[i]] - o;
    const Vec3 q = pos[verts[i + 1]] - o;
    a += p[u] * q[v] - p[v] * q[u];
  }
  return 0.5 * a;
}

}  // namespace

int PolycubeStructure::num_convex_edges() const {
  return static_cast<int>(
      std::count_if(edges.begin(), edges.end(), [](const Edge& e) { return e.convex; }));
}
int PolycubeStructure::num_concave_edges() const {
  return static_cast<int>(edges.size()) - num_convex_edges();
}
int PolycubeStructure::num_faces_with_holes() const {
  return static_cast<int>(
      std::count_if(faces.begin(), faces.end(), [](const Face& f) { return f.num_holes() > 0; }));
}
double PolycubeStructure::max_chart_deviation() const {
  double d = 0.0;
  for (const Chart& c : charts) d = std::max(d, c.deviation);
  return d;
}

PolycubeStructure extract_structure(const core::PolycubeMap& map) {
  core::check_map_indices(map);
  const std::vector<Vec3>& pos = map.polycube;
  PolycubeStructure s;

  // 1. boundary triangles (local surface ids inside, map ids in the result)
  const core::TetBoundary bnd = core::boundary(map.polycube_mesh());
  const core::TriMesh& surf = bnd.surface;
  const int nf = surf.num_cells();
  const auto& vmap = bnd.vertex_map;
  s.triangles.resize(static_cast<std::size_t>(nf));
  s.triangle_tet = bnd.cell_of_face;
  s.triangle_label.resize(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    const auto& t = surf.cells[f];
    s.triangles[f] = {vmap[t[0]], vmap[t[1]], vmap[t[2]]};
    const Vec3& a = surf.points[t[0]];
    s.triangle_label[f] =
        core::dominant_axis_label((surf.points[t[1]] - a).cross(surf.points[t[2]] - a));
  }

  // 2. charts: components of equally labelled triangles through manifold edges
  const core::TriangleCharts tc = core::triangle_charts(s.triangles, s.triangle_label);
  s.triangle_chart = tc.triangle_chart;
  s.charts.resize(static_cast<std::size_t>(tc.count));
  for (int f = 0; f < nf; ++f) {
    Chart& c = s.charts[s.triangle_chart[f]];
    if (c.triangles.empty()) {  // the chart's first triangle
      c.label = s.triangle_label[f];
      c.axis = core::label_axis(c.label);
      c.sign = core::label_sign(c.label);
    }
    c.triangles.push_back(f);
  }
  const auto et = core::unique_edges(surf);
  const core::Adjacency ec = core::edge_cells(et);
  for (Chart& c : s.charts) {
    std::vector<int> verts;
    for (int f : c.triangles) {
      for (int v : s.triangles[f]) verts.push_back(v);
      const Vec3& a = pos[s.triangles[f][0]];
      c.area += 0.5 * (pos[s.triangles[f][1]] - a).cross(pos[s.triangles[f][2]] - a).norm();
    }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    double sum = 0.0;
    for (int v : verts) sum += pos[v][c.axis];
    c.coordinate = sum / static_cast<double>(verts.size());
    for (int v : verts)
      c.deviation = std::max(c.deviation, std::abs(pos[v][c.axis] - c.coordinate));
  }

  // 3. corners: vertices where three or more charts meet
  const core::Adjacency vc = core::vertex_cells(surf);
  s.vertex_corner.assign(static_cast<std::size_t>(map.num_vertices()), -1);
  for (int lv = 0; lv < surf.num_points(); ++lv) {
    std::vector<int> charts;
    for (int f : vc[lv]) charts.push_back(s.triangle_chart[f]);
    std::sort(charts.begin(), charts.end());
    charts.erase(std::unique(charts.begin(), charts.end()), charts.end());
    if (charts.size() < 3) continue;
    Corner c;
    c.vertex = vmap[lv];
    c.position = pos[c.vertex];
    c.charts = std::move(charts);
    s.vertex_corner[c.vertex] = static_cast<int>(s.corners.size());
    s.corners.push_back(std::move(c));
  }

  // 4. polycube edges: chains of feature edges (two different charts), cut at corners
  std::vector<char> feature(static_cast<std::size_t>(et.num_edges()), 0);
  for (int e = 0; e < et.num_edges(); ++e)
    feature[e] = ec.degree(e) == 2 && s.triangle_chart[ec[e][0]] != s.triangle_chart[ec[e][1]];
  const int nlv = surf.num_points();
  std::vector<std::vector<int>> vfeat(static_cast<std::size_t>(nlv));
  for (int e = 0; e < et.num_edges(); ++e)
    if (feature[e]) {
      vfeat[et.edges[e][0]].push_back(e);
      vfeat[et.edges[e][1]].push_back(e);
    }
  auto chart_pair = [&](int e) {
    std::array<int, 2> p{s.triangle_chart[ec[e][0]], s.triangle_chart[ec[e][1]]};
    if (p[0] > p[1]) std::swap(p[0], p[1]);
    return p;
  };
  auto is_corner_local = [&](int lv) { return s.vertex_corner[vmap[lv]] >= 0; };
  std::vector<char> used(static_cast<std::size_t>(et.num_edges()), 0);
  std::vector<std::vector<int>> edge_mesh_edges;  // mesh edges of each polycube edge
  auto trace = [&](int start_lv, int first_edge) {
    Edge pe;
    pe.charts = chart_pair(first_edge);
    std::vector<int> chain{start_lv};
    std::vector<int> medges;
    int lv = start_lv;
    int e = first_edge;
    while (e >= 0 && !used[e]) {
      used[e] = 1;
      medges.push_back(e);
      lv = et.edges[e][0] == lv ? et.edges[e][1] : et.edges[e][0];
      chain.push_back(lv);
      if (is_corner_local(lv) || lv == start_lv) break;
      int next = -1;
      for (int e2 : vfeat[lv])  // sorted by edge id: deterministic
        if (!used[e2] && chart_pair(e2) == pe.charts) {
          next = e2;
          break;
        }
      e = next;
    }
    const bool closed = chain.size() > 2 && chain.front() == chain.back();
    if (closed) chain.pop_back();
    for (int v : chain) pe.vertices.push_back(vmap[v]);
    if (!closed) {
      pe.corners = {s.vertex_corner[pe.vertices.front()], s.vertex_corner[pe.vertices.back()]};
    }
    edge_mesh_edges.push_back(std::move(medges));
    s.edges.push_back(std::move(pe));
  };
  for (const Corner& c : s.corners) {
    const auto lv =
        static_cast<int>(std::lower_bound(vmap.begin(), vmap.end(), c.vertex) - vmap.begin());
    for (int e : vfeat[lv])
      if (!used[e]) trace(lv, e);
  }
  for (int e = 0; e < et.num_edges(); ++e)  // loops without corners (not in a valid polycube)
    if (feature[e] && !used[e]) trace(et.edges[e][0], e);

  // axis, length, convexity
  for (std::size_t i = 0; i < s.edges.size(); ++i) {
    Edge& pe = s.edges[i];
    const Chart& ca = s.charts[pe.charts[0]];
    const Chart& cb = s.charts[pe.charts[1]];
    pe.axis = ca.axis == cb.axis ? -1 : 3 - ca.axis - cb.axis;
    for (std::size_t k = 0; k + 1 < pe.vertices.size(); ++k)
      pe.length += (pos[pe.vertices[k + 1]] - pos[pe.vertices[k]]).norm();
    if (pe.vertices.size() > 2 && pe.corners[0] < 0)
      pe.length += (pos[pe.vertices.front()] - pos[pe.vertices.back()]).norm();
    // Convex when the triangle of chart b leaves the edge on the inner side of chart a's plane.
    double vote = 0.0;
    for (int e : edge_mesh_edges[i]) {
      const int fa = s.triangle_chart[ec[e][0]] == pe.charts[0] ? ec[e][0] : ec[e][1];
      const int fb = fa == ec[e][0] ? ec[e][1] : ec[e][0];
      (void)fa;
      const int u = vmap[et.edges[e][0]];
      int w = -1;
      for (int v : s.triangles[fb])
        if (v != u && v != vmap[et.edges[e][1]]) w = v;
      vote += ca.sign * (pos[w][ca.axis] - pos[u][ca.axis]);
    }
    pe.convex = vote < 0.0;
  }
  for (std::size_t i = 0; i < s.edges.size(); ++i)
    for (int c : s.edges[i].corners)
      if (c >= 0) s.corners[c].edges.push_back(static_cast<int>(i));
  for (Corner& c : s.corners) {
    std::sort(c.edges.begin(), c.edges.end());
    c.edges.erase(std::unique(c.edges.begin(), c.edges.end()), c.edges.end());
  }

  // 5. faces: boundary loops of each chart, oriented as the triangles (ccw from outside)
  s.faces.resize(s.charts.size());
  for (std::size_t ci = 0; ci < s.charts.size(); ++ci) {
    const Chart& ch = s.charts[ci];
    Face& face = s.faces[ci];
    face.chart = static_cast<int>(ci);
    std::vector<std::array<int, 2>> half;  // (from, to) map vertices
    for (int f : ch.triangles)
      for (int k = 0; k < 3; ++k) {
        const int e = et.cell_edges[f][k];
        const bool interior = ec.degree(e) == 2 &&
                              s.triangle_chart[ec[e][0]] == static_cast<int>(ci) &&
                              s.triangle_chart[ec[e][1]] == static_cast<int>(ci);
        if (!interior) half.push_back({s.triangles[f][k], s.triangles[f][(k + 1) % 3]});
      }
    std::sort(half.begin(), half.end());
    std::vector<char> taken(half.size(), 0);
    std::vector<Loop> loops;
    for (std::size_t h0 = 0; h0 < half.size(); ++h0) {
      if (taken[h0]) continue;
      Loop loop;
      std::size_t h = h0;
      while (true) {
        taken[h] = 1;
        loop.vertices.push_back(half[h][0]);
        const int to = half[h][1];
        if (to == half[h0][0]) break;
        auto it = std::lower_bound(half.begin(), half.end(), std::array<int, 2>{to, -1});
        std::size_t next = half.size();
        for (; it != half.end() && (*it)[0] == to; ++it)
          if (!taken[static_cast<std::size_t>(it - half.begin())]) {
            next = static_cast<std::size_t>(it - half.begin());
            break;
          }
        if (next == half.size()) break;  // broken chain (invalid map): keep what we have
        h = next;
      }
      // Start at the loop's lowest corner (or lowest vertex) for determinism.
      std::size_t start = 0;
      int best_corner = -1;
      for (std::size_t k = 0; k < loop.vertices.size(); ++k) {
        const int c = s.vertex_corner[loop.vertices[k]];
        if (c >= 0 && (best_corner < 0 || c < best_corner)) {
          best_corner = c;
          start = k;
        }
      }
      if (best_corner < 0)
        start = static_cast<std::size_t>(
            std::min_element(loop.vertices.begin(), loop.vertices.end()) - loop.vertices.begin());
      std::rotate(loop.vertices.begin(), loop.vertices.begin() + static_cast<std::ptrdiff_t>(start),
                  loop.vertices.end());
      for (int v : loop.vertices)
        if (s.vertex_corner[v] >= 0) loop.corners.push_back(s.vertex_corner[v]);
      loop.area = loop.vertices.size() >= 3 ? loop_area(loop.vertices, pos, ch.axis, ch.sign) : 0.0;
      loops.push_back(std::move(loop));
    }
    // Outer loop (largest signed area) first, then holes in discovery order.
    if (!loops.empty()) {
      auto outer = std::max_element(loops.begin(), loops.end(),
                                    [](const Loop& a, const Loop& b) { return a.area < b.area; });
      std::rotate(loops.begin(), outer, outer + 1);
    }
    face.loops = std::move(loops);
  }
  return s;
}

}  // namespace polycube::structure
