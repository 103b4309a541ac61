#include "quality/surface_distance.h"

#include "core/errors.h"
#include "core/topology.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <Eigen/Geometry>

#ifdef POLYCUBE_HAS_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace polycube::quality {

namespace {

using core::Vec3;
using K = CGAL::Simple_cartesian<double>;
using Triangle3 = K::Triangle_3;
using Point3 = K::Point_3;
using TriIterator = std::vector<Triangle3>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, TriIterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

Point3 to_point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

//! Check indices and finiteness; name is "surface" or "reference".
void check_surface(const core::TriMesh& m, const char* name) {
  if (m.cells.empty())
    throw core::InputError(std::string("surface distance: the ") + name + " has no triangle");
  const int nv = m.num_points();
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    for (int v : m.cells[c]) {
      if (v < 0 || v >= nv)
        throw core::InputError(std::string("surface distance: ") + name + " triangle " +
                               std::to_string(c) + " references vertex " + std::to_string(v) +
                               " outside [0, " + std::to_string(nv) + ")");
      if (!m.points[v].allFinite())
        throw core::InputError(std::string("surface distance: ") + name + " vertex " +
                               std::to_string(v) + " has a non-finite coordinate");
    }
}

//! Bounding box of the points the triangles use.
core::BoundingBox used_box(const core::TriMesh& m) {
  std::vector<Vec3> pts;
  pts.reserve(m.cells.size() * 3);
  for (const auto& t : m.cells)
    for (int v : t) pts.push_back(m.points[v]);
  return core::bounding_box(pts);
}

//! The non-degenerate triangles of a surface, for the AABB tree.
std::vector<Triangle3> tree_triangles(const core::TriMesh& m, const char* name) {
  std::vector<Triangle3> tris;
  tris.reserve(m.cells.size());
  for (const auto& t : m.cells) {
    const Vec3 &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
    const double longest =
        std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    const double area2 = (b - a).cross(c - a).norm();
    if (!(area2 > 1e-14 * longest)) continue;  // zero area (relative to the triangle's size)
    tris.emplace_back(to_point(a), to_point(b), to_point(c));
  }
  if (tris.empty())
    throw core::GeometryError(std::string("surface distance: every triangle of the ") + name +
                              " is degenerate");
  return tris;
}

//! Refinement depth allowed per triangle so that a fully refined surface stays within the
//! query budget (a split costs 7 queries: 3 midpoints and 4 child centroids).
int depth_cap(std::size_t triangles, std::size_t max_queries) {
  auto full = [](int depth) {
    return 1.0 + 7.0 * (std::pow(4.0, depth) - 1.0) / 3.0;
  };  // queries per triangle
  int depth = 0;
  while (depth < 24 &&
         static_cast<double>(triangles) * full(depth + 1) <= static_cast<double>(max_queries))
    ++depth;
  return depth;
}

//! Per-triangle (or per-block) result of the refinement.
struct Partial {
  double lower = 0.0;
  Vec3 worst = Vec3::Zero();
  double upper = 0.0;
  double weighted = 0.0;  // sum of area * centroid distance over accepted triangles
  double area = 0.0;
  std::size_t queries = 0;

  void see(double d, const Vec3& p) {
    if (d > lower) {
      lower = d;
      worst = p;
    }
  }

  //! Take in another part's results (a block's, or a triangle's), in a fixed order.
  void merge(const Partial& o) {
    see(o.lower, o.worst);
    upper = std::max(upper, o.upper);
    weighted += o.weighted;
    area += o.area;
    queries += o.queries;
  }
};

//! A measured point: its distance to the other surface and that surface's closest triangle.
struct Sample {
  double d = 0.0;
  const Triangle3* tri = nullptr;
};

//! Distance queries against one tree, with a hint carried between neighbouring queries.
class Distance {
 public:
  explicit Distance(const Tree& tree) : tree_(tree) {}
  Sample operator()(const Vec3& p, Partial& acc) {
    const Point3 q = to_point(p);
    hint_ = has_hint_ ? tree_.closest_point_and_primitive(q, hint_)
                      : tree_.closest_point_and_primitive(q);
    has_hint_ = true;
    ++acc.queries;
    const double d = std::sqrt(CGAL::squared_distance(q, hint_.first));
    acc.see(d, p);
    return {d, &*hint_.second};
  }

