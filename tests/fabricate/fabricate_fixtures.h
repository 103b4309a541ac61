#pragma once
// A T of 4 unit hexes (cells (0..2, 0) and (1, 1)) tetrahedralized, as a polycube map whose
// model space is the affine image A x + shift: planes fitted to mapped points are exact, so
// the figures of every step are known by hand.
#include "core/polycube_map.h"

#include "../support/fixtures.h"

#include <Eigen/Dense>

namespace polycube::test {

struct AffineT {
  Eigen::Matrix3d A;
  core::Vec3 shift{1, -2, 3};
  core::PolycubeMap map;
};

inline AffineT affine_t() {
  AffineT t;
  t.A << 2, 0.5, 0, 0.1, 3, 0.2, 1, 0, 0.5;
  core::HexMesh h = hex_grid(3, 2, 1);
  h.cells.erase(h.cells.begin() + 5);  // cell (2, 1, 0)
  h.cells.erase(h.cells.begin() + 3);  // cell (0, 1, 0)
  const core::TetMesh tets = tetrahedralize(h);
  t.map.tets = tets.cells;
  t.map.polycube = tets.points;
  for (const auto& p : tets.points) t.map.model.push_back(t.A * p + t.shift);
  return t;
}

}  // namespace polycube::test
