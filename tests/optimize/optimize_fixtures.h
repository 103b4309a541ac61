#pragma once
// Small hex meshes and target surfaces built in code for the optimize tests.

#include "core/types.h"

#include <cmath>
#include <functional>
#include <random>

namespace polycube::test {

//! nx by ny by nz grid of the box [0,sx] x [0,sy] x [0,sz].
inline core::HexMesh box_grid(int nx, int ny, int nz, double sx = 1, double sy = 1, double sz = 1) {
  core::HexMesh m;
  auto id = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) m.points.emplace_back(sx * i / nx, sy * j / ny, sz * k / nz);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        m.cells.push_back({id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k), id(i, j, k + 1),
                           id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)});
  return m;
}

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
