//! Sharp features of a target surface and closest-point queries (see features.h).
#include "optimize/features.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace polycube::optimize {

namespace {

using core::Vec3;
using K = CGAL::Simple_cartesian<double>;
using Point3 = K::Point_3;
using Triangle3 = K::Triangle_3;
using Segment3 = K::Segment_3;
using TriPrimitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle3>::const_iterator>;
using TriTree = CGAL::AABB_tree<CGAL::AABB_traits<K, TriPrimitive>>;
using SegPrimitive = CGAL::AABB_segment_primitive<K, std::vector<Segment3>::const_iterator>;
using SegTree = CGAL::AABB_tree<CGAL::AABB_traits<K, SegPrimitive>>;

Point3 to_cgal(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
Vec3 from_cgal(const Point3& p) { return {p.x(), p.y(), p.z()}; }

}  // namespace

SurfaceFeatures detect_features(const core::TriMesh& surface, double angle_degrees) {
  PC_REQUIRE(angle_degrees > 0 && angle_degrees < 180, "detect_features: angle out of (0, 180)");
  core::check_indices(surface);
  const auto et = core::unique_edges(surface);
  const core::Adjacency ec = core::edge_cells(et);
  std::vector<std::optional<Vec3>> normal(surface.cells.size());
  for (std::size_t f = 0; f < surface.cells.size(); ++f) {
    const auto& t = surface.cells[f];
    const Vec3 n = (surface.points[t[1]] - surface.points[t[0]]).cross(surface.points[t[2]] - surface.points[t[0]]);
    if (n.norm() > 0) normal[f] = n.normalized();
  }
  const double cos_max = std::cos(angle_degrees * std::numbers::pi / 180.0);
  SurfaceFeatures out;
  for (int e = 0; e < et.num_edges(); ++e) {
    const auto cells = ec[e];
    bool sharp = cells.size() != 2;
    if (!sharp) {
      const auto& n0 = normal[cells[0]];
      const auto& n1 = normal[cells[1]];
      sharp = n0 && n1 && n0->dot(*n1) < cos_max;
    }
    if (sharp && et.edges[e][0] != et.edges[e][1]) out.edges.push_back(et.edges[e]);
  }
  // Valence in the feature graph; corners where it is not 2.
  std::vector<int> valence(surface.points.size(), 0);
  for (const auto& e : out.edges) {
    ++valence[e[0]];
    ++valence[e[1]];
  }
  for (int v = 0; v < surface.num_points(); ++v)
    if (valence[v] > 0 && valence[v] != 2) out.corners.push_back(v);
  // Lines: edges joined at valence-2 vertices.
  const int ne = static_cast<int>(out.edges.size());
  core::DisjointSets ds(ne);
  std::vector<int> first_edge(surface.points.size(), -1);
  for (int e = 0; e < ne; ++e)
    for (int v : out.edges[e]) {
      if (valence[v] != 2) continue;
      if (first_edge[v] < 0) first_edge[v] = e;
      else ds.unite(first_edge[v], e);
    }
  out.edge_line.assign(ne, -1);
  std::vector<int> line_of_root(ne, -1);
  for (int e = 0; e < ne; ++e) {
    const int r = ds.find(e);
    if (line_of_root[r] < 0) line_of_root[r] = out.num_lines++;
    out.edge_line[e] = line_of_root[r];
  }
  return out;
}

struct TargetSurface::Impl {
  core::TriMesh surface;
  SurfaceFeatures features;
  std::vector<Triangle3> triangles;
  std::vector<Vec3> normals;  //!< outward unit normal of each triangle
  std::vector<Segment3> segments;
  TriTree tri_tree;
  SegTree seg_tree;
  double diagonal = 0;
};

TargetSurface::TargetSurface(const core::TriMesh& surface, SurfaceFeatures features)
    : impl_(std::make_unique<Impl>()) {
  core::check_indices(surface);
  Impl& m = *impl_;
  m.surface = surface;
  m.features = std::move(features);
  for (const auto& t : surface.cells) {
    const Triangle3 tri(to_cgal(surface.points[t[0]]), to_cgal(surface.points[t[1]]), to_cgal(surface.points[t[2]]));
    if (!tri.is_degenerate()) m.triangles.push_back(tri);
  }
  if (m.triangles.empty()) throw core::InputError("target surface: no non-degenerate triangle");
  // Outward normals: flip them all when the surface encloses a negative volume.
  double volume6 = 0.0;
  for (const auto& t : m.triangles) {
    const Vec3 a = from_cgal(t[0]), b = from_cgal(t[1]), c = from_cgal(t[2]);
    volume6 += a.dot(b.cross(c));
    m.normals.push_back((b - a).cross(c - a).normalized());
  }
  if (volume6 < 0)
    for (Vec3& n : m.normals) n = -n;
  m.tri_tree.insert(m.triangles.begin(), m.triangles.end());
  m.tri_tree.accelerate_distance_queries();
  for (const auto& e : m.features.edges)
    if (surface.points[e[0]] != surface.points[e[1]])
      m.segments.emplace_back(to_cgal(surface.points[e[0]]), to_cgal(surface.points[e[1]]));
  if (!m.segments.empty()) {
    m.seg_tree.insert(m.segments.begin(), m.segments.end());
    m.seg_tree.accelerate_distance_queries();
  }
  std::vector<Vec3> used;
  for (const auto& t : surface.cells)
    for (int v : t) used.push_back(surface.points[v]);
  m.diagonal = core::bounding_box(used).diagonal();
}

TargetSurface::~TargetSurface() = default;
TargetSurface::TargetSurface(TargetSurface&&) noexcept = default;
TargetSurface& TargetSurface::operator=(TargetSurface&&) noexcept = default;

Vec3 TargetSurface::closest_point(const Vec3& p) const { return from_cgal(impl_->tri_tree.closest_point(to_cgal(p))); }

Vec3 TargetSurface::normal(const Vec3& p) const {
  const auto hit = impl_->tri_tree.closest_point_and_primitive(to_cgal(p));
  return impl_->normals[static_cast<std::size_t>(hit.second - impl_->triangles.begin())];
}

namespace {

//! CGAL AABB traversal traits: the closest point among the primitives whose normal faces n
//! (a node is visited only when its box is closer than the best point so far).
class FacingProjection {
 public:
  //! Only points closer than sqrt(bound2) count.
  FacingProjection(const std::vector<Triangle3>& triangles, const std::vector<Vec3>& normals, const Vec3& n,
                   double bound2)
      : triangles_(triangles), normals_(normals), n_(n), best_(bound2) {}
  [[nodiscard]] bool go_further() const { return true; }
  void intersection(const Point3& q, const TriPrimitive& primitive) {
    const auto k = static_cast<std::size_t>(primitive.id() - triangles_.begin());
    if (!(normals_[k].dot(n_) > 0)) return;
    const Point3 c = K().construct_projected_point_3_object()(*primitive.id(), q);
    const double d = CGAL::squared_distance(q, c);
    if (d < best_) {
      best_ = d;
      point_ = c;
      index_ = k;
    }
  }
  template <class Node>
  [[nodiscard]] bool do_intersect(const Point3& q, const Node& node) const {
    const CGAL::Bbox_3& b = node.bbox();
    double d = 0;
    for (int i = 0; i < 3; ++i) {
      const double below = b.min(i) - q[i], above = q[i] - b.max(i);
      const double gap = std::max({below, above, 0.0});
      d += gap * gap;
    }
    return d < best_;
  }
  [[nodiscard]] bool found() const { return index_ != kNone; }
  [[nodiscard]] Vec3 point() const { return from_cgal(point_); }
  [[nodiscard]] std::size_t index() const { return index_; }

