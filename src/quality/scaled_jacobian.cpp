#include "quality/scaled_jacobian.h"

#include "core/elements.h"
#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace polycube::quality {

namespace {

using core::Vec3;

bool all_finite(const Vec3* p, int n) {
  for (int i = 0; i < n; ++i)
    if (!p[i].allFinite()) return false;
  return true;
}

//! Squared-length threshold of an element: Verdict's absolute one, or the relative one.
double degenerate_threshold_sq(double longest_edge_sq) {
  const double rel = kRelativeDegenerateLength * kRelativeDegenerateLength * longest_edge_sq;
  return std::max(kVerdictDblMin, rel);
}

double clamp_unit(double v) { return std::clamp(v, -1.0, 1.0); }

ElementJacobian invalid() { return {}; }

//! Normalized determinant of three vectors, as Verdict computes it; false when degenerate.
bool normalized_det(const Vec3& a, const Vec3& b, const Vec3& c, double threshold_sq, double& out) {
  const double la = a.squaredNorm(), lb = b.squaredNorm(), lc = c.squaredNorm();
  if (la <= threshold_sq || lb <= threshold_sq || lc <= threshold_sq) return false;
  out = a.dot(b.cross(c)) / std::sqrt(la * lb * lc);
  return true;
}

template <class Mesh>
void check_cells(const Mesh& mesh) {
  const int nv = mesh.num_points();
  for (std::size_t c = 0; c < mesh.cells.size(); ++c)
    for (int v : mesh.cells[c])
      if (v < 0 || v >= nv)
        throw core::InputError(
            "scaled Jacobian: " + std::string(core::cell_type_name(Mesh::cell_type)) + " " +
            std::to_string(c) + " references vertex " + std::to_string(v) + " outside [0, " +
            std::to_string(nv) + ")");
}

void accumulate(ScaledJacobianSummary& s, const ElementJacobian& e, bool keep) {
  const double v = e.value;
  if (keep) s.values.push_back(v);
  if (s.count == 0) {
    s.min = v;
    s.max = v;
  } else {
    s.min = std::min(s.min, v);
    s.max = std::max(s.max, v);
  }
  ++s.count;
  s.average += v;  // the sum for now
  if (!e.valid)
    ++s.invalid;
  else if (v <= 0.0)
    ++s.inverted;
  int bin = 0;
  if (v > 0.0)
    bin = std::clamp(static_cast<int>(std::ceil(v * 5.0 - 1e-12)), 1, kHistogramBins - 1);
  ++s.histogram[bin];
}

void finish(ScaledJacobianSummary& s) {
  if (s.count > 0) s.average /= s.count;
}

}  // namespace

ElementJacobian hex_scaled_jacobian(const std::array<Vec3, 8>& p) {
  if (!all_finite(p.data(), 8)) return invalid();
  double longest = 0.0;
  for (const auto& e : core::kHexEdges)
    longest = std::max(longest, (p[e[1]] - p[e[0]]).squaredNorm());
  const double thr = degenerate_threshold_sq(longest);

  // Centre: principal axes, summed in Verdict's order (calc_hex_efg).
  const Vec3 x1 = p[1] + p[2] + p[5] + p[6] - p[0] - p[3] - p[4] - p[7];
  const Vec3 x2 = p[2] + p[3] + p[6] + p[7] - p[0] - p[1] - p[4] - p[5];
  const Vec3 x3 = p[4] + p[5] + p[6] + p[7] - p[0] - p[1] - p[2] - p[3];
  double best = 0.0;
  if (!normalized_det(x1, x2, x3, thr, best)) return invalid();

  // Corners: the three outgoing edges in right-handed order.
  for (int i = 0; i < 8; ++i) {
    const auto& n = core::kHexCornerNeighbors[i];
    double v = 0.0;
    if (!normalized_det(p[n[0]] - p[i], p[n[1]] - p[i], p[n[2]] - p[i], thr, v)) return invalid();
    best = std::min(best, v);
  }
  return {clamp_unit(best), true};
}

