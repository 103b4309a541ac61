#pragma once
//! \file shapes.h
//! \brief Small closed surfaces built in code, shared by the tests of every folder.
#include "core/types.h"

#include <cmath>
#include <map>
#include <numbers>
#include <utility>

namespace polycube::test {

//! Axis-aligned box [0,sx]x[0,sy]x[0,sz], each face split into n x n quads (2 triangles each),
//! outward.
inline core::TriMesh make_box(double sx, double sy, double sz, int n = 1, core::Vec3 offset = core::Vec3::Zero()) {
  core::TriMesh m;
  std::map<std::array<long, 3>, int> index;  // lattice coordinates -> vertex
  auto vertex = [&](int i, int j, int k) {
    const std::array<long, 3> key{i, j, k};
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    const int id = m.num_points();
    m.points.emplace_back(offset + core::Vec3(sx * i / n, sy * j / n, sz * k / n));
    index.emplace(key, id);
    return id;
  };
  // For each axis and side, (u, v) spans the face; orientation chosen so normals point out.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3;
      const int v = (axis + 2) % 3;
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          auto at = [&](int da, int db) {
            std::array<int, 3> c{};
            c[axis] = side * n;
            c[u] = a + da;
            c[v] = b + db;
            return vertex(c[0], c[1], c[2]);
          };
          const int p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if (side == 1) {
            m.cells.push_back({p00, p10, p11});
            m.cells.push_back({p00, p11, p01});
          } else {
            m.cells.push_back({p00, p11, p10});
            m.cells.push_back({p00, p01, p11});
          }
        }
    }
  return m;
}

//! A UV sphere of radius r (rings x segments), outward.
inline core::TriMesh make_sphere(double r, int rings, int segments) {
  core::TriMesh m;
  const double pi = std::numbers::pi;
  m.points.emplace_back(0, 0, r);
  for (int i = 1; i < rings; ++i) {
    const double th = pi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double ph = 2 * pi * j / segments + 0.37;  // avoid symmetric ties with the axes
      m.points.emplace_back(r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th));
    }
  }
  m.points.emplace_back(0, 0, -r);
  const int south = m.num_points() - 1;
  auto id = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.cells.push_back({0, id(1, j), id(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      m.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j) m.cells.push_back({south, id(rings - 1, j + 1), id(rings - 1, j)});
  return m;
}

//! A torus around the z axis (major radius R, minor r), outward.
inline core::TriMesh make_torus(double R, double r, int nu, int nv) {
  core::TriMesh m;
  const double pi = std::numbers::pi;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * pi * i / nu + 0.11;
      const double v = 2 * pi * j / nv;
      m.points.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      m.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

//! `b` appended to `a` as a separate set of vertices.
inline core::TriMesh join(core::TriMesh a, const core::TriMesh& b) {
  const int base = a.num_points();
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (core::Tri t : b.cells) {
    for (int& v : t) v += base;
    a.cells.push_back(t);
  }
  return a;
}

//! Every triangle turned the other way (an outward surface faces inward).
inline core::TriMesh turned(core::TriMesh m) {
  for (core::Tri& t : m.cells) std::swap(t[1], t[2]);
  return m;
}

//! Every triangle with its own three vertices, as many exporters write.
inline core::TriMesh soup_of(const core::TriMesh& m) {
  core::TriMesh s;
  for (const core::Tri& t : m.cells) {
    const int base = s.num_points();
    for (const int v : t) s.points.push_back(m.points[static_cast<std::size_t>(v)]);
    s.cells.push_back({base, base + 1, base + 2});
  }
  return s;
}

//! Coarse CAD-like solids, too coarse to label as they are (construct refines them).
//! A wedge of 8 triangles: a triangular prism 20 long on a 10-wide base, 8 high.
inline core::TriMesh wedge() {
  core::TriMesh m;
  m.points = {{0, 0, 0}, {0, 10, 0}, {0, 5, 8}, {20, 0, 0}, {20, 10, 0}, {20, 5, 8}};
  m.cells = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  return m;
}

//! A square pyramid of 6 triangles, 10 wide and 7 high.
inline core::TriMesh pyramid() {
  core::TriMesh m;
  m.points = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}, {5, 5, 7}};
  m.cells = {{0, 2, 1}, {0, 3, 2}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return m;
}

//! A regular tetrahedron with edges 10 long, standing on the plane z = 0.
inline core::TriMesh regular_tetrahedron() {
  core::TriMesh m;
  const double h = 10.0 * std::sqrt(3.0) / 2.0;
  m.points = {{0, 0, 0}, {10, 0, 0}, {5, h, 0}, {5, h / 3.0, 10.0 * std::sqrt(2.0 / 3.0)}};
  m.cells = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return m;
}

}  // namespace polycube::test
