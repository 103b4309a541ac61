//! Box corners mapped back to model space (see corners.h).
#include "fabricate/corners.h"

#include "mesh/tet_locator.h"

namespace polycube::fabricate {

BoxCorners map_corners(const core::PolycubeMap& map, const OccupancyGrid& grid,
                       const BoxPartition& partition, double tolerance) {
  const mesh::TetLocator locator(map.tets, map.polycube, tolerance);
  BoxCorners out;
  out.model.reserve(8 * partition.boxes.size());
  for (const Box& b : partition.boxes)
    for (int c = 0; c < 8; ++c) {
      bool located = false;
      const auto hit = mesh::locate_or_nearest(
          locator, box_corner(grid, b, c & 1, (c >> 1) & 1, (c >> 2) & 1), located);
      out.not_located += located ? 0 : 1;
      out.model.push_back(mesh::map_through(map.tets, map.model, hit));
    }
  return out;
}

}  // namespace polycube::fabricate
