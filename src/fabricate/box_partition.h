#pragma once
//! \file box_partition.h
//! \brief The polycube cut into axis-aligned boxes (thesis §6.2, ARCHITECTURE §6.7).
//!
//! The polycube's charts lie on a few planes per axis; those planes cut space into a rectilinear
//! grid whose cells are each inside or outside the polycube (OccupancyGrid). The thesis's sweep
//! splits the polycube at every concave edge by the two planes through it; here each plane's
//! cut is the connected region of interior grid faces of that plane that touches a concave edge
//! lying in it, extended until it meets the polycube's boundary. Every box of the result is a
//! connected set of cells with no concave edge left, i.e. a box. Merging (beyond the thesis:
//! its §6.6 used none) then joins adjacent boxes whose union is a box, largest union first.

#include "core/polycube_map.h"
#include "core/types.h"

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace polycube::fabricate {

//! The rectilinear grid of the polycube's chart planes, each cell inside or outside.
struct OccupancyGrid {
  std::array<std::vector<double>, 3> planes;  //!< sorted coordinates per axis (polycube space)
  std::vector<std::uint8_t> inside;           //!< per cell (x fastest), 1 inside the polycube

  [[nodiscard]] int cells(int axis) const { return static_cast<int>(planes[axis].size()) - 1; }
  [[nodiscard]] int index(int i, int j, int k) const { return i + cells(0) * (j + cells(1) * k); }
  [[nodiscard]] int index(const std::array<int, 3>& c) const { return index(c[0], c[1], c[2]); }
  //! Inside, with cells beyond the grid outside.
  [[nodiscard]] bool in(std::array<int, 3> c) const;
};

//! An axis-aligned box of grid cells [lo, hi) per axis.
struct Box {
  std::array<int, 3> lo{}, hi{};
  [[nodiscard]] long long cells() const {
    return static_cast<long long>(hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
  }
};

//! Two boxes touching along a plane: the rectangle they share.
struct Contact {
  std::array<int, 2> boxes{-1, -1};  //!< box a below the plane, box b above (along axis)
  int axis = 0;                      //!< normal axis of the shared plane
  int plane = 0;                     //!< grid plane index along axis
  std::array<int, 3> lo{}, hi{};  //!< the rectangle in grid indices (lo[axis] == hi[axis] == plane)
};

//! Boxes covering the polycube's cells exactly once, with their contacts.
struct BoxPartition {
  std::vector<Box> boxes;
  std::vector<int> cell_box;  //!< per grid cell: its box, -1 outside
  std::vector<Contact> contacts;
  int concave_edges =
      0;                //!< grid edges where the polycube boundary is concave (3 of 4 cells inside)
  int cut_regions = 0;  //!< plane regions the concave edges cut along
};

//! The occupancy grid of a polycube map's polycube: planes from its charts (within `tolerance`
//! of each other, relative to the polycube's bounding-box diagonal, merged), cells located in
//! its tets.
//! \throw core::InputError when the map has no tets or no chart on some axis
OccupancyGrid occupancy_grid(const core::PolycubeMap& map, double tolerance = 1e-6);

//! Cut the polycube at its concave edges (the thesis's sweep).
//! \throw core::InputError when the grid has no inside cell, or the polycube is not a manifold
//!        solid the sweep can handle (two cells touching along an edge only), naming where
BoxPartition partition_boxes(const OccupancyGrid& grid);

//! Join adjacent boxes whose union is a box, largest union first (ties: lowest box ids), while
//! `fits` (when given) accepts the union. Box ids are renumbered in order of their lowest cell.
void merge_boxes(const OccupancyGrid& grid, BoxPartition& partition,
                 const std::function<bool(const Box&)>& fits = nullptr);

//! cell_box and contacts of partition.boxes.
//! \throw core::InputError when the boxes do not cover the inside cells exactly once
void index_boxes(const OccupancyGrid& grid, BoxPartition& partition);

//! The grid with one more plane at `coordinate` on `axis` (cells it crosses split in two, each
//! half inside when the cell was); the same grid when a plane lies within `tolerance` (relative
//! to the grid's diagonal) of it. Returns the plane's index.
int insert_plane(OccupancyGrid& grid, int axis, double coordinate, double tolerance = 1e-9);

//! Split every box that grid plane `plane` of `axis` crosses into its two halves, then re-index.
void split_boxes(const OccupancyGrid& grid, BoxPartition& partition, int axis, int plane);

//! Length of the grid's diagonal (polycube units): what the tolerances are relative to, so a
//! model in micrometres or kilometres is cut as in millimetres.
double grid_diagonal(const OccupancyGrid& grid);

//! Box corner (i, j, k each 0 or 1 for lo or hi) in polycube coordinates.
core::Vec3 box_corner(const OccupancyGrid& grid, const Box& box, int i, int j, int k);

}  // namespace polycube::fabricate
