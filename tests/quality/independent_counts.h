#pragma once
// Singular edges and vertices, base-complex blocks (#D) and the boundary quad layout's singular
// vertices and patches of a closed hex mesh, counted from the raw cells with maps and a union-find
// written here, independently of src/core/topology and src/quality: the reference the report's
// counts are checked against (ARCHITECTURE §6.1, the cinolib definitions).
#include "core/types.h"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

namespace polycube::test {

struct IndependentCounts {
  int singular_edges = 0, boundary_singular_edges = 0, interior_singular_edges = 0;
  int singular_vertices = 0;
  int domains = 0;
  int surface_singular_vertices = 0;
  int surface_domains = 0;
};

namespace detail {

using Edge = std::pair<int, int>;
using Face = std::array<int, 4>;  // sorted vertex ids

inline Edge edge_key(int a, int b) { return {std::min(a, b), std::max(a, b)}; }
inline Face face_key(Face f) {
  std::sort(f.begin(), f.end());
  return f;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
  void join(int a, int b) { parent[find(a)] = find(b); }
  int components() {
    std::set<int> roots;
    for (int i = 0; i < static_cast<int>(parent.size()); ++i) roots.insert(find(i));
    return static_cast<int>(roots.size());
  }
};

}  // namespace detail

inline IndependentCounts independent_counts(const core::HexMesh& m) {
  using namespace detail;
  // Hex faces in VTK order (outward when the hex is positive; orientation is not used here).
  static const int kFaces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                   {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::map<Face, std::vector<int>> face_hexes;
  std::map<Face, Face> face_ring;  // sorted key -> vertices in cyclic order
  for (int h = 0; h < static_cast<int>(m.cells.size()); ++h)
    for (const auto& f : kFaces) {
      const Face ring{m.cells[h][f[0]], m.cells[h][f[1]], m.cells[h][f[2]], m.cells[h][f[3]]};
      face_hexes[face_key(ring)].push_back(h);
      face_ring[face_key(ring)] = ring;
    }
  std::map<Edge, std::set<int>> edge_hexes;
  std::map<Edge, std::vector<Face>> edge_faces;
  std::set<Edge> boundary_edges;
  for (const auto& [key, hexes] : face_hexes) {
    const Face& r = face_ring[key];
    for (int i = 0; i < 4; ++i) {
      const Edge e = edge_key(r[i], r[(i + 1) % 4]);
      edge_faces[e].push_back(key);
      edge_hexes[e].insert(hexes.begin(), hexes.end());
      if (hexes.size() == 1) boundary_edges.insert(e);
    }
  }
  IndependentCounts c;
  // Singular edges: boundary with #hexes != 2, interior with #hexes != 4.
  std::set<Edge> singular;
  std::map<int, int> singular_at;
  for (const auto& [e, hexes] : edge_hexes) {
    const bool boundary = boundary_edges.count(e) > 0;
    const int n = static_cast<int>(hexes.size());
    if (boundary ? n == 2 : n == 4) continue;
    singular.insert(e);
    ++(boundary ? c.boundary_singular_edges : c.interior_singular_edges);
    ++singular_at[e.first];
    ++singular_at[e.second];
  }
  c.singular_edges = static_cast<int>(singular.size());
  for (const auto& [v, n] : singular_at) c.singular_vertices += (n != 0 && n != 2);

  // Sheets: interior faces at a singular edge, grown across regular interior edges to the face
  // that shares no hex with the current one.
  std::set<Face> traced;
  std::vector<Face> stack;
  for (const auto& e : singular)
    for (const auto& f : edge_faces[e])
      if (face_hexes[f].size() == 2 && traced.insert(f).second) stack.push_back(f);
  while (!stack.empty()) {
    const Face f = stack.back();
    stack.pop_back();
    const Face& r = face_ring[f];
    for (int i = 0; i < 4; ++i) {
      const Edge e = edge_key(r[i], r[(i + 1) % 4]);
      if (singular.count(e) || boundary_edges.count(e)) continue;
      for (const auto& g : edge_faces[e]) {
        const auto& a = face_hexes[f];
        const auto& b = face_hexes[g];
        const bool shares = std::any_of(a.begin(), a.end(), [&](int h) {
          return std::find(b.begin(), b.end(), h) != b.end();
        });
        if (!shares && traced.insert(g).second) stack.push_back(g);
      }
    }
  }
  UnionFind blocks(static_cast<int>(m.cells.size()));
  for (const auto& [f, hexes] : face_hexes)
    if (hexes.size() == 2 && !traced.count(f)) blocks.join(hexes[0], hexes[1]);
  c.domains = blocks.components();

  // Boundary quad layout of a closed mesh: every vertex is interior to the surface, singular
  // when not in exactly 4 boundary quads; separatrices run straight on at regular vertices.
  std::vector<Face> quads;
  for (const auto& [f, hexes] : face_hexes)
    if (hexes.size() == 1) quads.push_back(face_ring[f]);
  std::map<int, int> valence;
  std::map<Edge, std::vector<int>> edge_quads;
  std::map<int, std::vector<Edge>> vertex_edges;
  for (int q = 0; q < static_cast<int>(quads.size()); ++q)
    for (int i = 0; i < 4; ++i) {
      ++valence[quads[q][i]];
      const Edge e = edge_key(quads[q][i], quads[q][(i + 1) % 4]);
      auto& qs = edge_quads[e];
      if (qs.empty()) {
        vertex_edges[e.first].push_back(e);
        vertex_edges[e.second].push_back(e);
      }
      qs.push_back(q);
    }
  std::set<int> singular_vertex;
  for (const auto& [v, n] : valence)
    if (n != 4) singular_vertex.insert(v);
  c.surface_singular_vertices = static_cast<int>(singular_vertex.size());
  std::set<Edge> traced_edges;
  std::vector<std::pair<Edge, int>> walk;  // edge, vertex it leaves from
  for (const int v : singular_vertex)
    for (const auto& e : vertex_edges[v])
      if (traced_edges.insert(e).second) walk.emplace_back(e, v);
  while (!walk.empty()) {
    const auto [e, from] = walk.back();
    walk.pop_back();
    const int to = e.first == from ? e.second : e.first;
    if (singular_vertex.count(to)) continue;
    for (const auto& g : vertex_edges[to]) {
      const auto& a = edge_quads[e];
      const auto& b = edge_quads[g];
      const bool shares = std::any_of(a.begin(), a.end(), [&](int q) {
        return std::find(b.begin(), b.end(), q) != b.end();
      });
      if (!shares && traced_edges.insert(g).second) walk.emplace_back(g, to);
    }
  }
  UnionFind patches(static_cast<int>(quads.size()));
  for (const auto& [e, qs] : edge_quads)
    if (qs.size() == 2 && !traced_edges.count(e)) patches.join(qs[0], qs[1]);
  c.surface_domains = patches.components();
  return c;
}

}  // namespace polycube::test
