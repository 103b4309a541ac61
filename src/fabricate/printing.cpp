//! Support needed to print a part (see printing.h).
#include "fabricate/printing.h"

#include "core/topology.h"

#include <fmt/format.h>
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

//! Heights along -down, and the bed: within a billionth of the part's height of its lowest point
//! (relative: the same for the model in any unit).
struct Heights {
  std::vector<double> z;
  double bed = 0.0;
  double eps = 0.0;
};
Heights heights(const core::TriMesh& mesh, const Vec3& d) {
  Heights h;
  h.z.reserve(mesh.points.size());
  for (const Vec3& p : mesh.points) h.z.push_back(-p.dot(d));
  if (h.z.empty()) return h;
  const auto [lo, hi] = std::minmax_element(h.z.begin(), h.z.end());
  h.bed = *lo;
  h.eps = 1e-9 * (*hi - *lo);
  return h;
}

//! Whether some direction within the printer's angle of straight down enters the solid through
//! both faces of a convex edge (unit outward normals n1, n2). A direction (v, -1) in a frame with
//! up = -d and horizontal axes e1, e2 is within the angle when |v| <= tan(angle), and enters
//! behind a face n when v.n_h < n.up: the half-planes' intersection must come within that radius
//! of the origin. Its nearest point is the origin, the foot on one line, or their corner.
bool held_from_below(const Vec3& n1, const Vec3& n2, const Vec3& d, double radius) {
  const Vec3 up = -d;
  const Vec3 e1 = up.unitOrthogonal(), e2 = up.cross(e1);
  const Eigen::Vector2d a1(n1.dot(e1), n1.dot(e2)), a2(n2.dot(e1), n2.dot(e2));
  const double b1 = n1.dot(up), b2 = n2.dot(up);
  const double tol = 1e-12;
  const auto inside = [&](const Eigen::Vector2d& v) {
    return a1.dot(v) <= b1 + tol && a2.dot(v) <= b2 + tol;
  };
  std::vector<Eigen::Vector2d> candidates{Eigen::Vector2d::Zero()};
  for (const auto& [a, b] : {std::pair{a1, b1}, std::pair{a2, b2}})
    if (a.squaredNorm() > 0.0) candidates.push_back(a * (b / a.squaredNorm()));
  Eigen::Matrix2d m;
  m << a1.transpose(), a2.transpose();
  if (std::abs(m.determinant()) > 1e-12)
    candidates.push_back(m.inverse() * Eigen::Vector2d(b1, b2));
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& v : candidates)
    if (inside(v)) nearest = std::min(nearest, v.norm());
  // Exactly at the angle counts as held, as for a face (relative tolerance).
  return nearest <= radius * (1.0 + 1e-9);
}

//! A part on a direction: heights and unit triangle normals (zero for degenerate triangles).
struct OnBed {
  const core::TriMesh& mesh;
  Vec3 d;
  Heights h;
  std::vector<Vec3> normal;
  core::EdgeTopology<core::CellType::Triangle> edges;

  OnBed(const core::TriMesh& m, const Vec3& down)
      : mesh(m), d(down.normalized()), h(heights(m, d)), edges(core::unique_edges(m)) {
    normal.reserve(m.cells.size());
    for (std::size_t t = 0; t < m.cells.size(); ++t) {
      const Vec3 n = area_normal(m, t);
      normal.push_back(n.norm() > 0.0 ? Vec3(n.normalized()) : Vec3::Zero());
    }
  }
  [[nodiscard]] bool on_bed(int v) const { return h.z[v] <= h.bed + h.eps; }
};

//! Convex edges whose faces do not overhang but that nothing holds up from below (see
//! keels_and_tips in printing.h).
void find_keels(const OnBed& s, const std::vector<std::uint8_t>& over, double radius,
                KeelsAndTips& out) {
  const core::Adjacency edge_tris = core::edge_cells(s.edges);
  for (int e = 0; e < s.edges.num_edges(); ++e) {
    const auto tris = edge_tris[e];
    if (tris.size() != 2) continue;  // parts are closed manifolds; nothing to say elsewhere
    const auto t1 = static_cast<std::size_t>(tris[0]), t2 = static_cast<std::size_t>(tris[1]);
    if (over[t1] || over[t2]) continue;  // counted in the area already
    const auto [u, w] = s.edges.edges[static_cast<std::size_t>(e)];
    if (s.on_bed(u) && s.on_bed(w)) continue;
    const Vec3 &n1 = s.normal[t1], &n2 = s.normal[t2];
    if (n1.isZero() || n2.isZero()) continue;
    // Convex: t2's far vertex below t1's plane (coplanar faces hold what each face holds).
    int far = -1;
    for (const int v : s.mesh.cells[t2])
      if (v != u && v != w) far = v;
    const Vec3 to_far = s.mesh.points[far] - s.mesh.points[u];
    if (to_far.dot(n1) >= -1e-9 * to_far.norm()) continue;
    if (held_from_below(n1, n2, s.d, radius)) continue;
    ++out.keels;
    out.keel_length += (s.mesh.points[u] - s.mesh.points[w]).norm();
    out.triangle[t1] = out.triangle[t2] = 1;
  }
}

