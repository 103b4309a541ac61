//! Centre tets of hexes (see centre_frames.h).
#include "optimize/centre_frames.h"

#include "core/elements.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace polycube::optimize {

namespace {

using core::Vec3;

//! The faces whose centroids difference to the principal axes: X_a = 4 (centroid of plus[a] -
//! centroid of minus[a]), vertices in core/elements.h order.
constexpr std::array<std::array<int, 4>, 3> kMinus{{{0, 3, 4, 7}, {0, 1, 4, 5}, {0, 1, 2, 3}}};
constexpr std::array<std::array<int, 4>, 3> kPlus{{{1, 2, 5, 6}, {2, 3, 6, 7}, {4, 5, 6, 7}}};

std::array<Vec3, 3> principal_axes(const core::HexMesh& m, const core::Hex& h) {
  std::array<Vec3, 3> x;
  for (int a = 0; a < 3; ++a) {
    x[a] = Vec3::Zero();
    for (int i = 0; i < 4; ++i) x[a] += m.points[h[kPlus[a][i]]] - m.points[h[kMinus[a][i]]];
  }
  return x;
}

double normalized(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double l = a.norm() * b.norm() * c.norm();
  return l > 0 ? a.dot(b.cross(c)) / l : 0.0;
}

}  // namespace

double centre_value(const core::HexMesh& mesh, const core::Hex& h) {
  const auto x = principal_axes(mesh, h);
  return normalized(x[0], x[1], x[2]);
}

std::vector<std::array<double, 3>> centre_lengths(const core::HexMesh& mesh,
                                                  const std::vector<double>& size,
                                                  const std::vector<double>& scale) {
  std::vector<std::array<double, 3>> out(mesh.cells.size());
  for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
    const auto x = principal_axes(mesh, mesh.cells[c]);
    for (int a = 0; a < 3; ++a) {
      const double l = 0.25 * x[a].norm();
      out[c][a] = scale[c] * (l > 0.05 * size[c] ? l : size[c]);  // collapsed axis: the hex size
    }
  }
  return out;
}

solve::LinearReduction with_centre_tets(const solve::LinearReduction& reduction,
                                        const core::HexMesh& mesh,
                                        const std::vector<std::array<double, 3>>& lengths,
                                        const std::vector<double>& multiplier, double weight,
                                        solve::TetElements& elements) {
  // Level 1: the six face centroids of each hex (point base1 + 6k + 2a for minus[a], +1 for
  // plus[a]).
  const int base1 = reduction.num_points();
  std::vector<solve::DerivedPoint> faces;
  const std::size_t n = mesh.cells.size();
  faces.reserve(6 * n);
  for (std::size_t c = 0; c < n; ++c)
    for (int a = 0; a < 3; ++a)
      for (const auto& face : {kMinus[a], kPlus[a]}) {
        solve::DerivedPoint p;
        for (int i = 0; i < 4; ++i) {
          p.vertex[i] = mesh.cells[c][face[i]];
          p.weight[i] = 0.25;
        }
        faces.push_back(p);
      }
  const solve::LinearReduction with_faces = solve::with_derived_points(reduction, faces);
  // Level 2: the tips F- + (F+ - F-) of axes 2 and 3 taken from F- of axis 1.
  const int base2 = with_faces.num_points();
  std::vector<solve::DerivedPoint> tips;
  tips.reserve(2 * n);
  for (std::size_t k = 0; k < n; ++k) {
    const int f = base1 + 6 * static_cast<int>(k);
    for (int a = 1; a < 3; ++a) {
      solve::DerivedPoint p;
      p.vertex = {f, f + 2 * a + 1, f + 2 * a, -1};
      p.weight = {1.0, 1.0, -1.0, 0.0};
      tips.push_back(p);
    }
  }
  // The tet (F1-, F1+, tip 2, tip 3) against a right-angled corner of the reference lengths.
  for (std::size_t c = 0; c < n; ++c) {
    const std::size_t k = c;
    const int f = base1 + 6 * static_cast<int>(k);
    const int t = base2 + 2 * static_cast<int>(k);
    const auto& l = lengths[c];
    Eigen::Matrix<double, 4, 3> G = Eigen::Matrix<double, 4, 3>::Zero();
    for (int d = 0; d < 3; ++d) {
      G(d + 1, d) = 1.0 / l[d];
      G(0, d) = -1.0 / l[d];
    }
    elements.tets.push_back({f, f + 1, t, t + 1});
    elements.gradients.push_back(G);
    elements.weights.push_back(weight * multiplier[c] * l[0] * l[1] * l[2] / 6.0);
  }
  return solve::with_derived_points(with_faces, tips);
}

}  // namespace polycube::optimize
