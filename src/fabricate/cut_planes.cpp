//! Model-space planes of the cuts (see cut_planes.h).
#include "fabricate/cut_planes.h"

#include "core/errors.h"
#include "fabricate/corners.h"

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include <cmath>
#include <optional>
#include <set>

namespace polycube::fabricate {

namespace {

using core::Vec3;

//! How far each box's corners are drawn towards its centre before the cut must keep them on the
//! box's side: halfway keeps a good share of the box's material without asking for a plane
//! that follows the map's curved interfaces exactly.
constexpr double kShrink = 0.5;

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

//! Diagonal of the points' bounding box.
double extent(const std::vector<Vec3>& p) {
  Vec3 lo = p.front(), hi = p.front();
  for (const Vec3& x : p) {
    lo = lo.cwiseMin(x);
    hi = hi.cwiseMax(x);
  }
  return (hi - lo).norm();
}

//! The grid vertices of the polycube's section by a grid plane (those with an inside cell around
//! them): a cut without contacts (between the arms of a U) follows the map through these.
std::vector<Vec3> section_vertices(const OccupancyGrid& g, int axis, int plane) {
  std::vector<Vec3> out;
  const int e1 = (axis + 1) % 3, e2 = (axis + 2) % 3;
  std::array<int, 3> v{};
  v[axis] = plane;
  for (v[e2] = 0; v[e2] <= g.cells(e2); ++v[e2])
    for (v[e1] = 0; v[e1] <= g.cells(e1); ++v[e1]) {
      bool inside = false;
      for (int k = 0; k < 8 && !inside; ++k) {
        std::array<int, 3> c{};
        for (int a = 0; a < 3; ++a) c[a] = v[a] - ((k >> a) & 1);
        inside = g.in(c);
      }
      if (inside) out.emplace_back(g.planes[0][v[0]], g.planes[1][v[1]], g.planes[2][v[2]]);
    }
  return out;
}

//! Mean of the mapped centres of the boxes.
Vec3 mean_centre(const ToModel& to_model, const OccupancyGrid& g, const BoxPartition& p,
                 const std::vector<int>& boxes) {
  Vec3 sum = Vec3::Zero();
  for (int b : boxes) sum += to_model(box_centre(g, p.boxes[static_cast<std::size_t>(b)]));
  return sum / static_cast<double>(boxes.size());
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

//! The points a cut must leave on their box's side: per box of the group its mapped centre and,
//! when shrink > 0, its corners moved that fraction of the way towards the centre.
struct SidePoints {
  std::vector<Vec3> below, above;
};

SidePoints side_points(const ToModel& to_model, const OccupancyGrid& g, const BoxPartition& p,
                       const Cut& cut, double shrink) {
  SidePoints out;
  for (int s = 0; s < 2; ++s)
    for (int b : s ? cut.above : cut.below) {
      auto& list = s ? out.above : out.below;
      const Box& box = p.boxes[static_cast<std::size_t>(b)];
      const Vec3 c = box_centre(g, box);
      list.push_back(to_model(c));
      if (shrink <= 0) continue;
      for (int k = 0; k < 8; ++k) {
        const Vec3 corner = box_corner(g, box, k & 1, (k >> 1) & 1, (k >> 2) & 1);
        list.push_back(to_model(c + (1.0 - shrink) * (corner - c)));
      }
    }
  return out;
}

//! Signed distance of x from the plane, positive on the above side.
double signed_distance(const CutPlane& plane, const Vec3& x) {
  return plane.normal.dot(x) - plane.offset;
}

//! Points of the side points on the wrong side of the plane (or within `margin` of it).
int misplaced(const CutPlane& plane, const SidePoints& s, double margin) {
  int n = 0;
  for (const Vec3& x : s.below) n += signed_distance(plane, x) > -margin ? 1 : 0;
  for (const Vec3& x : s.above) n += signed_distance(plane, x) < margin ? 1 : 0;
  return n;
}

//! min 1/2 z'Hz + g'z subject to a_j . z >= b_j (H symmetric positive definite, 3 x 3), by
//! Hildreth's dual coordinate ascent: exact in the limit, deterministic, and small enough for
//! the few hundred constraints of a cut. Empty when the constraints are not met within `tol`
//! (they may be infeasible: no plane separates the points).
std::optional<Eigen::Vector3d> constrained_least_squares(const Eigen::Matrix3d& H,
                                                         const Eigen::Vector3d& g,
                                                         const std::vector<Eigen::Vector3d>& a,
                                                         const std::vector<double>& b, double tol) {
  const Eigen::Matrix3d Hinv = H.inverse();
  Eigen::Vector3d z = -Hinv * g;
  std::vector<Eigen::Vector3d> Ha(a.size());
  std::vector<double> d(a.size()), lambda(a.size(), 0.0);
  for (std::size_t j = 0; j < a.size(); ++j) {
    Ha[j] = Hinv * a[j];
    d[j] = a[j].dot(Ha[j]);
  }
  constexpr int kSweeps = 20000;
  for (int sweep = 0; sweep < kSweeps; ++sweep) {
    double worst = 0.0;
    for (std::size_t j = 0; j < a.size(); ++j) {
      const double r = b[j] - a[j].dot(z);
      worst = std::max(worst, r);
      const double step = std::max(-lambda[j], r / d[j]);
      lambda[j] += step;
      z += step * Ha[j];
    }
    if (worst <= tol) return z;
  }
  return std::nullopt;
}

//! The plane closest to the contact points (least squares along the plane's normal) that has
//! the side points on their sides by at least `margin`: in the frame (u, v, n) of the plane's
//! normal, the tilted plane w = alpha x + beta y + gamma is linear in (alpha, beta, gamma).
std::optional<CutPlane> fit_keeping_sides(const CutPlane& plane, const std::vector<Vec3>& points,
                                          const SidePoints& sides, double margin) {
  const Vec3 n = plane.normal;
  const Vec3 u = (std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(n).normalized();
  const Vec3 v = n.cross(u);
  const Vec3 o = plane.offset * n;
  const auto local = [&](const Vec3& x) {
    return Eigen::Vector3d(u.dot(x - o), v.dot(x - o), n.dot(x - o));
  };
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  for (const Vec3& x : points) {
    const Eigen::Vector3d l = local(x);
    const Eigen::Vector3d r(l.x(), l.y(), 1.0);
    H += r * r.transpose();
    g -= l.z() * r;
  }
  std::vector<Eigen::Vector3d> a;
  std::vector<double> b;
  for (int s = 0; s < 2; ++s) {
    const double sign = s ? 1.0 : -1.0;  // above: w - plane >= margin; below: plane - w >= margin
    for (const Vec3& x : s ? sides.above : sides.below) {
      const Eigen::Vector3d l = local(x);
      a.emplace_back(-sign * l.x(), -sign * l.y(), -sign);
      b.push_back(margin - sign * l.z());
    }
  }
  const auto z = constrained_least_squares(H, g, a, b, 0.5 * margin);
  if (!z) return std::nullopt;
  const Vec3 m = n - (*z)[0] * u - (*z)[1] * v;
  CutPlane out = plane;
  out.normal = m.normalized();
  out.offset = out.normal.dot(o) + (*z)[2] / m.norm();
  return out;
}

//! Tilt and shift the plane, if needed, so that every box of the cut keeps its shrunk corners
//! (else at least its centre) on its side; see cut_planes.h.
void keep_boxes_on_their_sides(CutPlane& plane, const std::vector<Vec3>& points,
                               const SidePoints& corners, const SidePoints& centres,
                               double margin) {
  if (misplaced(plane, corners, margin) == 0) return;
  if (auto p = fit_keeping_sides(plane, points, corners, margin)) {
    plane = *p;
    plane.constrained = 1;
    return;
  }
  if (misplaced(plane, centres, margin) > 0) {
    if (auto p = fit_keeping_sides(plane, points, centres, margin)) {
      plane = *p;
    } else {
      plane.unkept_boxes = misplaced(plane, centres, 0.0);
    }
  }
  plane.constrained = 2;
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

CutPlane fit_cut_plane(const ToModel& to_model, const OccupancyGrid& grid,
                       const BoxPartition& partition, const Cut& cut) {
  if (cut.axis < 0) return {};
  std::vector<Vec3> points;
  for (const Vec3& q : cut.contacts.empty() ? section_vertices(grid, cut.axis, cut.plane)
                                            : contact_vertices(grid, cut))
    points.push_back(to_model(q));
  if (points.size() < 3)
    throw core::GeometryError(
        fmt::format("cut along plane {} of axis {}: fewer than 3 points "
                    "to fit a plane",
                    cut.plane, "xyz"[cut.axis]));
  CutPlane plane = least_squares_plane(points);
  // Orientation: from the below side to the above side, as the map carries the polycube axis.
  const Vec3 across = mean_centre(to_model, grid, partition, cut.above) -
                      mean_centre(to_model, grid, partition, cut.below);
  if (plane.normal.dot(across) < 0) {
    plane.normal = -plane.normal;
    plane.offset = -plane.offset;
  }
  const double margin = 1e-4 * extent(points);
  keep_boxes_on_their_sides(plane, points, side_points(to_model, grid, partition, cut, kShrink),
                            side_points(to_model, grid, partition, cut, 0.0), margin);
  measure(plane, points);
  return plane;
}

std::vector<CutPlane> fit_cut_planes(const core::PolycubeMap& map, const OccupancyGrid& grid,
                                     const CutPlan& plan, double tolerance) {
  const ToModel to_model(map, tolerance);
  std::vector<CutPlane> planes;
  planes.reserve(plan.cuts.size());
  for (const Cut& cut : plan.cuts)
    planes.push_back(fit_cut_plane(to_model, grid, plan.partition, cut));
  return planes;
}

}  // namespace polycube::fabricate
