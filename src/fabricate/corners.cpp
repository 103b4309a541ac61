//! Box corners mapped back to model space (see corners.h).
#include "fabricate/corners.h"

namespace polycube::fabricate {

ToModel::ToModel(const core::PolycubeMap& map, double tolerance)
    : map_(map),
      locator_(map.tets, map.polycube, tolerance * core::bounding_box(map.polycube).diagonal()) {}

core::Vec3 ToModel::operator()(const core::Vec3& q, bool* located) const {
  bool inside = false;
  const auto hit = mesh::locate_or_nearest(locator_, q, inside);
  if (located) *located = inside;
  return mesh::map_through(map_.tets, map_.model, hit);
}

BoxCorners map_corners(const core::PolycubeMap& map, const OccupancyGrid& grid,
                       const BoxPartition& partition, double tolerance) {
  const ToModel to_model(map, tolerance);
  BoxCorners out;
  out.model.reserve(8 * partition.boxes.size());
  for (const Box& b : partition.boxes)
    for (int c = 0; c < 8; ++c) {
      bool located = false;
      out.model.push_back(
          to_model(box_corner(grid, b, c & 1, (c >> 1) & 1, (c >> 2) & 1), &located));
      out.not_located += located ? 0 : 1;
    }
  return out;
}

std::vector<core::Vec3> map_centres(const ToModel& to_model, const OccupancyGrid& grid,
                                    const BoxPartition& partition) {
  std::vector<core::Vec3> out;
  out.reserve(partition.boxes.size());
  for (const Box& b : partition.boxes)
    out.push_back(to_model(0.5 * (box_corner(grid, b, 0, 0, 0) + box_corner(grid, b, 1, 1, 1))));
  return out;
}

}  // namespace polycube::fabricate