 private:
  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  const std::vector<Triangle3>& triangles_;
  const std::vector<Vec3>& normals_;
  Vec3 n_;
  double best_;
  Point3 point_;
  std::size_t index_ = kNone;
};

}  // namespace

std::pair<Vec3, Vec3> TargetSurface::closest_point_facing(const Vec3& p, const Vec3& n, double reach) const {
  const Impl& m = *impl_;
  const auto hit = m.tri_tree.closest_point_and_primitive(to_cgal(p));
  const auto k = static_cast<std::size_t>(hit.second - m.triangles.begin());
  const std::pair<Vec3, Vec3> closest{from_cgal(hit.first), m.normals[k]};
  if (m.normals[k].dot(n) > 0 || !(n.squaredNorm() > 0) || !(reach > 0)) return closest;
  const double bound = (closest.first - p).norm() + reach;
  FacingProjection facing(m.triangles, m.normals, n, bound * bound);
  m.tri_tree.traversal(to_cgal(p), facing);
  if (!facing.found()) return closest;
  return {facing.point(), m.normals[facing.index()]};
}

Vec3 TargetSurface::closest_feature_point(const Vec3& p) const {
  if (impl_->segments.empty()) return p;
  return from_cgal(impl_->seg_tree.closest_point(to_cgal(p)));
}

int TargetSurface::nearest_corner(const Vec3& p) const {
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  const auto& c = impl_->features.corners;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double d = (impl_->surface.points[c[k]] - p).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = static_cast<int>(k);
    }
  }
  return best;
}

Vec3 TargetSurface::corner_position(int k) const { return impl_->surface.points[impl_->features.corners[k]]; }
const SurfaceFeatures& TargetSurface::features() const { return impl_->features; }
const core::TriMesh& TargetSurface::surface() const { return impl_->surface; }
double TargetSurface::diagonal() const { return impl_->diagonal; }

}  // namespace polycube::optimize
