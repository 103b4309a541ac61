#include "mesh/tet_locator.h"

#include "core/errors.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace polycube::mesh {

using core::Vec3;

TetLocator::TetLocator(const std::vector<core::Tet>& tets, const std::vector<Vec3>& points,
                       double tolerance)
    : tolerance_(std::max(0.0, tolerance)) {
  const int nv = static_cast<int>(points.size());
  // 1. per-tet data (flat tets skipped)
  double max_edge = 0.0;
  for (std::size_t t = 0; t < tets.size(); ++t) {
    const auto& c = tets[t];
    for (int v : c)
      if (v < 0 || v >= nv)
        throw core::InputError("TetLocator: tet " + std::to_string(t) + " has an invalid vertex");
    const Vec3& p0 = points[c[0]];
    Eigen::Matrix3d m;
    m.col(0) = points[c[1]] - p0;
    m.col(1) = points[c[2]] - p0;
    m.col(2) = points[c[3]] - p0;
    const double l = std::max(
        {m.col(0).norm(), m.col(1).norm(), m.col(2).norm(), (points[c[2]] - points[c[1]]).norm(),
         (points[c[3]] - points[c[1]]).norm(), (points[c[3]] - points[c[2]]).norm()});
    const double det = m.determinant();
    if (!(std::abs(det) > 1e-14 * l * l * l)) continue;
    max_edge = std::max(max_edge, l);
    TetData d;
    d.p0 = p0;
    d.inv = m.inverse();
    const Vec3 g1 = d.inv.row(0).transpose();
    const Vec3 g2 = d.inv.row(1).transpose();
    const Vec3 g3 = d.inv.row(2).transpose();
    d.height = {1.0 / (g1 + g2 + g3).norm(), 1.0 / g1.norm(), 1.0 / g2.norm(), 1.0 / g3.norm()};
    tet_ids_.push_back(static_cast<int>(t));
    data_.push_back(d);
  }
  inside_threshold_ = 1e-9 * max_edge + tolerance_ * 1e-3;

  // 2. grid over the bounding box of the indexed tets, about two cells per tet
  Vec3 lo = Vec3::Constant(1e300);
  Vec3 hi = Vec3::Constant(-1e300);
  for (int tid : tet_ids_)
    for (int v : tets[tid]) {
      lo = lo.cwiseMin(points[v]);
      hi = hi.cwiseMax(points[v]);
    }
  if (tet_ids_.empty()) {
    lo = hi = Vec3::Zero();
  }
  lo.array() -= tolerance_;
  hi.array() += tolerance_;
  const Vec3 ext = (hi - lo).cwiseMax(1e-300);
  const double target = 2.0 * std::max<double>(1.0, static_cast<double>(tet_ids_.size()));
  // cell size h with prod(ext / h) ~ target (axes of zero extent get one cell)
  double h = std::cbrt(std::max(ext.prod(), 1e-300) / target);
  for (int a = 0; a < 3; ++a) h = std::max(h, ext[a] / 4096.0);
  for (int a = 0; a < 3; ++a) {
    dims_[a] = std::clamp(static_cast<int>(std::ceil(ext[a] / h)), 1, 4096);
    inv_cell_[a] = dims_[a] / ext[a];
  }
  origin_ = lo;

  // 3. CSR: register each tet in every cell its (tolerance-expanded) bounding box overlaps
  const std::size_t ncell = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  cell_start_.assign(ncell + 1, 0);
  auto range = [&](std::size_t slot, std::array<int, 3>& a, std::array<int, 3>& b) {
    const auto& c = tets[tet_ids_[slot]];
    Vec3 tlo = points[c[0]];
    Vec3 thi = tlo;
    for (int k = 1; k < 4; ++k) {
      tlo = tlo.cwiseMin(points[c[k]]);
      thi = thi.cwiseMax(points[c[k]]);
    }
    tlo.array() -= tolerance_;
    thi.array() += tolerance_;
    a = cell_of(tlo);
    b = cell_of(thi);
  };
  auto cell_index = [&](int i, int j, int k) {
    return (static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i;
  };
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < ncell; ++c) cell_start_[c + 1] += cell_start_[c];
      cell_items_.resize(static_cast<std::size_t>(cell_start_[ncell]));
      fill.assign(cell_start_.begin(), cell_start_.end() - 1);
    }
    for (std::size_t s = 0; s < tet_ids_.size(); ++s) {
      std::array<int, 3> a{};
      std::array<int, 3> b{};
      range(s, a, b);
      for (int k = a[2]; k <= b[2]; ++k)
        for (int j = a[1]; j <= b[1]; ++j)
          for (int i = a[0]; i <= b[0]; ++i) {
            const std::size_t ci = cell_index(i, j, k);
            if (pass == 0)
              ++cell_start_[ci + 1];
            else
              cell_items_[static_cast<std::size_t>(fill[ci]++)] = static_cast<int>(s);
          }
    }
  }
}