ElementJacobian tet_scaled_jacobian(const std::array<Vec3, 4>& p) {
  if (!all_finite(p.data(), 4)) return invalid();
  // Verdict's sides: 0 = p1-p0, 1 = p2-p1, 2 = p0-p2, 3 = p3-p0, 4 = p3-p1, 5 = p3-p2.
  const Vec3 s0 = p[1] - p[0], s1 = p[2] - p[1], s2 = p[0] - p[2];
  const Vec3 s3 = p[3] - p[0], s4 = p[3] - p[1], s5 = p[3] - p[2];
  const double l2[6] = {s0.squaredNorm(), s1.squaredNorm(), s2.squaredNorm(),
                        s3.squaredNorm(), s4.squaredNorm(), s5.squaredNorm()};
  const double thr = degenerate_threshold_sq(*std::max_element(l2, l2 + 6));
  for (double l : l2)
    if (l <= thr) return invalid();

  const double jacobi = s3.dot(s2.cross(s0));
  const double l[6] = {std::sqrt(l2[0]), std::sqrt(l2[1]), std::sqrt(l2[2]),
                       std::sqrt(l2[3]), std::sqrt(l2[4]), std::sqrt(l2[5])};
  // Corner products: corner 0 (sides 0,2,3), 1 (0,1,4), 2 (1,2,5), 3 (3,4,5).
  double length_product =
      std::max({l[0] * l[2] * l[3], l[0] * l[1] * l[4], l[1] * l[2] * l[5], l[3] * l[4] * l[5]});
  length_product = std::max(length_product, std::fabs(jacobi));
  if (length_product < kVerdictDblMin) return invalid();
  return {clamp_unit(std::sqrt(2.0) * jacobi / length_product), true};
}

ElementJacobian quad_scaled_jacobian(const std::array<Vec3, 4>& p,
                                     const std::optional<Vec3>& reference_normal) {
  if (!all_finite(p.data(), 4)) return invalid();
  const Vec3 e[4] = {p[1] - p[0], p[2] - p[1], p[3] - p[2], p[0] - p[3]};
  double len[4];
  double longest = 0.0;
  for (int i = 0; i < 4; ++i) {
    len[i] = e[i].norm();
    longest = std::max(longest, len[i]);
  }
  const double thr = std::max(kVerdictDblMin, kRelativeDegenerateLength * longest);
  for (double l : len)
    if (l <= thr) return invalid();

  Vec3 n;
  if (reference_normal) {
    n = *reference_normal;
  } else {
    n = (e[0] - e[2]).cross(e[1] - e[3]);  // Verdict's centre normal
  }
  const double nn = n.norm();
  if (!(nn > 0.0) || !std::isfinite(nn)) return invalid();
  n /= nn;

  // Corner i lies between e[i-1] (incoming) and e[i] (outgoing): Verdict's e_{i-1} x e_i.
  double best = std::numeric_limits<double>::max();
  for (int i = 0; i < 4; ++i) {
    const int prev = (i + 3) % 4;
    const double area = n.dot(e[prev].cross(e[i]));
    best = std::min(best, area / (len[i] * len[prev]));
  }
  return {clamp_unit(best), true};
}

core::Field ScaledJacobianSummary::field(const std::string& name) const {
  PC_REQUIRE(static_cast<int>(values.size()) == count, "scaled Jacobian values were not kept");
  return core::Field{name, values};
}

ScaledJacobianSummary scaled_jacobian(const core::HexMesh& mesh,
                                      const ScaledJacobianOptions& options) {
  check_cells(mesh);
  ScaledJacobianSummary s;
  if (options.keep_values) s.values.reserve(mesh.cells.size());
  std::array<Vec3, 8> p;
  for (const auto& c : mesh.cells) {
    for (int i = 0; i < 8; ++i) p[i] = mesh.points[c[i]];
    accumulate(s, hex_scaled_jacobian(p), options.keep_values);
  }
  finish(s);
  return s;
}

ScaledJacobianSummary scaled_jacobian(const core::TetMesh& mesh,
                                      const ScaledJacobianOptions& options) {
  check_cells(mesh);
  ScaledJacobianSummary s;
  if (options.keep_values) s.values.reserve(mesh.cells.size());
  std::array<Vec3, 4> p;
  for (const auto& c : mesh.cells) {
    for (int i = 0; i < 4; ++i) p[i] = mesh.points[c[i]];
    accumulate(s, tet_scaled_jacobian(p), options.keep_values);
  }
  finish(s);
  return s;
}

ScaledJacobianSummary scaled_jacobian(const core::QuadMesh& mesh,
                                      const ScaledJacobianOptions& options,
                                      const std::vector<Vec3>& reference_normals) {
  check_cells(mesh);
  if (!reference_normals.empty() && reference_normals.size() != mesh.cells.size())
    throw core::InputError("scaled Jacobian: " + std::to_string(reference_normals.size()) +
                           " reference normals for " + std::to_string(mesh.cells.size()) +
                           " quads");
  ScaledJacobianSummary s;
  if (options.keep_values) s.values.reserve(mesh.cells.size());
  std::array<Vec3, 4> p;
  for (std::size_t q = 0; q < mesh.cells.size(); ++q) {
    for (int i = 0; i < 4; ++i) p[i] = mesh.points[mesh.cells[q][i]];
    const auto n =
        reference_normals.empty() ? std::nullopt : std::optional<Vec3>(reference_normals[q]);
    accumulate(s, quad_scaled_jacobian(p, n), options.keep_values);
  }
  finish(s);
  return s;
}

}  // namespace polycube::quality
