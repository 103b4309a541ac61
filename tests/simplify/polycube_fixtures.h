#pragma once
// Polycube maps built in code for the simplification tests: a union of cells of a rectilinear
// grid (coordinates gx, gy, gz), each cell split into the 6 Kuhn tetrahedra (conforming across
// cells, positively oriented). The model positions are a smooth deformation of the polycube
// positions (the identity by default), so the map is valid by construction.

#include "core/polycube_map.h"

#include <array>
#include <functional>
#include <vector>

namespace polycube::test {

using core::Vec3;

//! Map of the union of the inside cells (i, j, k) of the grid gx × gy × gz.
inline core::PolycubeMap grid_polycube(const std::vector<double>& gx, const std::vector<double>& gy,
                                       const std::vector<double>& gz,
                                       const std::function<bool(int, int, int)>& inside,
                                       const std::function<Vec3(const Vec3&)>& deform = [](const Vec3& p) { return p; }) {
  const int nx = static_cast<int>(gx.size()), ny = static_cast<int>(gy.size()), nz = static_cast<int>(gz.size());
  auto cell_in = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i + 1 < nx && j + 1 < ny && k + 1 < nz && inside(i, j, k);
  };
  std::vector<int> id(static_cast<std::size_t>(nx * ny * nz), -1);
  auto gid = [&](int i, int j, int k) { return (k * ny + j) * nx + i; };
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        if (cell_in(i, j, k))
          for (int c = 0; c < 8; ++c) id[gid(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1))] = 0;
  core::PolycubeMap map;
  int nv = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        if (id[gid(i, j, k)] == 0) {
          id[gid(i, j, k)] = nv++;
          const Vec3 p(gx[i], gy[j], gz[k]);
          map.polycube.push_back(p);
          map.model.push_back(deform(p));
        }
  const std::array<std::array<int, 3>, 6> perms{{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
  const std::array<bool, 6> odd{false, true, true, false, false, true};
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i) {
        if (!cell_in(i, j, k)) continue;
        for (int p = 0; p < 6; ++p) {
          std::array<int, 3> idx{i, j, k};
          core::Tet t{};
          t[0] = id[gid(idx[0], idx[1], idx[2])];
          for (int s = 0; s < 3; ++s) {
            idx[perms[p][s]] += 1;
            t[s + 1] = id[gid(idx[0], idx[1], idx[2])];
          }
          if (odd[p]) std::swap(t[1], t[2]);
          map.tets.push_back(t);
        }
      }
  return map;
}

//! Comb (thesis fig. 3.5 in 3D): five teeth of width 1 along x, height 3, with two notches
//! whose floors are at y = 1.0 and y = 1.0 + delta (x in [1,2] and [3,4]); depth z in [0,1].
//! The two floors' planes run through the whole base: aligning them saves a layer of blocks.
inline core::PolycubeMap comb(double delta = 0.1) {
  const std::vector<double> gx{0, 1, 2, 3, 4, 5};
  const std::vector<double> gy{0, 1.0, 1.0 + delta, 3};
  const std::vector<double> gz{0, 1};
  return grid_polycube(gx, gy, gz, [](int i, int j, int) {
    if (i == 1) return j == 0;       // notch 1: floor at y = 1.0
    if (i == 3) return j <= 1;       // notch 2: floor at y = 1.0 + delta
    return true;
  });
}

//! Fig. 3.6 case: a C shape (bottom bar, left column, top bar) with a bump on the bottom bar
//! whose top (y = 3 − gap) nearly touches the top bar's underside (y = 3). Aligning the bump
//! top with the underside would make the parts touch: the constraints must keep them apart.
inline core::PolycubeMap c_with_bump(double gap = 0.1) {
  const std::vector<double> gx{0, 1, 2, 2.5, 3};
  const std::vector<double> gy{0, 1, 3 - gap, 3, 4};
  const std::vector<double> gz{0, 1};
  return grid_polycube(gx, gy, gz, [](int i, int j, int) {
    if (j == 0 || j == 3) return true;  // bottom and top bars
    if (i == 0) return true;            // left column
    if (i == 2 && j == 1) return true;  // bump x in [2, 2.5], y in [1, 3 - gap]
    return false;
  });
}

}  // namespace polycube::test