std::array<int, 3> TetLocator::cell_of(const Vec3& q) const {
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double x = (q[a] - origin_[a]) * inv_cell_[a];
    c[a] = x <= 0.0 ? 0 : (x >= dims_[a] - 1 ? dims_[a] - 1 : static_cast<int>(x));
  }
  return c;
}

void TetLocator::evaluate(int slot, const Vec3& q, Hit& best) const {
  const TetData& d = data_[static_cast<std::size_t>(slot)];
  const Vec3 l = d.inv * (q - d.p0);
  const double l0 = 1.0 - l[0] - l[1] - l[2];
  const double score = std::min(std::min(l0 * d.height[0], l[0] * d.height[1]),
                                std::min(l[1] * d.height[2], l[2] * d.height[3]));
  const int tid = tet_ids_[static_cast<std::size_t>(slot)];
  if (score > best.score || (score == best.score && tid < best.tet)) {
    best.tet = tid;
    best.score = score;
    best.bary = {l0, l[0], l[1], l[2]};
  }
}

TetLocator::Hit TetLocator::locate(const Vec3& q) const {
  Hit best;
  for (int a = 0; a < 3; ++a) {
    const double x = (q[a] - origin_[a]) * inv_cell_[a];
    if (!(x >= 0.0 && x <= dims_[a])) return {};  // outside the grid (or NaN)
  }
  const auto c = cell_of(q);
  const std::size_t ci = (static_cast<std::size_t>(c[2]) * dims_[1] + c[1]) * dims_[0] + c[0];
  for (int k = cell_start_[ci]; k < cell_start_[ci + 1]; ++k) {
    evaluate(cell_items_[static_cast<std::size_t>(k)], q, best);
    if (best.score > inside_threshold_) break;  // strictly inside one tet: no other can contain q
  }
  if (best.tet >= 0 && best.score < -tolerance_) return {};
  return best;
}

TetLocator::Hit TetLocator::nearest(const Vec3& q, int rings) const {
  Hit best;
  const auto c = cell_of(q);
  for (int k = std::max(0, c[2] - rings); k <= std::min(dims_[2] - 1, c[2] + rings); ++k)
    for (int j = std::max(0, c[1] - rings); j <= std::min(dims_[1] - 1, c[1] + rings); ++j)
      for (int i = std::max(0, c[0] - rings); i <= std::min(dims_[0] - 1, c[0] + rings); ++i) {
        const std::size_t ci = (static_cast<std::size_t>(k) * dims_[1] + j) * dims_[0] + i;
        for (int s = cell_start_[ci]; s < cell_start_[ci + 1]; ++s)
          evaluate(cell_items_[static_cast<std::size_t>(s)], q, best);
      }
  return best;
}

TetLocator::Hit TetLocator::nearest_brute_force(const Vec3& q) const {
  Hit best;
  for (std::size_t s = 0; s < data_.size(); ++s) evaluate(static_cast<int>(s), q, best);
  return best;
}

TetLocator::Hit locate_or_nearest(const TetLocator& locator, const core::Vec3& q, bool& located) {
  TetLocator::Hit hit = locator.locate(q);
  located = hit.tet >= 0;
  if (!located) {
    hit = locator.nearest(q, 2);
    if (hit.tet < 0) hit = locator.nearest_brute_force(q);
  }
  return hit;
}

core::Vec3 map_through(const std::vector<core::Tet>& tets, const std::vector<core::Vec3>& to,
                       const TetLocator::Hit& hit) {
  std::array<double, 4> b = hit.bary;
  double sum = 0.0;
  for (double& x : b) sum += (x = std::max(0.0, x));
  const auto& t = tets[static_cast<std::size_t>(hit.tet)];
  core::Vec3 p = core::Vec3::Zero();
  for (int k = 0; k < 4; ++k) p += (b[k] / sum) * to[t[k]];
  return p;
}

}  // namespace polycube::mesh
