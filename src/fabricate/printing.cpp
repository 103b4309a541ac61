//! Support needed to print a part (see printing.h).
#include "fabricate/printing.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace polycube::fabricate {

namespace {

using core::Vec3;

//! Twice-area normal of triangle t.
Vec3 area_normal(const core::TriMesh& m, std::size_t t) {
  const auto& c = m.cells[t];
  return (m.points[c[1]] - m.points[c[0]]).cross(m.points[c[2]] - m.points[c[0]]);
}

double surface_area(const core::TriMesh& m) {
  double a = 0.0;
  for (std::size_t t = 0; t < m.cells.size(); ++t) a += 0.5 * area_normal(m, t).norm();
  return a;
}

}  // namespace

std::vector<std::uint8_t> overhanging(const core::TriMesh& mesh, const Vec3& down,
                                      double overhang_degrees) {
  const Vec3 d = down.normalized();
  // On the bed: within a billionth of the part's size of its lowest point.
  double bed = -std::numeric_limits<double>::infinity(),
         lo = std::numeric_limits<double>::infinity();
  for (const Vec3& p : mesh.points) {
    bed = std::max(bed, p.dot(d));
    lo = std::min(lo, p.dot(d));
  }
  const double eps = 1e-9 * (bed - lo);  // relative: the same for the model in any unit
  const double steep = std::cos(overhang_degrees * M_PI / 180.0);
  std::vector<std::uint8_t> out(mesh.cells.size(), 0);
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    const Vec3 n = area_normal(mesh, t);
    const double len = n.norm();
    if (len == 0.0 || n.dot(d) / len <= steep) continue;
    const auto& c = mesh.cells[t];
    const bool on_bed =
        std::all_of(c.begin(), c.end(), [&](int v) { return mesh.points[v].dot(d) >= bed - eps; });
    out[t] = on_bed ? 0 : 1;
  }
  return out;
}

Standing stand(const core::TriMesh& mesh, const Vec3& down, const PrintOptions& options) {
  Standing s;
  s.down = down.normalized();
  const std::vector<std::uint8_t> over = overhanging(mesh, s.down, options.overhang_degrees);
  for (std::size_t t = 0; t < mesh.cells.size(); ++t)
    if (over[t]) s.overhang_area += 0.5 * area_normal(mesh, t).norm();
  const double area = surface_area(mesh);
  s.support_fraction = area > 0 ? s.overhang_area / area : 0.0;
  s.fits = fits_standing_on(mesh.points, s.down, options.chamber);
  return s;
}

PartPrint check_part_printing(const Part& part, const PrintOptions& options) {
  PartPrint out;
  out.area = surface_area(part.mesh);
  for (std::size_t i = 0; i < part.sides.size(); ++i) {
    out.sides.push_back(stand(part.mesh, part.sides[i].normal, options));
    const Standing& s = out.sides.back();
    if (!s.fits) continue;
    const auto better = [&](int b) {
      const Standing& o = out.sides[static_cast<std::size_t>(b)];
      if (s.support_fraction != o.support_fraction) return s.support_fraction < o.support_fraction;
      return part.sides[i].area > part.sides[static_cast<std::size_t>(b)].area;
    };
    if (out.best < 0 || better(out.best)) out.best = static_cast<int>(i);
  }
  return out;
}

core::TriMesh stand_on_bed(const core::TriMesh& mesh, const Vec3& down) {
  const Vec3 d = down.normalized();
  // FromTwoVectors picks an arbitrary axis for opposite vectors; up-facing bases turn about x.
  const Eigen::Matrix3d turn =
      d.z() > 1.0 - 1e-12
          ? Eigen::Matrix3d(Eigen::AngleAxisd(M_PI, Vec3::UnitX()))
          : Eigen::Quaterniond::FromTwoVectors(d, -Vec3::UnitZ()).toRotationMatrix();
  core::TriMesh out = mesh;
  for (Vec3& p : out.points) p = turn * p;
  if (out.points.empty()) return out;
  const core::BoundingBox box = core::bounding_box(out.points);
  const Vec3 shift(-(box.min.x() + box.max.x()) / 2, -(box.min.y() + box.max.y()) / 2,
                   -box.min.z());
  for (Vec3& p : out.points) p += shift;
  return out;
}

Standing best_axis_standing(const core::TriMesh& solid, const PrintOptions& options) {
  Standing best;
  best.support_fraction = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
    for (const double sign : {-1.0, 1.0}) {
      const Standing s = stand(solid, sign * Vec3::Unit(a), options);
      if (s.support_fraction < best.support_fraction) best = s;
    }
  return best;
}

}  // namespace polycube::fabricate
