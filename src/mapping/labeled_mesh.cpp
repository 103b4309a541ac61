//! Labeled tet meshes and their chart variables (see labeled_mesh.h).
#include "mapping/labeled_mesh.h"

#include "core/charts.h"
#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "core/polycube_map.h"
#include "core/topology.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <utility>

namespace polycube::mapping {

namespace {

using core::Tri;
using core::Vec3;

std::array<int, 3> sorted(const Tri& t) {
  std::array<int, 3> k{t[0], t[1], t[2]};
  std::sort(k.begin(), k.end());
  return k;
}

//! The boundary of mesh in core::boundary() order with the labels of `given` (same triangles,
//! any order and orientation) and the owning tets.
void match_boundary(LabeledTetMesh& lm, const std::vector<Tri>& given, const std::vector<int>& labels) {
  const core::TetBoundary b = core::boundary(lm.mesh);
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
  std::vector<Tri> tris = core::boundary_triangles(b);
  std::vector<int> matched(nb);
  for (std::size_t f = 0; f < nb; ++f) {
    const auto k = sorted(tris[f]);
    auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    if (it == keys.end() || it->first != k)
      throw core::InputError(fmt::format("deform: boundary face ({}, {}, {}) of the tet mesh has no label", k[0], k[1], k[2]));
    matched[f] = it->second;
  }
  lm.boundary = std::move(tris);
  lm.labels = std::move(matched);
  lm.boundary_cell = b.cell_of_face;
}

}  // namespace

LabeledTetMesh label_tet_mesh(core::TetMesh mesh, const std::vector<Tri>& tris, const std::vector<int>& labels) {
  LabeledTetMesh lm;
  lm.mesh = std::move(mesh);
  match_boundary(lm, tris, labels);
  update_charts(lm);
  return lm;
}

void refresh_boundary(LabeledTetMesh& lm) {
  const std::vector<Tri> tris = lm.boundary;
  const std::vector<int> labels = lm.labels;
  match_boundary(lm, tris, labels);
}

void update_charts(LabeledTetMesh& lm) { lm.charts = chart_variables(lm.mesh.num_points(), lm.boundary, lm.labels); }

ChartVariables chart_variables(int nv, const std::vector<Tri>& tris, const std::vector<int>& labels) {
  ChartVariables cv;
  const int nb = static_cast<int>(tris.size());
  core::TriangleCharts charts = core::triangle_charts(tris, labels);
  cv.triangle_chart = std::move(charts.triangle_chart);
  cv.num_charts = charts.count;
  std::vector<int> chart_axis(static_cast<std::size_t>(cv.num_charts));
  for (int t = 0; t < nb; ++t) chart_axis[cv.triangle_chart[t]] = labels[t] / 2;
  // Charts of one axis sharing a vertex share their coordinate.
  core::DisjointSets cu(static_cast<std::size_t>(cv.num_charts));
  std::vector<int> first(3 * static_cast<std::size_t>(nv), -1);
  for (int t = 0; t < nb; ++t) {
    const int c = cv.triangle_chart[t];
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

std::vector<int> forced_flat_triangles(const LabeledTetMesh& lm) {
  const std::vector<Tri>& tris = lm.boundary;
  const std::vector<int>& labels = lm.labels;
  const ChartVariables& cv = lm.charts;
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

std::vector<std::array<int, 2>> chord_edges(const LabeledTetMesh& lm) {
  const std::vector<Tri>& tris = lm.boundary;
  const std::vector<int>& labels = lm.labels;
  const ChartVariables& cv = lm.charts;
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
    if (cv.triangle_chart[t0] != cv.triangle_chart[t1]) continue;
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

std::vector<std::array<int, 2>> thin_fan_edges(const LabeledTetMesh& lm, int min_fan) {
  const int nv = lm.mesh.num_points();
  const std::vector<Tri>& tris = lm.boundary;
  const std::vector<int>& labels = lm.labels;
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

int split_edges(LabeledTetMesh& lm, const std::vector<std::array<int, 2>>& edges, std::vector<Vec3>* other) {
  core::TetMesh& mesh = lm.mesh;
  // Vertex -> cells and vertex -> boundary triangles, kept up to date while splitting: an edge
  // that shares a vertex with an edge split earlier in this call must see the new cells, or it
  // would be split in some of its tets only (a hanging node, a non-conforming mesh).
  std::vector<std::vector<int>> vc(static_cast<std::size_t>(mesh.num_points()));
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (int w : mesh.cells[c]) vc[w].push_back(static_cast<int>(c));
  std::vector<std::vector<int>> vt(static_cast<std::size_t>(mesh.num_points()));
  for (std::size_t t = 0; t < lm.boundary.size(); ++t)
    for (int w : lm.boundary[t]) vt[w].push_back(static_cast<int>(t));
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
      Tri& tri = lm.boundary[t];
      if (std::find(tri.begin(), tri.end(), v) == tri.end()) continue;
      Tri second = tri;
      for (int& w : tri)
        if (w == v) w = m;
      for (int& w : second)
        if (w == u) w = m;
      const int t2 = static_cast<int>(lm.boundary.size());
      lm.boundary.push_back(second);
      lm.labels.push_back(lm.labels[t]);
      drop(vt[v], t);
      vt[m].push_back(t);
      for (int w : second) vt[w].push_back(t2);
    }
    ++count;
  }
  return count;
}

namespace {

//! Append the centroid of `face` to the mesh's points (and to `other` when given); its index.
int add_face_centroid(core::TetMesh& mesh, const std::array<int, 3>& face, std::vector<Vec3>* other) {
  const int m = mesh.num_points();
  mesh.points.push_back((mesh.points[face[0]] + mesh.points[face[1]] + mesh.points[face[2]]) / 3.0);
  if (other) other->push_back(((*other)[face[0]] + (*other)[face[1]] + (*other)[face[2]]) / 3.0);
  return m;
}

//! Tet t in three, point m (inside its face `face`) taking each face vertex's place in turn:
//! replacing one face vertex by a point inside the face keeps the orientation.
void split_tet_at_face_point(core::TetMesh& mesh, int t, const std::array<int, 3>& face, int m) {
  const core::Tet old = mesh.cells[t];
  for (int k = 0; k < 3; ++k) {
    core::Tet nt = old;
    for (int& v : nt)
      if (v == face[k]) v = m;
    if (k == 0) {
      mesh.cells[t] = nt;
    } else {
      mesh.cells.push_back(nt);
      if (!mesh.labels.empty()) mesh.labels.push_back(mesh.labels[t]);
    }
  }
}

}  // namespace

bool split_boundary_triangle(LabeledTetMesh& lm, int f, std::vector<char>& touched, std::vector<Vec3>* other) {
  core::TetMesh& mesh = lm.mesh;
  const int t = lm.boundary_cell[f];
  if (touched[t]) return false;
  const Tri tri = lm.boundary[f];
  const int m = add_face_centroid(mesh, tri, other);
  split_tet_at_face_point(mesh, t, tri, m);
  touched.resize(mesh.cells.size(), 1);
  touched[t] = 1;
  const int label = lm.labels[f];
  lm.boundary[f] = {m, tri[1], tri[2]};
  lm.boundary.push_back({tri[0], m, tri[2]});
  lm.boundary.push_back({tri[0], tri[1], m});
  lm.labels.push_back(label);
  lm.labels.push_back(label);
  return true;
}

std::vector<LockedVertex> locked_interior_vertices(const LabeledTetMesh& lm) {
  const core::TetMesh& mesh = lm.mesh;
  const std::vector<int>& group = lm.charts.vertex_group;
  const auto nv = static_cast<std::size_t>(mesh.num_points());
  std::vector<char> on_boundary(nv, 0);
  for (const Tri& t : lm.boundary)
    for (int v : t) on_boundary[v] = 1;
  std::set<std::array<int, 3>> boundary_faces;
  for (Tri t : lm.boundary) {
    std::sort(t.begin(), t.end());
    boundary_faces.insert(t);
  }
  std::vector<std::array<int, 3>> shared(nv, {-1, -1, -1});
  for (const auto& c : mesh.cells)
    for (int v : c) {
      if (on_boundary[v]) continue;
      for (int w : c) {
        if (w == v) continue;
        for (int a = 0; a < 3; ++a) {
          const int g = group[3 * static_cast<std::size_t>(w) + a];
          int& s = shared[v][a];
          if (g < 0) s = -2;
          else if (s == -1) s = g;
          else if (s != g) s = -2;
        }
      }
    }
  std::vector<LockedVertex> out;
  for (const auto& c : mesh.cells)
    for (int k = 0; k < 4; ++k) {
      const int v = c[k];
      if (on_boundary[v] || std::none_of(shared[v].begin(), shared[v].end(), [](int g) { return g >= 0; })) continue;
      std::array<int, 3> face{};
      for (int i = 0, j = 0; i < 4; ++i)
        if (i != k) face[j++] = c[i];
      std::sort(face.begin(), face.end());
      if (!boundary_faces.count(face)) out.push_back({v, face});
    }
  return out;
}

bool split_interior_face(LabeledTetMesh& lm, std::array<int, 3> face, std::vector<char>& touched,
                         std::vector<Vec3>* other) {
  core::TetMesh& mesh = lm.mesh;
  std::sort(face.begin(), face.end());
  std::vector<int> cells;
  for (int t = 0; t < mesh.num_cells(); ++t) {
    int hits = 0;
    for (int v : mesh.cells[t]) hits += std::binary_search(face.begin(), face.end(), v) ? 1 : 0;
    if (hits == 3) cells.push_back(t);
  }
  if (cells.size() != 2 || touched[cells[0]] || touched[cells[1]]) return false;
  const int m = add_face_centroid(mesh, face, other);
  for (int t : cells) split_tet_at_face_point(mesh, t, face, m);
  touched.resize(mesh.cells.size(), 1);
  for (int t : cells) touched[t] = 1;
  return true;
}

MapVariables map_variables(const LabeledTetMesh& lm) {
  MapVariables mv;
  const std::vector<int>& group = lm.charts.vertex_group;
  mv.var.assign(3 * static_cast<std::size_t>(lm.mesh.num_points()), -1);
  int n = lm.charts.num_groups;
  for (std::size_t i = 0; i < mv.var.size(); ++i) mv.var[i] = group[i] >= 0 ? group[i] : n++;
  mv.count = n;
  return mv;
}

int facing_away(const LabeledTetMesh& lm, const std::vector<Vec3>& P) {
  int n = 0;
  for (std::size_t f = 0; f < lm.boundary.size(); ++f) n += !core::faces_label(P, lm.boundary[f], lm.labels[f]);
  return n;
}

int failures(const LabeledTetMesh& lm, const std::vector<Vec3>& P) {
  int n = facing_away(lm, P);
  for (const auto& c : lm.mesh.cells) n += !core::positive_tet(P, c);
  return n;
}

}  // namespace polycube::mapping
