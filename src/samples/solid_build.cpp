//! Primitives of the samples' CSG toolkit: prisms from polygons, and conversions.
#include "samples/cgal_mesh.h"

#include "core/errors.h"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <Eigen/Geometry>

#include <array>
#include <atomic>
#include <cmath>
#include <numbers>
#include <string>

namespace polycube::samples::detail {

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

//! Ear clipping of a simple counter-clockwise polygon into n-2 counter-clockwise triangles.
//! O(n^2) per ear; the polygons here have at most a few dozen vertices.
std::vector<std::array<int, 3>> ear_clip(const Polygon2& poly) {
  std::vector<int> ring(poly.size());
  for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = static_cast<int>(i);
  std::vector<std::array<int, 3>> tris;
  while (ring.size() > 3) {
    const std::size_t n = ring.size();
    bool clipped = false;
    for (std::size_t k = 0; k < n && !clipped; ++k) {
      const int a = ring[(k + n - 1) % n], b = ring[k], c = ring[(k + 1) % n];
      if (cross2(poly[a], poly[b], poly[c]) <= 0.0) continue;  // reflex or flat corner
      bool empty = true;
      for (int q : ring) {
        if (q == a || q == b || q == c) continue;
        if (cross2(poly[a], poly[b], poly[q]) >= 0.0 && cross2(poly[b], poly[c], poly[q]) >= 0.0 &&
            cross2(poly[c], poly[a], poly[q]) >= 0.0) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      tris.push_back({a, b, c});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(k));
      clipped = true;
    }
    PC_REQUIRE(clipped, "ear clipping found no ear: polygon not simple or not counter-clockwise");
  }
  tris.push_back({ring[0], ring[1], ring[2]});
  return tris;
}

//! A fresh block of n facet ids. Ids only label which triangles share a planar facet; they are
//! compared for equality and never ordered, so sharing the counter across threads is harmless.
int new_facet_ids(int n) {
  static std::atomic<int> next{0};
  return next.fetch_add(n);
}

double signed_area(const Polygon2& poly) {
  double a = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % poly.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

}  // namespace

Solid::Solid(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

Polygon2 regular_polygon(const Eigen::Vector2d& c, double r, int n) {
  PC_REQUIRE(n >= 3 && r > 0.0, "regular_polygon needs n >= 3 and r > 0");
  Polygon2 poly;
  poly.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * std::numbers::pi * i / n;
    poly.emplace_back(c.x() + r * std::cos(t), c.y() + r * std::sin(t));
  }
  return poly;
}

Polygon2 rectangle(double x0, double y0, double x1, double y1) {
  PC_REQUIRE(x0 < x1 && y0 < y1, "rectangle needs x0 < x1 and y0 < y1");
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

Solid prism(const Polygon2& polygon, const Frame& frame, double w0, double w1) {
  PC_REQUIRE(polygon.size() >= 3 && w0 < w1, "prism needs a polygon and w0 < w1");
  PC_REQUIRE(signed_area(polygon) > 0.0, "prism polygon must be counter-clockwise");
  const int n = static_cast<int>(polygon.size());
  const bool right_handed = frame.e_u.cross(frame.e_v).dot(frame.e_w) > 0.0;

  SurfaceMesh m;
  FacetMap facet = facet_map(m);
  const int top_id = new_facet_ids(n + 2), bottom_id = top_id + 1, side_id = top_id + 2;
  using VI = SurfaceMesh::Vertex_index;
  std::vector<VI> bottom(polygon.size()), top(polygon.size());
  auto world = [&](const Eigen::Vector2d& p, double w) {
    const core::Vec3 x = frame.origin + p.x() * frame.e_u + p.y() * frame.e_v + w * frame.e_w;
    return Point3(x.x(), x.y(), x.z());
  };
  for (int i = 0; i < n; ++i) bottom[i] = m.add_vertex(world(polygon[i], w0));
  for (int i = 0; i < n; ++i) top[i] = m.add_vertex(world(polygon[i], w1));

  // Counter-clockwise seen from +w is outward for the top cap of a right-handed frame.
  auto add = [&](VI a, VI b, VI c, int id) {
    const auto f = right_handed ? m.add_face(a, b, c) : m.add_face(a, c, b);
    PC_REQUIRE(f != SurfaceMesh::null_face(), "prism: non-manifold face insertion");
    facet[f] = id;
  };
  for (const auto& t : ear_clip(polygon)) {
    add(top[t[0]], top[t[1]], top[t[2]], top_id);
    add(bottom[t[0]], bottom[t[2]], bottom[t[1]], bottom_id);
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    add(bottom[i], bottom[j], top[j], side_id + i);
    add(bottom[i], top[j], top[i], side_id + i);
  }
  return make_solid(std::move(m));
}

double area(const Solid& s) { return CGAL::Polygon_mesh_processing::area(s.impl().mesh); }

core::TriMesh to_tri_mesh(const Solid& s) {
  const SurfaceMesh& m = s.impl().mesh;
  PC_REQUIRE(!m.has_garbage(), "to_tri_mesh: mesh has garbage");
  core::TriMesh out;
  out.points.reserve(m.number_of_vertices());
  for (auto v : m.vertices()) {
    const Point3& p = m.point(v);
    out.points.emplace_back(p.x(), p.y(), p.z());
  }
  out.cells.reserve(m.number_of_faces());
  for (auto f : m.faces()) {
    core::Tri t{};
    int k = 0;
    for (auto v : m.vertices_around_face(m.halfedge(f))) {
      PC_REQUIRE(k < 3, "to_tri_mesh: face is not a triangle");
      t[static_cast<std::size_t>(k++)] = static_cast<int>(v.idx());
    }
    PC_REQUIRE(k == 3, "to_tri_mesh: face is not a triangle");
    out.cells.push_back(t);
  }
  return out;
}

}  // namespace polycube::samples::detail
