#pragma once
// Polycube maps built analytically in code, for the structure and gridding tests.
//
// A polycube is a union of cells of a rectilinear grid (coordinates gx, gy, gz); each inside
// cell is split into the 6 Kuhn tetrahedra (conforming across cells). The model positions are a
// closed-form deformation of the polycube positions at the tet vertices, so the map is the
// piecewise-linear interpolant of the deformation on the tets. pl_image() evaluates that
// interpolant independently of the library (cell by binary search, Kuhn simplex by sorting the
// local coordinates), which gives exact expected positions for lattice points.

#include "core/polycube_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

namespace polycube::test {

using core::Vec3;

//! n+1 equally spaced values from a to b.
inline std::vector<double> uniform(double a, double b, int n) {
  std::vector<double> v;
  for (int i = 0; i <= n; ++i) v.push_back(a + (b - a) * i / n);
  return v;
}

//! Sorted union of coordinate lists (exact duplicates removed).
inline std::vector<double> merged(std::vector<double> a, const std::vector<double>& b) {
  a.insert(a.end(), b.begin(), b.end());
  std::sort(a.begin(), a.end());
  a.erase(std::unique(a.begin(), a.end()), a.end());
  return a;
}

struct GridMap {
  std::array<std::vector<double>, 3> g;     // grid coordinates per axis
  std::function<bool(const Vec3&)> inside;  // is a cell (given its centre) in the polycube
  std::function<Vec3(const Vec3&)> deform;  // model position of a polycube point
  core::PolycubeMap map;

  [[nodiscard]] bool cell_inside(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i + 1 >= static_cast<int>(g[0].size()) ||
        j + 1 >= static_cast<int>(g[1].size()) || k + 1 >= static_cast<int>(g[2].size()))
      return false;
    const Vec3 c(0.5 * (g[0][i] + g[0][i + 1]), 0.5 * (g[1][j] + g[1][j + 1]),
                 0.5 * (g[2][k] + g[2][k + 1]));
    return inside(c);
  }

  //! The piecewise-linear map evaluated at polycube point q (false when q is outside).
  bool pl_image(const Vec3& q, Vec3& out, double tol = 1e-12) const {
    // candidate cells per axis: the cell containing q, both when q is on a grid plane
    std::array<std::vector<int>, 3> cand;
    for (int a = 0; a < 3; ++a) {
      const auto& ga = g[a];
      const int n = static_cast<int>(ga.size()) - 1;
      for (int i = 0; i < n; ++i)
        if (q[a] >= ga[i] - tol && q[a] <= ga[i + 1] + tol) cand[a].push_back(i);
    }
    for (int i : cand[0])
      for (int j : cand[1])
        for (int k : cand[2]) {
          if (!cell_inside(i, j, k)) continue;
          const std::array<int, 3> c{i, j, k};
          std::array<double, 3> f{};
          for (int a = 0; a < 3; ++a)
            f[a] = std::clamp((q[a] - g[a][c[a]]) / (g[a][c[a] + 1] - g[a][c[a]]), 0.0, 1.0);
          std::array<int, 3> order{0, 1, 2};
          std::stable_sort(order.begin(), order.end(), [&](int x, int y) { return f[x] > f[y]; });
          // Kuhn simplex: v0 = corner, then add unit steps in decreasing order of f.
          std::array<int, 3> idx = c;
          const double lam0 = 1.0 - f[order[0]];
          Vec3 acc = lam0 * deform(point(idx));
          for (int s = 0; s < 3; ++s) {
            idx[order[s]] += 1;
            const double lam = f[order[s]] - (s < 2 ? f[order[s + 1]] : 0.0);
            acc += lam * deform(point(idx));
          }
          out = acc;
          return true;
        }
    return false;
  }

  [[nodiscard]] Vec3 point(const std::array<int, 3>& idx) const {
    return {g[0][idx[0]], g[1][idx[1]], g[2][idx[2]]};
  }
};

//! Build the map: vertices of inside cells (numbered in x-fastest order), 6 Kuhn tets per cell
//! (positively oriented), model = deform(polycube).
inline GridMap make_grid_map(std::vector<double> gx, std::vector<double> gy, std::vector<double> gz,
                             std::function<bool(const Vec3&)> inside,
                             std::function<Vec3(const Vec3&)> deform) {
  GridMap m;
  m.g = {std::move(gx), std::move(gy), std::move(gz)};
  m.inside = std::move(inside);
  m.deform = std::move(deform);
  const int nx = static_cast<int>(m.g[0].size());
  const int ny = static_cast<int>(m.g[1].size());
  const int nz = static_cast<int>(m.g[2].size());
  std::vector<int> id(static_cast<std::size_t>(nx * ny * nz), -1);
  auto gid = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        if (m.cell_inside(i, j, k))
          for (int c = 0; c < 8; ++c)
            id[gid(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] = 0;
  int nv = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (id[gid(i, j, k)] == 0) {
          id[gid(i, j, k)] = nv++;
          const Vec3 p = m.point({i, j, k});
          m.map.polycube.push_back(p);
          m.map.model.push_back(m.deform(p));
        }
  const std::array<std::array<int, 3>, 6> perms{
      {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  const std::array<bool, 6> odd{false, true, true, false, false, true};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        if (!m.cell_inside(i, j, k)) continue;
        for (int p = 0; p < 6; ++p) {
          std::array<int, 3> idx{i, j, k};
          core::Tet t{};
          t[0] = id[gid(idx[0], idx[1], idx[2])];
          for (int s = 0; s < 3; ++s) {
            idx[perms[p][s]] += 1;
            t[s + 1] = id[gid(idx[0], idx[1], idx[2])];
          }
          if (odd[p]) std::swap(t[1], t[2]);
          m.map.tets.push_back(t);
        }
      }
  return m;
}

// --- the polycubes of the tests ---------------------------------------------------------------

//! L-shaped polycube of 3 unit cubes: ([0,2]x[0,1] u [0,1]x[1,2]) x [0,1], r grid steps per unit.
inline GridMap l_shape(
    int r, std::function<Vec3(const Vec3&)> deform = [](const Vec3& p) { return p; }) {
  return make_grid_map(
      uniform(0, 2, 2 * r), uniform(0, 2, 2 * r), uniform(0, 1, r),
      [](const Vec3& c) { return c.x() < 1 || c.y() < 1; }, std::move(deform));
}

//! Polycube volume and surface area of l_shape (scaled by s).
inline constexpr double kLVolume = 3.0;
inline constexpr double kLArea = 14.0;

}  // namespace polycube::test
