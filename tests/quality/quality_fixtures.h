#pragma once
//! \file quality_fixtures.h
//! \brief Meshes built in code for the quality tests: single elements, voxel polycubes gridded at
//! any resolution, a padded box, icospheres, tet grids.

#include "core/elements.h"
#include "core/topology.h"
#include "core/types.h"

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

namespace polycube::test {

using core::Vec3;

//! Unit cube corners in the canonical hex order.
inline std::array<Vec3, 8> unit_hex() {
  return {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
          Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
}

//! A polycube made of unit voxels (integer corner coordinates), gridded with n hexes per unit:
//! every voxel becomes n^3 hexes sharing lattice vertices. Deterministic numbering.
inline core::HexMesh voxel_polycube(const std::vector<std::array<int, 3>>& voxels, int n) {
  core::HexMesh m;
  std::map<std::tuple<int, int, int>, int> ids;
  auto vid = [&](int x, int y, int z) {
    auto [it, inserted] = ids.try_emplace({x, y, z}, m.num_points());
    if (inserted) m.points.emplace_back(double(x) / n, double(y) / n, double(z) / n);
    return it->second;
  };
  for (const auto& v : voxels)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const int x = v[0] * n + i, y = v[1] * n + j, z = v[2] * n + k;
          m.cells.push_back({vid(x, y, z), vid(x + 1, y, z), vid(x + 1, y + 1, z), vid(x, y + 1, z),
                             vid(x, y, z + 1), vid(x + 1, y, z + 1), vid(x + 1, y + 1, z + 1),
                             vid(x, y + 1, z + 1)});
        }
  return m;
}

//! Box of nx x ny x nz unit voxels gridded at resolution n.
inline core::HexMesh gridded_box(int nx, int ny, int nz, int n) {
  std::vector<std::array<int, 3>> voxels;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) voxels.push_back({i, j, k});
  return voxel_polycube(voxels, n);
}

//! Pillow (globally pad) a hex mesh: every boundary quad is extruded outwards into one hex.
//! The outer copy of a boundary vertex p is p + offset(p).
template <class Offset>
core::HexMesh pad(const core::HexMesh& in, Offset offset) {
  core::HexMesh m = in;
  const core::HexBoundary b = core::boundary(in);
  std::vector<int> outer(b.vertex_map.size());
  for (std::size_t s = 0; s < b.vertex_map.size(); ++s) {
    outer[s] = m.num_points();
    const Vec3 p = in.points[b.vertex_map[s]];
    m.points.push_back(p + offset(p));
  }
  // Boundary quads are outward: counter-clockwise seen from outside = the bottom ring of a hex
  // whose top is outside.
  for (const auto& q : b.surface.cells)
    m.cells.push_back({b.vertex_map[q[0]], b.vertex_map[q[1]], b.vertex_map[q[2]],
                       b.vertex_map[q[3]], outer[q[0]], outer[q[1]], outer[q[2]], outer[q[3]]});
  return m;
}

//! Box [0,1]^3 gridded n x n x n, padded by a layer of thickness t (outer box [-t, 1+t]^3).
inline core::HexMesh padded_box(int n, double t = 0.25) {
  return pad(gridded_box(1, 1, 1, n), [t](const Vec3& p) {
    Vec3 d = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      if (p[i] < 1e-9) d[i] = -t;
      if (p[i] > 1 - 1e-9) d[i] = t;
    }
    return d;
  });
}

//! Triangle icosphere of the given radius: the icosahedron subdivided `level` times (each
//! triangle into 4), vertices projected on the sphere, optionally rotated.
inline core::TriMesh icosphere(int level, double radius,
                               const Eigen::Matrix3d& rotation = Eigen::Matrix3d::Identity()) {
  core::TriMesh m;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> p = {{-1, g, 0},  {1, g, 0},  {-1, -g, 0}, {1, -g, 0}, {0, -1, g},  {0, 1, g},
                         {0, -1, -g}, {0, 1, -g}, {g, 0, -1},  {g, 0, 1},  {-g, 0, -1}, {-g, 0, 1}};
  for (auto& v : p) v.normalize();
  std::vector<core::Tri> t = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                              {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                              {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                              {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = mid.try_emplace({key.first, key.second}, static_cast<int>(p.size()));
      if (inserted) p.push_back((p[a] + p[b]).normalized());
      return it->second;
    };
    std::vector<core::Tri> next;
    for (const auto& f : t) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    t = std::move(next);
  }
  for (auto& v : p) m.points.push_back(radius * (rotation * v));
  m.cells = t;
  return m;
}

inline double signed_tet_volume(const std::vector<Vec3>& p, const core::Tet& t) {
  return (p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) / 6.0;
}

//! Tet mesh of an n^3 grid on [0,1]^3: each hex split into 6 positive tets around its 0-6
//! diagonal.
inline core::TetMesh tet_grid(int n) {
  static constexpr std::array<std::array<int, 4>, 6> kSplit{
      {{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}}};
  const core::HexMesh h = gridded_box(1, 1, 1, n);
  core::TetMesh t;
  t.points = h.points;
  for (const auto& c : h.cells)
    for (const auto& s : kSplit) {
      core::Tet tet{c[s[0]], c[s[1]], c[s[2]], c[s[3]]};
      if (signed_tet_volume(t.points, tet) < 0) std::swap(tet[2], tet[3]);
      t.cells.push_back(tet);
    }
  return t;
}

}  // namespace polycube::test
