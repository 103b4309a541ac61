//! Ghost tets of a labeled boundary (see ghost_tets.h).
#include "mapping/ghost_tets.h"

#include "core/errors.h"
#include "core/polycube_map.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace polycube::mapping {

namespace {

core::Vec3 base_point(const std::vector<core::Vec3>& P, const core::Tri& t, GhostBase base) {
  return base == GhostBase::Centroid ? core::Vec3((P[t[0]] + P[t[1]] + P[t[2]]) / 3.0) : P[t[0]];
}

}  // namespace

GhostTets ghost_tets(const std::vector<core::Vec3>& points, const std::vector<core::Tri>& tris,
                     const std::vector<int>& labels, double h, int first_apex, GhostBase base,
                     GhostDirection direction) {
  PC_REQUIRE(labels.size() == tris.size(), "ghost_tets: one label per triangle");
  GhostTets g;
  g.tets.reserve(tris.size());
  g.reference.reserve(tris.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const core::Tri& t = tris[f];
    const core::Vec3 c = base_point(points, t, base);
    const core::Vec3 n = direction == GhostDirection::Normal
                             ? core::Vec3((points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]).normalized())
                             : core::label_direction(labels[f]);
    g.reference.push_back(c + h * n);
    g.tets.push_back({t[0], t[1], t[2], first_apex + static_cast<int>(f)});
  }
  return g;
}

core::Vec3 ghost_apex(const std::vector<core::Vec3>& P, const core::Tri& t, int label, double h, GhostBase base,
                      ApexLift lift) {
  const int a = core::label_axis(label);
  const double sign = label % 2 == 0 ? 1.0 : -1.0;
  core::Vec3 apex = base_point(P, t, base);
  apex[a] = (lift == ApexLift::FromChartPlane ? P[t[0]][a] : apex[a]) + sign * h;
  return apex;
}

double ghost_height(const std::vector<core::Vec3>& points, const std::vector<core::Tri>& tris, double fraction) {
  if (!(fraction > 0)) return 0.0;
  double sum = 0;
  for (const core::Tri& t : tris)
    for (int e = 0; e < 3; ++e) sum += (points[t[e]] - points[t[(e + 1) % 3]]).norm();
  return fraction * sum / static_cast<double>(std::max<std::size_t>(1, 3 * tris.size()));
}

}  // namespace polycube::mapping
