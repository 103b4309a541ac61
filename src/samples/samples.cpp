//! The built-in sample shapes: their CSG recipes and the registry (no CGAL here: the CSG
//! toolkit in solid.h hides it).
#include "samples/samples.h"

#include "core/errors.h"
#include "core/log.h"
#include "samples/solid.h"

#include <fmt/format.h>

#include <cmath>
#include <functional>

namespace polycube::samples {

namespace {

using detail::Frame;
using detail::Solid;
using Eigen::Vector2d;

constexpr int kBigSegments = 64;    // polygonal cylinders of radius >= 15 mm
constexpr int kSmallSegments = 48;  // holes

//! A sample: its public description, its CSG recipe and its size limits.
struct Recipe {
  SampleInfo info;
  std::function<Solid()> build;
  double default_edge_length;  //!< mm: bounding-box diagonal / 55
  double max_edge_length;      //!< mm: half the smallest feature (hole radius or wall)
};

//! Vertical (z-axis) cylinder of radius r centred at (x,y), from z0 to z1.
Solid z_cylinder(double x, double y, double r, double z0, double z1, int segments) {
  return detail::prism(detail::regular_polygon({x, y}, r, segments), Frame{}, z0, z1);
}

//! Axis-aligned box [x0,x1] x [y0,y1] x [z0,z1].
Solid box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return detail::prism(detail::rectangle(x0, y0, x1, y1), Frame{}, z0, z1);
}

// Cutting tools stick out of the part by kOverlap, and added solids start inside the part, so
// no boolean has coplanar faces to resolve.
constexpr double kOverlap = 2.0;

// box-cylinder: box 100 x 60 x 40, cylinder r = 20, h = 40 centred on its top face.
Solid build_box_cylinder() {
  const Solid base = box(0, 0, 0, 100, 60, 40);
  const Solid post = z_cylinder(50, 30, 20, 30, 80, kBigSegments);  // sunk 10 mm into the box
  return detail::unite(base, post);
}

// l-bracket: L profile in the xz plane (base 80 x 15, upright 15 x 60), 40 wide along y;
// one vertical hole r = 8 through the base at (x, y) = (50, 20).
Solid build_l_bracket() {
  const detail::Polygon2 profile = {{0, 0}, {80, 0}, {80, 15}, {15, 15}, {15, 60}, {0, 60}};
  // Frame (u, v, w) = (x, z, -y) is right-handed; sweep w over [-40, 0] to get y in [0, 40].
  Frame xz;
  xz.e_u = core::Vec3::UnitX();
  xz.e_v = core::Vec3::UnitZ();
  xz.e_w = -core::Vec3::UnitY();
  const Solid body = detail::prism(profile, xz, -40, 0);
  const Solid hole = z_cylinder(50, 20, 8, -kOverlap, 15 + kOverlap, kSmallSegments);
  return detail::subtract(body, hole);
}

// flange: disc r = 50, 12 thick; hub r = 22 rising to z = 40; two holes r = 6 through the disc
// at (±36, 0).
Solid build_flange() {
  const Solid disc = z_cylinder(0, 0, 50, 0, 12, kBigSegments);
  const Solid hub = z_cylinder(0, 0, 22, 6, 40, kBigSegments);  // sunk 6 mm into the disc
  Solid part = detail::unite(disc, hub);
  for (const double x : {-36.0, 36.0})
    part = detail::subtract(part, z_cylinder(x, 0, 6, -kOverlap, 12 + kOverlap, kSmallSegments));
  return part;
}

// ring: annulus R = 40, r = 28, 20 high.
Solid build_ring() {
  const Solid outer = z_cylinder(0, 0, 40, 0, 20, kBigSegments);
  const Solid inner = z_cylinder(0, 0, 28, -kOverlap, 20 + kOverlap, kBigSegments);
  return detail::subtract(outer, inner);
}

double diagonal(double dx, double dy, double dz) { return std::sqrt(dx * dx + dy * dy + dz * dz); }

const std::vector<Recipe>& recipes() {
  static const std::vector<Recipe> all = {
      {{"box-cylinder", "box 100x60x40 mm with a cylinder r=20 h=40 standing on its top", 0},
       build_box_cylinder,
       diagonal(100, 60, 80) / 55.0,
       10.0},
      {{"l-bracket", "L-bracket 80x40x60 mm, 15 mm thick, one through-hole r=8 in its base", 1},
       build_l_bracket,
       diagonal(80, 40, 60) / 55.0,
       4.0},
      {{"flange", "disc r=50 t=12 mm with a hub r=22 up to z=40 and two through-holes r=6", 2},
       build_flange,
       diagonal(100, 100, 40) / 55.0,
       3.0},
      {{"ring", "thick ring R=40 r=28 h=20 mm (annular cylinder)", 1},
       build_ring,
       diagonal(80, 80, 20) / 55.0,
       6.0},
  };
  return all;
}

//! Estimated triangle count of an isotropic mesh of edge length l over a surface of area a.
double estimated_triangles(double a, double l) { return a / (std::sqrt(3.0) / 4.0 * l * l); }

constexpr double kMaxTriangles = 2e6;

}  // namespace

std::vector<SampleInfo> list_samples() {
  std::vector<SampleInfo> out;
  for (const Recipe& r : recipes()) out.push_back(r.info);
  return out;
}

core::TriMesh make_sample(const std::string& name, const SampleOptions& opt) {
  const Recipe* recipe = nullptr;
  std::string names;
  for (const Recipe& r : recipes()) {
    if (r.info.name == name) recipe = &r;
    names += (names.empty() ? "" : ", ") + r.info.name;
  }
  if (recipe == nullptr)
    throw core::InputError(fmt::format("unknown sample '{}' (valid: {})", name, names));

  const double l = opt.target_edge_length;
  if (!std::isfinite(l) || l < 0.0)
    throw core::InputError(
        fmt::format("sample '{}': target edge length must be a finite number "
                    ">= 0 (0: default), got {}",
                    name, l));
  if (l > recipe->max_edge_length)
    throw core::InputError(
        fmt::format("sample '{}': target edge length {} mm is larger than the "
                    "shape's smallest feature allows ({} mm)",
                    name, l, recipe->max_edge_length));

  const Solid solid = recipe->build();
  detail::RemeshParams params;
  params.target_edge_length = l > 0.0 ? l : recipe->default_edge_length;
  const double estimate = estimated_triangles(detail::area(solid), params.target_edge_length);
  if (estimate > kMaxTriangles)
    throw core::InputError(
        fmt::format("sample '{}': target edge length {} mm would give about "
                    "{:.0f} triangles (limit {:.0f})",
                    name, params.target_edge_length, estimate, kMaxTriangles));

  core::logger().debug("sample {}: remeshing to edge length {:.3g} mm", name,
                       params.target_edge_length);
  core::TriMesh mesh = detail::remesh(solid, params);
  core::logger().debug("sample {}: {} vertices, {} triangles", name, mesh.num_points(),
                       mesh.num_cells());
  return mesh;
}

}  // namespace polycube::samples
