#include "quality/distortion.h"

#include "core/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <Eigen/Dense>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>

namespace polycube::quality {

namespace {

using core::Vec3;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;

bool positive(const std::vector<Vec3>& p, const core::Tet& t) {
  auto pt = [&](int i) { return Epick::Point_3(p[t[i]].x(), p[t[i]].y(), p[t[i]].z()); };
  return CGAL::orientation(pt(0), pt(1), pt(2), pt(3)) == CGAL::POSITIVE;
}

Eigen::Matrix3d edge_matrix(const std::vector<Vec3>& p, const core::Tet& t) {
  Eigen::Matrix3d m;
  m.col(0) = p[t[1]] - p[t[0]];
  m.col(1) = p[t[2]] - p[t[0]];
  m.col(2) = p[t[3]] - p[t[0]];
  return m;
}

void check_input(const core::TetMesh& source, const std::vector<Vec3>& target) {
  if (target.size() != source.points.size())
    throw core::InputError("map distortion: " + std::to_string(target.size()) +
                           " target positions for " + std::to_string(source.points.size()) +
                           " source positions");
  const int nv = source.num_points();
  for (std::size_t c = 0; c < source.cells.size(); ++c)
    for (int v : source.cells[c])
      if (v < 0 || v >= nv)
        throw core::InputError("map distortion: tet " + std::to_string(c) + " references vertex " +
                               std::to_string(v) + " outside [0, " + std::to_string(nv) + ")");
  for (std::size_t v = 0; v < target.size(); ++v)
    if (!source.points[v].allFinite() || !target[v].allFinite())
      throw core::InputError("map distortion: vertex " + std::to_string(v) +
                             " has a non-finite coordinate");
}

struct Accumulator {
  double weighted_sum = 0.0;
  double max = 0.0;
  void add(double value, double weight) {
    weighted_sum += value * weight;
    max = std::max(max, value);
  }
  DistortionStat finish(double total_weight) const {
    return {total_weight > 0.0 ? weighted_sum / total_weight : 0.0, max};
  }
};

}  // namespace

std::vector<core::Field> MapDistortion::fields() const {
  PC_REQUIRE(static_cast<int>(per_tet_isometric.size()) == tets, "per-tet distortion was not kept");
  auto finite = [](const std::vector<double>& v) {
    std::vector<double> out(v);
    for (double& x : out)
      if (!std::isfinite(x)) x = -1.0;
    return out;
  };
  return {{"isometric", finite(per_tet_isometric)},
          {"conformal", finite(per_tet_conformal)},
          {"volume", finite(per_tet_volume)}};
}

MapDistortion map_distortion(const core::TetMesh& source, const std::vector<Vec3>& target_points,
                             const DistortionOptions& options) {
  check_input(source, target_points);
  MapDistortion r;
  r.tets = source.num_cells();
  const auto& sp = source.points;
  const auto& tp = target_points;

  if (options.normalize_volume) {
    double vs = 0.0, vt = 0.0;
    for (const auto& t : source.cells) {
      vs += edge_matrix(sp, t).determinant() / 6.0;
      vt += edge_matrix(tp, t).determinant() / 6.0;
    }
    if (!(vs > 0.0) || !(vt > 0.0))
      throw core::GeometryError(
          "map distortion: cannot normalize volumes, total signed volumes are " +
          std::to_string(vs) + " (source) and " + std::to_string(vt) + " (target)");
    r.target_scale = std::cbrt(vs / vt);
  }

  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (options.keep_per_tet) {
    r.per_tet_isometric.assign(r.tets, kInf);
    r.per_tet_conformal.assign(r.tets, kInf);
    r.per_tet_volume.assign(r.tets, kInf);
    r.per_tet_volume_ratio.assign(r.tets, 0.0);
  }
  Accumulator iso, conf, vol;
  double total_weight = 0.0;
  for (int c = 0; c < r.tets; ++c) {
    const auto& t = source.cells[c];
    const bool src_ok = positive(sp, t);
    const bool tgt_ok = positive(tp, t);
    if (!src_ok) ++r.inverted_source;
    if (!tgt_ok) ++r.inverted_target;
    const Eigen::Matrix3d s = edge_matrix(sp, t);
    const Eigen::Matrix3d g = edge_matrix(tp, t) * r.target_scale;
    const double ds = s.determinant();
    if (options.keep_per_tet && ds != 0.0) r.per_tet_volume_ratio[c] = g.determinant() / ds;
    if (!src_ok || !tgt_ok) {
      ++r.invalid;
      continue;
    }
    // J = G S^-1; S is invertible (positive orientation, exactly).
    const Eigen::Matrix3d j = g * s.inverse();
    const Eigen::JacobiSVD<Eigen::Matrix3d> svd(j);
    const Eigen::Vector3d sv = svd.singularValues();  // decreasing
    const double s1 = sv[0], s3 = sv[2];
    const double det = sv[0] * sv[1] * sv[2];
    const double i_val = s3 > 0.0 ? std::max(s1, 1.0 / s3) : kInf;
    const double c_val = s3 > 0.0 ? s1 / s3 : kInf;
    const double v_val = det > 0.0 ? std::max(det, 1.0 / det) : kInf;
    if (options.keep_per_tet) {
      r.per_tet_isometric[c] = i_val;
      r.per_tet_conformal[c] = c_val;
      r.per_tet_volume[c] = v_val;
    }
    const double w = ds / 6.0;
    total_weight += w;
    iso.add(i_val, w);
    conf.add(c_val, w);
    vol.add(v_val, w);
  }
  r.isometric = iso.finish(total_weight);
  r.conformal = conf.finish(total_weight);
  r.volume = vol.finish(total_weight);
  return r;
}

}  // namespace polycube::quality