  //! The last query's closest point, the hint of the next one.
  const Tree::Point_and_primitive_id& hint() const { return hint_; }

  //! Start from the closest point of a nearby query made elsewhere: CGAL searches the ball
  //! through the hint, so a hint far away costs much of the tree.
  void seed(const Tree::Point_and_primitive_id& hint) {
    hint_ = hint;
    has_hint_ = true;
  }

 private:
  const Tree& tree_;
  Tree::Point_and_primitive_id hint_;
  bool has_hint_ = false;
};

struct Refiner {
  Distance& dist;
  double floor;      // lower bound known before the refinement (max over the vertices)
  double tolerance;  // absolute
  int max_depth;

  //! Upper bound of the distance over triangle v (corner samples s, centroid c with sample sc).
  static double upper_bound(const std::array<Vec3, 3>& v, const std::array<Sample, 3>& s,
                            const Vec3& c, const Sample& sc) {
    // Lipschitz bounds from the centroid and from each corner.
    double rc = 0.0;
    for (const auto& p : v) rc = std::max(rc, (p - c).norm());
    double ub = sc.d + rc;
    for (int i = 0; i < 3; ++i) {
      double reach = 0.0;
      for (int j = 0; j < 3; ++j) reach = std::max(reach, (v[j] - v[i]).norm());
      ub = std::min(ub, s[i].d + reach);
    }
    // The distance to one fixed triangle t of the other surface is convex, so over v it is at
    // most its value at v's corners; and d(p) <= dist(p, t).
    const std::array<const Triangle3*, 4> candidates{sc.tri, s[0].tri, s[1].tri, s[2].tri};
    for (int k = 0; k < 4; ++k) {
      const Triangle3* t = candidates[k];
      if (t == nullptr) continue;
      bool seen = false;
      for (int l = 0; l < k; ++l) seen = seen || candidates[l] == t;
      if (seen) continue;
      double worst = 0.0;
      for (int i = 0; i < 3 && worst < ub; ++i)
        worst = std::max(
            worst, s[i].tri == t ? s[i].d : std::sqrt(CGAL::squared_distance(to_point(v[i]), *t)));
      ub = std::min(ub, worst);
    }
    return ub;
  }

  //! Refine triangle v with corner samples s.
  void refine(const std::array<Vec3, 3>& v, const std::array<Sample, 3>& s, int depth,
              Partial& acc) {
    const Vec3 c = (v[0] + v[1] + v[2]) / 3.0;
    refine(v, s, c, dist(c, acc), depth, acc);
  }

