#pragma once
//! \file corners.h
//! \brief Box corners mapped back to model space through the polycube map (thesis §6.2): each
//! corner is located in a tet of the polycube and takes the same barycentric combination of that
//! tet's model-space vertices.

#include "core/polycube_map.h"
#include "fabricate/box_partition.h"
#include "mesh/tet_locator.h"

#include <vector>

namespace polycube::fabricate {

//! Polycube-space points taken to model space through the map: the tet holding the point (or
//! the nearest one), the same barycentric coordinates in its model-space twin.
class ToModel {
 public:
  //! \param tolerance distance within which a point counts as inside a tet, relative to the
  //!        polycube's bounding-box diagonal
  explicit ToModel(const core::PolycubeMap& map, double tolerance = 1e-6);
  //! The model-space point of q; `located` says whether q was inside a tet.
  core::Vec3 operator()(const core::Vec3& q, bool* located = nullptr) const;

 private:
  const core::PolycubeMap& map_;
  mesh::TetLocator locator_;
};

//! Model-space corners of every box.
struct BoxCorners {
  //! #boxes * 8: corner (i, j, k) of box b (each 0 for lo, 1 for hi) at 8 b + i + 2 j + 4 k
  std::vector<core::Vec3> model;
  int not_located = 0;  //!< corners outside every tet, mapped through the nearest one
};

//! Map the corners of the partition's boxes into model space.
//! \param tolerance distance within which a corner counts as inside a tet, relative to the
//!        polycube's bounding-box diagonal
BoxCorners map_corners(const core::PolycubeMap& map, const OccupancyGrid& grid,
                       const BoxPartition& partition, double tolerance = 1e-6);

//! The mapped centre of every box of the partition.
std::vector<core::Vec3> map_centres(const ToModel& to_model, const OccupancyGrid& grid,
                                    const BoxPartition& partition);

}  // namespace polycube::fabricate
