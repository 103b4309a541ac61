//! Model-space planes of the cuts (see cut_planes.h).
#include "fabricate/cut_planes.h"

#include "core/errors.h"
#include "mesh/tet_locator.h"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <set>

namespace polycube::fabricate {

namespace {

using core::Vec3;

Vec3 to_model(const core::PolycubeMap& map, const mesh::TetLocator& locator, const Vec3& q) {
  bool located = false;
  return mesh::map_through(map.tets, map.model, mesh::locate_or_nearest(locator, q, located));
}

Vec3 box_centre(const OccupancyGrid& g, const Box& b) {
  return 0.5 * (box_corner(g, b, 0, 0, 0) + box_corner(g, b, 1, 1, 1));
}

//! The grid vertices of the cut's contact rectangles, in polycube space (each once).
std::vector<Vec3> contact_vertices(const OccupancyGrid& g, const Cut& cut) {
  std::set<std::array<int, 3>> seen;
  std::vector<Vec3> out;
  for (const Contact& c : cut.contacts)
    for (int k = c.lo[2]; k <= c.hi[2]; ++k)
      for (int j = c.lo[1]; j <= c.hi[1]; ++j)
        for (int i = c.lo[0]; i <= c.hi[0]; ++i)
          if (seen.insert({i, j, k}).second)
            out.emplace_back(g.planes[0][i], g.planes[1][j], g.planes[2][k]);
  return out;
}

CutPlane least_squares_plane(const std::vector<Vec3>& p) {
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& x : p) centroid += x;
  centroid /= static_cast<double>(p.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const Vec3& x : p) cov += (x - centroid) * (x - centroid).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  CutPlane plane;
  plane.normal = eig.eigenvectors().col(0).normalized();  // smallest eigenvalue first
  plane.offset = plane.normal.dot(centroid);
  plane.points = static_cast<int>(p.size());
  return plane;
}

void measure(CutPlane& plane, const std::vector<Vec3>& p) {
  double sq = 0.0;
  for (const Vec3& x : p) {
    const double d = std::abs(plane.normal.dot(x) - plane.offset);
    plane.max_deviation = std::max(plane.max_deviation, d);
    sq += d * d;
  }
  plane.rms_deviation = std::sqrt(sq / static_cast<double>(p.size()));
}

}  // namespace

std::vector<CutPlane> fit_cut_planes(const core::PolycubeMap& map, const OccupancyGrid& grid,
                                     const CutPlan& plan, double tolerance) {
  const mesh::TetLocator locator(map.tets, map.polycube, tolerance);
  std::vector<CutPlane> planes;
  planes.reserve(plan.cuts.size());
  for (std::size_t c = 0; c < plan.cuts.size(); ++c) {
    const Cut& cut = plan.cuts[c];
    if (cut.axis < 0) {
      planes.emplace_back();
      continue;
    }
    std::vector<Vec3> points;
    for (const Vec3& q : contact_vertices(grid, cut)) points.push_back(to_model(map, locator, q));
    if (points.size() < 3)
      throw core::GeometryError(fmt::format("cut {}: fewer than 3 points to fit a plane", c));
    CutPlane plane = least_squares_plane(points);
    // Orientation: from the below side to the above side, as the map carries the polycube axis.
    const Contact& k = cut.contacts.front();
    const Vec3 across = to_model(map, locator, box_centre(grid, plan.partition.boxes[k.boxes[1]])) -
                        to_model(map, locator, box_centre(grid, plan.partition.boxes[k.boxes[0]]));
    if (plane.normal.dot(across) < 0) {
      plane.normal = -plane.normal;
      plane.offset = -plane.offset;
    }
    measure(plane, points);
    planes.push_back(plane);
  }
  return planes;
}

}  // namespace polycube::fabricate