//! Vertices above the bed lower than all their neighbours, the solid above them.
void find_tips(const OnBed& s, KeelsAndTips& out) {
  const core::Adjacency ring =
      core::vertex_vertices(s.edges, static_cast<int>(s.mesh.points.size()));
  const core::Adjacency vertex_tris = core::vertex_cells(s.mesh);
  for (int v = 0; v < ring.size(); ++v) {
    if (ring.degree(v) == 0 || s.on_bed(v)) continue;
    const auto nbrs = ring[v];
    if (!std::all_of(nbrs.begin(), nbrs.end(), [&](int u) { return s.h.z[u] > s.h.z[v]; }))
      continue;
    Vec3 sum = Vec3::Zero();
    for (const int t : vertex_tris[v]) sum += s.normal[static_cast<std::size_t>(t)];
    if (sum.dot(s.d) <= 0.0) continue;  // the bottom of a pit: the solid is below it
    ++out.tips;
    for (const int t : vertex_tris[v]) out.triangle[static_cast<std::size_t>(t)] = 1;
  }
}

}  // namespace

KeelsAndTips keels_and_tips(const core::TriMesh& mesh, const Vec3& down, double overhang_degrees) {
  const OnBed standing(mesh, down);
  KeelsAndTips out;
  out.triangle.assign(mesh.cells.size(), 0);
  find_keels(standing, overhanging(mesh, down, overhang_degrees),
             std::tan(overhang_degrees * M_PI / 180.0), out);
  find_tips(standing, out);
  return out;
}

std::vector<std::uint8_t> overhanging(const core::TriMesh& mesh, const Vec3& down,
                                      double overhang_degrees) {
  const Vec3 d = down.normalized();
  const Heights h = heights(mesh, d);
  const double steep = std::cos(overhang_degrees * M_PI / 180.0);
  std::vector<std::uint8_t> out(mesh.cells.size(), 0);
  for (std::size_t t = 0; t < mesh.cells.size(); ++t) {
    const Vec3 n = area_normal(mesh, t);
    const double len = n.norm();
    if (len == 0.0 || n.dot(d) / len <= steep) continue;
    const auto& c = mesh.cells[t];
    const bool on_bed =
        std::all_of(c.begin(), c.end(), [&](int v) { return h.z[v] <= h.bed + h.eps; });
    out[t] = on_bed ? 0 : 1;
  }
  return out;
}

std::string describe_keels_and_tips(const Standing& s) {
  std::string text;
  if (s.keels > 0)
    text = fmt::format("{} keel edge{} ({:.4g} long)", s.keels, s.keels == 1 ? "" : "s",
                       s.keel_length);
  if (s.tips > 0)
    text += fmt::format("{}{} tip{} pointing down", text.empty() ? "" : ", ", s.tips,
                        s.tips == 1 ? "" : "s");
  return text;
}

std::vector<std::uint8_t> support_marks(const core::TriMesh& mesh, const Vec3& down,
                                        double overhang_degrees) {
  std::vector<std::uint8_t> marks = overhanging(mesh, down, overhang_degrees);
  const KeelsAndTips k = keels_and_tips(mesh, down, overhang_degrees);
  for (std::size_t t = 0; t < marks.size(); ++t)
    if (k.triangle[t] && !marks[t]) marks[t] = 2;
  return marks;
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
  const KeelsAndTips k = keels_and_tips(mesh, s.down, options.overhang_degrees);
  s.keels = k.keels;
  s.keel_length = k.keel_length;
  s.tips = k.tips;
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
      if (s.keel_length != o.keel_length) return s.keel_length < o.keel_length;
      if (s.tips != o.tips) return s.tips < o.tips;
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
