#pragma once
//! \file fixtures.h
//! \brief Tiny meshes built in code, shared by the tests of every folder.

#include "core/types.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace polycube::test {

using core::Vec3;

//! Structured nx x ny x nz hex grid, vertex (i,j,k) = i + (nx+1)(j + (ny+1)k) at position(i, j, k).
template <class Position>
core::HexMesh lattice_hexes(int nx, int ny, int nz, Position position) {
  core::HexMesh m;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.points.push_back(position(i, j, k));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.cells.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k),
                           id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
                           id(i, j + 1, k + 1)});
  return m;
}

//! Structured nx x ny x nz hex grid of cells of side h.
inline core::HexMesh hex_grid(int nx, int ny, int nz, double h = 1.0) {
  return lattice_hexes(nx, ny, nz, [h](int i, int j, int k) { return Vec3(h * i, h * j, h * k); });
}

//! nx by ny by nz grid of the box [0,sx] x [0,sy] x [0,sz].
inline core::HexMesh box_grid(int nx, int ny, int nz, double sx = 1, double sy = 1, double sz = 1) {
  return lattice_hexes(
      nx, ny, nz, [&](int i, int j, int k) { return Vec3(sx * i / nx, sy * j / ny, sz * k / nz); });
}

//! Six times the signed volume of tet `c` over the points `p`.
inline double tet_det(const std::vector<Vec3>& p, const core::Tet& c) {
  return (p[c[1]] - p[c[0]]).dot((p[c[2]] - p[c[0]]).cross(p[c[3]] - p[c[0]]));
}

//! How many flags of `s` are set (to 1).
inline int count_set(const std::vector<std::uint8_t>& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), 1));
}

inline double tet_volume(const core::TetMesh& m, int c) {
  return tet_det(m.points, m.cells[c]) / 6.0;
}

//! Split every hex into 6 tets around its 0-6 diagonal (conforming for a structured grid);
//! tets are made positive by swapping two vertices when needed.
inline core::TetMesh tetrahedralize(const core::HexMesh& h) {
  static constexpr std::array<std::array<int, 4>, 6> kSplit{
      {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}}};
  core::TetMesh t;
  t.points = h.points;
  for (const auto& c : h.cells)
    for (const auto& s : kSplit) {
      t.cells.push_back({c[s[0]], c[s[1]], c[s[2]], c[s[3]]});
      if (tet_volume(t, t.num_cells() - 1) < 0) std::swap(t.cells.back()[2], t.cells.back()[3]);
    }
  return t;
}

//! Torus surface: nu x nv grid of quads (outward), major radius R, minor radius r.
inline core::QuadMesh torus_quads(int nu, int nv, double R = 2.0, double r = 0.7) {
  core::QuadMesh m;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * std::numbers::pi * i / nu;
      const double v = 2 * std::numbers::pi * j / nv;
      m.points.emplace_back((R + r * std::cos(v)) * std::cos(u),
                            (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + nu) % nu) * nv + (j + nv) % nv; };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j)
      m.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

//! Split quads 0-1-2, 0-2-3.
inline core::TriMesh split_quads(const core::QuadMesh& q) {
  core::TriMesh t;
  t.points = q.points;
  for (const auto& c : q.cells) {
    t.cells.push_back({c[0], c[1], c[2]});
    t.cells.push_back({c[0], c[2], c[3]});
  }
  return t;
}

//! Octahedron (outward), optionally subdivided `levels` times (1:4) and projected to the unit
//! sphere.
inline core::TriMesh sphere(int levels) {
  core::TriMesh m;
  m.points = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
              Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  m.cells = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
             {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      m.points.push_back((0.5 * (m.points[a] + m.points[b])).normalized());
      const int id = m.num_points() - 1;
      mid.emplace(key, id);
      return id;
    };
    std::vector<core::Tri> next;
    for (const auto& c : m.cells) {
      const int ab = midpoint(c[0], c[1]), bc = midpoint(c[1], c[2]), ca = midpoint(c[2], c[0]);
      next.push_back({c[0], ab, ca});
      next.push_back({ab, c[1], bc});
      next.push_back({ca, bc, c[2]});
      next.push_back({ab, bc, ca});
    }
    m.cells = std::move(next);
  }
  return m;
}

//! Flat n x n grid of triangles in the plane z = 0 (a disk, counter-clockwise seen from +z).
inline core::TriMesh tri_grid(int n) {
  core::TriMesh m;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.emplace_back(i, j, 0.0);
  auto id = [&](int i, int j) { return i + (n + 1) * j; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.cells.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.cells.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

//! A triangular prism 4 long whose section is a V: the keel (y 0, z 0) and the top corners
//! (y +-1, z 2), so that its two lower faces are 63.4 degrees from straight down (printable alone).
//! Turned about y so that the keel rises at `rise` degrees from its end at the origin.
inline core::TriMesh keel_prism(double rise_degrees) {
  core::TriMesh m;
  for (const double x : {0.0, 4.0})
    for (const Vec3& p : {Vec3(x, 0, 0), Vec3(x, 1, 2), Vec3(x, -1, 2)}) m.points.push_back(p);
  // 0 1 2 at x = 0, 3 4 5 at x = 4; outward.
  m.cells = {{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3},
             {0, 3, 5}, {0, 5, 2}, {1, 2, 5}, {1, 5, 4}};
  const Eigen::Matrix3d turn(Eigen::AngleAxisd(-rise_degrees * M_PI / 180.0, Vec3::UnitY()));
  for (Vec3& p : m.points) p = turn * p;
  return m;
}

}  // namespace polycube::test
