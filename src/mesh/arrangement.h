#pragma once
//! \file arrangement.h
//! \brief The polycube seen as a union of boxes of the rectilinear grid of its chart planes
//! ("levels"): what the gridding (grid.h) scales onto the integer lattice and what the
//! fabrication's box partition cuts.

#include "core/types.h"
#include "mesh/tet_locator.h"
#include "structure/structure.h"

#include <array>
#include <vector>

namespace polycube::mesh {

struct Arrangement {
  std::array<std::vector<double>, 3> level;  //!< distinct chart coordinates per axis, increasing
  std::vector<int> chart_level;              //!< level index of each chart (along its axis)
  std::vector<char> inside;                  //!< per box (i fastest, then j, then k)
  double tolerance = 0.0;                    //!< absolute level tolerance (polycube units)

  [[nodiscard]] int boxes(int a) const { return static_cast<int>(level[a].size()) - 1; }
  [[nodiscard]] std::size_t box_index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * boxes(1) + j) * boxes(0) + i;
  }
  [[nodiscard]] bool is_inside(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= boxes(0) || j >= boxes(1) || k >= boxes(2)) return false;
    return inside[box_index(i, j, k)] != 0;
  }
  //! Index of the level nearest to x along axis a.
  [[nodiscard]] int nearest_level(int a, double x) const;
};

//! Levels: the chart coordinates of each axis clustered (a gap larger than tol starts a new
//! level), and the planes of `extra` strictly between the first and last of them and farther
//! than tol from every one (planes of no chart: a lattice finer between them,
//! GridOptions::refine_near); a box is inside when its centre lies in a tet of the locator (no
//! chart crosses a box).
//! \throw core::InputError with fewer than two levels on an axis, or more than max_boxes boxes
Arrangement build_arrangement(const structure::PolycubeStructure& s, const TetLocator& locator,
                              double tol, long long max_boxes,
                              const std::array<std::vector<double>, 3>& extra = {});

}  // namespace polycube::mesh
