//! Axis alignment of a surface (see orientation.h).
#include "construct/orientation.h"

#include <Eigen/Geometry>

#include <vector>

namespace polycube::construct {

namespace {

Eigen::Matrix3d rotation_of(double a, double b, double c) {
  return (Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(b, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(c, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace

AxisRotation best_axis_rotation(const core::TriMesh& surface, double min_gain) {
  AxisRotation res;
  // Area-weighted normals (length = twice the area).
  std::vector<Eigen::Vector3d> an;
  an.reserve(surface.cells.size());
  double area = 0;
  for (const auto& t : surface.cells) {
    const Eigen::Vector3d n = (surface.points[t[1]] - surface.points[t[0]]).cross(surface.points[t[2]] - surface.points[t[0]]);
    if (n.squaredNorm() > 0) an.push_back(n);
    area += n.norm();
  }
  if (an.empty() || area <= 0) return res;
  auto energy = [&](const Eigen::Matrix3d& R) {
    double e = 0;
    for (const auto& n : an) e += (R * n).cwiseAbs().sum();
    return e / area;
  };
  res.energy_before = res.energy_after = energy(Eigen::Matrix3d::Identity());
  // Grid: the cube's symmetries make 90° the period of each angle; 10° steps.
  constexpr double kPi = 3.14159265358979323846;
  const double step0 = kPi / 18;
  double best = res.energy_before, ba = 0, bb = 0, bc = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k) {
        const double a = i * step0, b = (j - 4) * step0, c = k * step0;
        const double e = energy(rotation_of(a, b, c));
        if (e < best - 1e-12) best = e, ba = a, bb = b, bc = c;
      }
  // Local refinement: halve the step around the best.
  for (double step = step0 / 2; step > 1e-6; step /= 2) {
    bool moved = true;
    while (moved) {
      moved = false;
      for (int d = 0; d < 3; ++d)
        for (int s = -1; s <= 1; s += 2) {
          double a = ba, b = bb, c = bc;
          (d == 0 ? a : d == 1 ? b : c) += s * step;
          const double e = energy(rotation_of(a, b, c));
          if (e < best - 1e-12) best = e, ba = a, bb = b, bc = c, moved = true;
        }
    }
  }
  res.energy_best = best;
  if (best < res.energy_before * (1.0 - min_gain)) {
    res.rotation = rotation_of(ba, bb, bc);
    res.energy_after = best;
  }
  return res;
}

}  // namespace polycube::construct
