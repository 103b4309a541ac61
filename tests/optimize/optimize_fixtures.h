#pragma once
// Small hex meshes and target surfaces built in code for the optimize tests.

#include "support/fixtures.h"
#include "core/topology.h"
#include "core/types.h"

#include <cmath>
#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

namespace polycube::test {

//! The box [0,sx] x [0,sy] x [0,sz] as 12 outward triangles.
inline core::TriMesh box_surface(double sx = 1, double sy = 1, double sz = 1) {
  core::TriMesh t;
  for (int c = 0; c < 8; ++c) t.points.emplace_back(c & 1 ? sx : 0, c & 2 ? sy : 0, c & 4 ? sz : 0);
  // quads as corner bit patterns, outward
  const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : q) {
    t.cells.push_back({f[0], f[1], f[2]});
    t.cells.push_back({f[0], f[2], f[3]});
  }
  return t;
}

//! The unit sphere as an icosahedron subdivided `levels` times (vertices on the sphere, faces
//! outward).
inline core::TriMesh sphere_surface(int levels) {
  core::TriMesh t;
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  for (const auto& p : {core::Vec3(-1, g, 0), core::Vec3(1, g, 0), core::Vec3(-1, -g, 0), core::Vec3(1, -g, 0),
                        core::Vec3(0, -1, g), core::Vec3(0, 1, g), core::Vec3(0, -1, -g), core::Vec3(0, 1, -g),
                        core::Vec3(g, 0, -1), core::Vec3(g, 0, 1), core::Vec3(-g, 0, -1), core::Vec3(-g, 0, 1)})
    t.points.push_back(p.normalized());
  t.cells = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
             {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
             {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      t.points.push_back((t.points[a] + t.points[b]).normalized());
      return mid[key] = t.num_points() - 1;
    };
    std::vector<std::array<int, 3>> next;
    for (const auto& f : t.cells) {
      const int a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.insert(next.end(), {{f[0], a, c}, {f[1], b, a}, {f[2], c, b}, {a, b, c}});
    }
    t.cells = next;
  }
  return t;
}

//! n by n by n grid of the cube [-1,1]³ mapped into the unit ball by pushing every point out
//! radially from the max-norm sphere to the Euclidean one (the boundary lands on the sphere).
//! Its corner hexes have three faces on the sphere, nearly coplanar: a poor scaled Jacobian
//! the optimizer could raise by pulling their vertices off the surface.
inline core::HexMesh ball_grid(int n) {
  core::HexMesh m = box_grid(n, n, n, 2, 2, 2);
  for (auto& p : m.points) {
    p -= core::Vec3(1, 1, 1);
    if (p.norm() > 0) p *= p.lpNorm<Eigen::Infinity>() / p.norm();
  }
  return m;
}

//! A bar of positive hexes bent along a circle by `turn` full turns: past one turn every hex is
//! still valid, but its end overlaps its start, so the boundary crosses itself.
inline core::HexMesh bent_bar(double turn) {
  const int n = 40;
  core::HexMesh m = box_grid(n, 1, 1, 1.0, 0.2, 0.2);
  for (auto& p : m.points) {
    const double a = turn * 2 * std::numbers::pi * p.x();
    const double r = 1.0 + p.y();
    p = core::Vec3(r * std::cos(a), -r * std::sin(a), p.z());
  }
  return m;
}

//! The boundary of a hex mesh as a triangle surface (each quad split along its 0-2 diagonal).
inline core::TriMesh boundary_surface(const core::HexMesh& m) {
  const core::HexBoundary b = core::boundary(m);
  core::TriMesh t;
  t.points = b.surface.points;
  for (const auto& q : b.surface.cells) {
    t.cells.push_back({q[0], q[1], q[2]});
    t.cells.push_back({q[0], q[2], q[3]});
  }
  return t;
}

//! Move every point by a seeded uniform random offset of at most `amplitude` per coordinate,
//! where `which(p)` holds.
inline void perturb(core::HexMesh& m, double amplitude, unsigned seed,
                    const std::function<bool(const core::Vec3&)>& which) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (auto& p : m.points) {
    const core::Vec3 d(u(rng), u(rng), u(rng));
    if (which(p)) p += d;
  }
}

}  // namespace polycube::test
