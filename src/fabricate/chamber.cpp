//! Fitting a chamber (see chamber.h).
#include "fabricate/chamber.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace polycube::fabricate {

namespace {

using Vec2 = Eigen::Vector2d;

double cross(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

//! Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

//! Extent of the hull along direction d.
double extent(const std::vector<Vec2>& hull, const Vec2& d) {
  double lo = hull.front().dot(d), hi = lo;
  for (const Vec2& q : hull) {
    lo = std::min(lo, q.dot(d));
    hi = std::max(hi, q.dot(d));
  }
  return hi - lo;
}

bool footprint_fits(const std::vector<Vec2>& hull, double x, double y) {
  const auto fits_along = [&](const Vec2& d) {
    const double w = extent(hull, d), h = extent(hull, Vec2(-d.y(), d.x()));
    return (w <= x && h <= y) || (w <= y && h <= x);
  };
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Vec2 e = hull[(i + 1) % hull.size()] - hull[i];
    if (e.norm() > 0 && fits_along(e.normalized())) return true;
  }
  constexpr int kTurns = 180;  // one per degree: a half-turn covers every rectangle orientation
  for (int k = 0; k < kTurns; ++k) {
    const double a = M_PI * k / kTurns;
    if (fits_along(Vec2(std::cos(a), std::sin(a)))) return true;
  }
  return false;
}

}  // namespace

bool fits_standing_on(const std::vector<core::Vec3>& points, const core::Vec3& down,
                      const Chamber& chamber) {
  if (!chamber.limited()) return true;
  if (points.empty()) return true;
  const core::Vec3 n = down.normalized();
  const core::Vec3 u =
      (std::abs(n.x()) < 0.9 ? core::Vec3::UnitX() : core::Vec3::UnitY()).cross(n).normalized();
  const core::Vec3 v = n.cross(u);
  double lo = points.front().dot(n), hi = lo;
  std::vector<Vec2> flat;
  flat.reserve(points.size());
  for (const core::Vec3& p : points) {
    lo = std::min(lo, p.dot(n));
    hi = std::max(hi, p.dot(n));
    flat.emplace_back(p.dot(u), p.dot(v));
  }
  if (hi - lo > chamber.z) return false;
  return footprint_fits(convex_hull(std::move(flat)), chamber.x, chamber.y);
}

int fitting_base(const std::vector<core::Vec3>& points, const std::vector<core::Vec3>& bases,
                 const Chamber& chamber) {
  for (std::size_t i = 0; i < bases.size(); ++i)
    if (fits_standing_on(points, bases[i], chamber)) return static_cast<int>(i);
  return -1;
}

}  // namespace polycube::fabricate