  //! Refine triangle v with corner samples s and the sample sc of its centroid c.
  void refine(const std::array<Vec3, 3>& v, const std::array<Sample, 3>& s, const Vec3& c,
              const Sample& sc, int depth, Partial& acc) {
    const double ub = upper_bound(v, s, c, sc);
    if (ub <= std::max(floor, acc.lower) + tolerance || depth >= max_depth) {
      acc.upper = std::max(acc.upper, ub);
      const double area = 0.5 * (v[1] - v[0]).cross(v[2] - v[0]).norm();
      acc.weighted += area * sc.d;
      acc.area += area;
      return;
    }
    const std::array<Vec3, 3> m{(v[0] + v[1]) / 2.0, (v[1] + v[2]) / 2.0, (v[2] + v[0]) / 2.0};
    const std::array<Sample, 3> sm{dist(m[0], acc), dist(m[1], acc), dist(m[2], acc)};
    refine({v[0], m[0], m[2]}, {s[0], sm[0], sm[2]}, depth + 1, acc);
    refine({m[0], v[1], m[1]}, {sm[0], s[1], sm[1]}, depth + 1, acc);
    refine({m[2], m[1], v[2]}, {sm[2], sm[1], s[2]}, depth + 1, acc);
    refine({m[0], m[1], m[2]}, {sm[0], sm[1], sm[2]}, depth + 1, acc);
  }
};

//! Run body(begin, end) over fixed blocks of [0, n), in parallel when TBB is available. The
//! blocks do not depend on the thread schedule, so results written per index are deterministic.
template <class Body>
void for_blocks(std::size_t n, std::size_t block, const Body& body) {
  const std::size_t blocks = (n + block - 1) / block;
  auto run = [&](std::size_t b) { body(b * block, std::min(n, (b + 1) * block)); };
#ifdef POLYCUBE_HAS_TBB
  tbb::parallel_for(std::size_t{0}, blocks, run);
#else
  for (std::size_t b = 0; b < blocks; ++b) run(b);
#endif
}

DirectedDistance directed(const core::TriMesh& m, const Tree& tree, double tolerance,
                          std::size_t max_queries) {
  // 1. Every referenced vertex.
  const std::size_t nv = m.points.size();
  std::vector<std::uint8_t> used(nv, 0);
  for (const auto& t : m.cells)
    for (int v : t) used[v] = 1;
  std::vector<Sample> vs(nv);
  std::vector<Partial> vertex_parts((nv + 1023) / 1024);
  for_blocks(nv, 1024, [&](std::size_t begin, std::size_t end) {
    Distance dist(tree);
    Partial& acc = vertex_parts[begin / 1024];
    for (std::size_t v = begin; v < end; ++v)
      if (used[v]) vs[v] = dist(m.points[v], acc);
  });
  Partial total;
  for (const auto& p : vertex_parts) total.merge(p);

  // 2. Every triangle's centroid. The refinement accepts a triangle once its upper bound is
  //    within the tolerance of the floor, so the higher the floor, the fewer splits: where the
  //    vertices lie on the other surface (a fitted mesh's boundary) their distances are near 0,
  //    while the largest distance is inside the triangles, which a centroid usually comes close to.
  std::vector<Vec3> centroid(m.cells.size());
  std::vector<Sample> cs(m.cells.size());
  std::vector<Tree::Point_and_primitive_id> closest(m.cells.size());
  constexpr std::size_t kBlock = 64;
  std::vector<Partial> centroid_parts((m.cells.size() + kBlock - 1) / kBlock);
  for_blocks(m.cells.size(), kBlock, [&](std::size_t begin, std::size_t end) {
    Distance dist(tree);
    Partial& acc = centroid_parts[begin / kBlock];
    for (std::size_t f = begin; f < end; ++f) {
      const auto& t = m.cells[f];
      centroid[f] = (m.points[t[0]] + m.points[t[1]] + m.points[t[2]]) / 3.0;
      cs[f] = dist(centroid[f], acc);
      closest[f] = dist.hint();
    }
  });
  for (const auto& p : centroid_parts) total.merge(p);
  const double floor = total.lower;

  // 3. Adaptive refinement of every triangle against that floor.
  const int max_depth =
      depth_cap(m.cells.size(), max_queries > total.queries ? max_queries - total.queries : 0);
  std::vector<Partial> parts((m.cells.size() + kBlock - 1) / kBlock);
  for_blocks(m.cells.size(), kBlock, [&](std::size_t begin, std::size_t end) {
    Distance dist(tree);
    Refiner r{dist, floor, tolerance, max_depth};
    Partial& block = parts[begin / kBlock];
    for (std::size_t f = begin; f < end; ++f) {
      const auto& t = m.cells[f];
      Partial acc;  // per triangle: its own samples tighten only its own pruning
      for (int v : t) acc.see(vs[v].d, m.points[v]);
      acc.see(cs[f].d, centroid[f]);
      dist.seed(closest[f]);
      r.refine({m.points[t[0]], m.points[t[1]], m.points[t[2]]}, {vs[t[0]], vs[t[1]], vs[t[2]]}, centroid[f],
               cs[f], 0, acc);
      block.merge(acc);
    }
  });
  for (const auto& p : parts) total.merge(p);

  DirectedDistance r;
  r.max = total.lower;
  r.upper_bound = std::max(total.upper, total.lower);
  r.mean = total.area > 0.0 ? total.weighted / total.area : total.lower;
  r.worst_point = total.worst;
  r.queries = total.queries;
  return r;
}

}  // namespace

SurfaceDistance hausdorff_distance(const core::TriMesh& surface, const core::TriMesh& reference,
                                   const SurfaceDistanceOptions& options) {
  check_surface(surface, "surface");
  check_surface(reference, "reference");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw core::InputError("surface distance: the tolerance must be a finite number > 0");

  SurfaceDistance r;
  r.reference_diagonal = used_box(reference).diagonal();
  double tolerance = options.tolerance * r.reference_diagonal;
  if (!(tolerance > 0.0)) tolerance = options.tolerance;  // a reference reduced to a point

  const std::vector<Triangle3> surface_tris = tree_triangles(surface, "surface");
  const std::vector<Triangle3> reference_tris = tree_triangles(reference, "reference");
  Tree surface_tree(surface_tris.begin(), surface_tris.end());
  Tree reference_tree(reference_tris.begin(), reference_tris.end());
  // Build everything before the (possibly parallel) queries.
  surface_tree.build();
  reference_tree.build();
  surface_tree.accelerate_distance_queries();
  reference_tree.accelerate_distance_queries();

  r.surface_to_reference = directed(surface, reference_tree, tolerance, options.max_queries);
  r.reference_to_surface = directed(reference, surface_tree, tolerance, options.max_queries);
  r.hausdorff = std::max(r.surface_to_reference.max, r.reference_to_surface.max);
  r.hausdorff_upper =
      std::max(r.surface_to_reference.upper_bound, r.reference_to_surface.upper_bound);
  r.relative = r.reference_diagonal > 0.0 ? r.hausdorff / r.reference_diagonal : 0.0;
  return r;
}

core::TriMesh triangulate(const core::QuadMesh& quads) {
  core::TriMesh t;
  t.points = quads.points;
  t.cells.reserve(quads.cells.size() * 2);
  for (const auto& q : quads.cells) {
    t.cells.push_back({q[0], q[1], q[2]});
    t.cells.push_back({q[0], q[2], q[3]});
  }
  if (quads.labels.size() == quads.cells.size())
    for (int l : quads.labels) {
      t.labels.push_back(l);
      t.labels.push_back(l);
    }
  return t;
}

SurfaceDistance hausdorff_distance(const core::HexMesh& hexes, const core::TriMesh& reference,
                                   const SurfaceDistanceOptions& options) {
  const core::HexBoundary b = core::boundary(hexes);
  return hausdorff_distance(triangulate(b.surface), reference, options);
}

std::vector<FarVertex> vertices_farther_than(const core::TriMesh& surface, const core::TriMesh& reference,
                                             double distance) {
  check_surface(surface, "surface");
  check_surface(reference, "reference");
  const std::vector<Triangle3> tris = tree_triangles(reference, "reference");
  Tree tree(tris.begin(), tris.end());
  tree.build();
  tree.accelerate_distance_queries();
  std::vector<std::uint8_t> used(surface.points.size(), 0);
  for (const auto& t : surface.cells)
    for (int v : t) used[static_cast<std::size_t>(v)] = 1;
  std::vector<FarVertex> out;
  for (std::size_t v = 0; v < surface.points.size(); ++v) {
    if (!used[v]) continue;
    const double d2 = tree.squared_distance(to_point(surface.points[v]));
    if (d2 > distance * distance) out.push_back({surface.points[v], std::sqrt(d2)});
  }
  std::stable_sort(out.begin(), out.end(), [](const FarVertex& a, const FarVertex& b) { return a.distance > b.distance; });
  return out;
}

const SurfaceDistance* RememberedDistance::find(const core::HexMesh& hex) const {
  if (!distance_ || hex.points != points_ || hex.cells != cells_) return nullptr;
  return &*distance_;
}

void RememberedDistance::remember(const core::HexMesh& hex, const SurfaceDistance& d) {
  points_ = hex.points;
  cells_ = hex.cells;
  distance_ = d;
}

const SurfaceDistance& RememberedDistance::measure(const core::HexMesh& hex, const core::TriMesh& reference) {
  if (find(hex) == nullptr) remember(hex, hausdorff_distance(hex, reference));
  return *distance_;
}

}  // namespace polycube::quality
