//! Tests of the built-in samples: topology, size, orientation, volume against the analytic
//! CSG shape, geometric fidelity (vertices on the shape, CAD edges kept), no self-intersection,
//! determinism, and argument checking.
#include "samples/samples.h"

#include "core/errors.h"
#include "core/topology.h"
#include "support/exact_geometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <string>

namespace {

using polycube::core::TriMesh;
using polycube::core::Vec3;
using polycube::test::self_intersects;
namespace samples = polycube::samples;
constexpr double kPi = std::numbers::pi;

// --- analytic CSG shapes (signed distance: negative inside) ------------------------------------

double sd_box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 q = (p - 0.5 * (lo + hi)).cwiseAbs() - 0.5 * (hi - lo);
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

//! Solid circular cylinder about the z axis through (cx, cy), from z0 to z1.
double sd_zcyl(const Vec3& p, double cx, double cy, double r, double z0, double z1) {
  const double dr = std::hypot(p.x() - cx, p.y() - cy) - r;
  const double dz = std::abs(p.z() - 0.5 * (z0 + z1)) - 0.5 * (z1 - z0);
  return std::min(std::max(dr, dz), 0.0) + std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
}

double sd_union(double a, double b) { return std::min(a, b); }
double sd_minus(double a, double b) { return std::max(a, -b); }

//! What each sample is meant to be, written independently of the generator.
struct Expected {
  std::function<double(const Vec3&)> sdf;
  double volume;  //!< mm^3 of the ideal (circular) CSG shape
  Vec3 bbox_min, bbox_max;
  double min_radius;  //!< smallest radius of a circular feature (bounds the chord error)
  //! Largest gap between a polygonal cylinder and its circle: r (1 - cos(pi / n)) over the
  //! shape's cylinders of radius r with n segments (64 for radii >= 15 mm, 48 below).
  double max_sagitta;
};

double sagitta(double r) { return r * (1.0 - std::cos(kPi / (r >= 15 ? 64 : 48))); }

Expected expected(const std::string& name) {
  if (name == "box-cylinder")
    // V = 100*60*40 + pi*20^2*40
    return {[](const Vec3& p) {
              return sd_union(sd_box(p, {0, 0, 0}, {100, 60, 40}), sd_zcyl(p, 50, 30, 20, 30, 80));
            },
            100.0 * 60 * 40 + kPi * 20 * 20 * 40,
            {0, 0, 0},
            {100, 60, 80},
            20,
            sagitta(20)};
  if (name == "l-bracket")
    // V = (80*15 + 15*45)*40 - pi*8^2*15
    return {[](const Vec3& p) {
              const double l =
                  sd_union(sd_box(p, {0, 0, 0}, {80, 40, 15}), sd_box(p, {0, 0, 0}, {15, 40, 60}));
              return sd_minus(l, sd_zcyl(p, 50, 20, 8, -2, 17));
            },
            (80.0 * 15 + 15.0 * 45) * 40 - kPi * 64 * 15,
            {0, 0, 0},
            {80, 40, 60},
            8,
            sagitta(8)};
  if (name == "flange")
    // V = pi*50^2*12 + pi*22^2*28 - 2*pi*6^2*12
    return {[](const Vec3& p) {
              double d = sd_union(sd_zcyl(p, 0, 0, 50, 0, 12), sd_zcyl(p, 0, 0, 22, 6, 40));
              d = sd_minus(d, sd_zcyl(p, -36, 0, 6, -2, 14));
              return sd_minus(d, sd_zcyl(p, 36, 0, 6, -2, 14));
            },
            kPi * (2500.0 * 12 + 484.0 * 28 - 2 * 36.0 * 12),
            {-50, -50, 0},
            {50, 50, 40},
            6,
            sagitta(50)};
  // ring: V = pi*(40^2 - 28^2)*20
  return {[](const Vec3& p) {
            return sd_minus(sd_zcyl(p, 0, 0, 40, 0, 20), sd_zcyl(p, 0, 0, 28, -2, 22));
          },
          kPi * (1600.0 - 784.0) * 20,
          {-40, -40, 0},
          {40, 40, 20},
          28,
          sagitta(40)};
}

// --- helpers -----------------------------------------------------------------------------------

//! Samples are generated once per test program (each takes a fraction of a second).
const TriMesh& sample(const std::string& name) {
  static std::map<std::string, TriMesh> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, samples::make_sample(name)).first;
  return it->second;
}

std::vector<std::string> names() {
  std::vector<std::string> out;
  for (const auto& s : samples::list_samples()) out.push_back(s.name);
  return out;
}

int genus_of(const std::string& name) {
  for (const auto& s : samples::list_samples())
    if (s.name == name) return s.genus;
  return -100;
}

// --- registry and argument checks -------------------------------------------------------------

TEST(Samples, ListIsFixedAndDescribed) {
  const auto list = samples::list_samples();
  ASSERT_EQ(list.size(), 4u);
  EXPECT_EQ(list[0].name, "box-cylinder");
  EXPECT_EQ(list[1].name, "l-bracket");
  EXPECT_EQ(list[2].name, "flange");
  EXPECT_EQ(list[3].name, "ring");
  EXPECT_EQ(list[0].genus, 0);
  EXPECT_EQ(list[1].genus, 1);
  EXPECT_EQ(list[2].genus, 2);
  EXPECT_EQ(list[3].genus, 1);
  for (const auto& s : list) EXPECT_FALSE(s.description.empty()) << s.name;
}

TEST(Samples, UnknownNameIsInputErrorListingValidNames) {
  try {
    (void)samples::make_sample("teapot");
    FAIL() << "no exception";
  } catch (const polycube::core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("teapot"), std::string::npos) << what;
    for (const auto& n : names()) EXPECT_NE(what.find(n), std::string::npos) << what;
  }
}

TEST(Samples, BadEdgeLengthIsInputError) {
  using polycube::core::InputError;
  for (const double l : {-1.0, std::numeric_limits<double>::quiet_NaN(),
                         std::numeric_limits<double>::infinity(), 50.0, 0.01}) {
    samples::SampleOptions opt;
    opt.target_edge_length = l;
    EXPECT_THROW((void)samples::make_sample("ring", opt), InputError) << "edge length " << l;
  }
}

// --- properties of every sample ---------------------------------------------------------------

class EverySample : public ::testing::TestWithParam<std::string> {};

TEST_P(EverySample, ClosedManifoldOrientedOfStatedGenus) {
  const TriMesh& m = sample(GetParam());
  const auto r = polycube::core::analyze_surface(m);
  EXPECT_TRUE(r.closed);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.orientable);
  EXPECT_TRUE(r.consistently_oriented);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.degenerate_faces, 0);
  EXPECT_EQ(r.isolated_vertices, 0);
  EXPECT_EQ(r.genus, genus_of(GetParam()));
  EXPECT_EQ(r.euler_characteristic, 2 - 2 * genus_of(GetParam()));
}

TEST_P(EverySample, TriangleCountInRange) {
  const TriMesh& m = sample(GetParam());
  EXPECT_GE(m.num_cells(), 2000);
  EXPECT_LE(m.num_cells(), 30000);
  RecordProperty("triangles", m.num_cells());
  RecordProperty("vertices", m.num_points());
}

TEST_P(EverySample, OutwardWithAnalyticVolume) {
  const TriMesh& m = sample(GetParam());
  const Expected e = expected(GetParam());
  const double v = polycube::core::signed_volume(m);
  EXPECT_GT(v, 0.0) << "normals point inward";
  // Cylinders are inscribed polygons: 64 and 48 segments lose < 0.3 % of their cross-section.
  EXPECT_NEAR(v / e.volume, 1.0, 0.01) << "volume " << v << " vs analytic " << e.volume;
}

TEST_P(EverySample, BoundingBoxInMillimetres) {
  const TriMesh& m = sample(GetParam());
  const Expected e = expected(GetParam());
  const auto b = polycube::core::bounding_box(m.points);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], e.bbox_min[k], 1e-6) << "axis " << k;
    EXPECT_NEAR(b.max[k], e.bbox_max[k], 1e-6) << "axis " << k;
  }
}

TEST_P(EverySample, NoSelfIntersection) { EXPECT_FALSE(self_intersects(sample(GetParam()))); }

// Vertices lie on the CSG shape (up to the polygonal cylinders' sagitta), and triangle
// centroids stay within the chord error of a circle of the smallest radius: a sharp edge cut
// by the remeshing (a chamfer of about one edge length) would move centroids by ~L/3.
TEST_P(EverySample, SurfaceFollowsTheShapeAndKeepsItsEdges) {
  const TriMesh& m = sample(GetParam());
  const Expected e = expected(GetParam());
  double max_vertex = 0.0;
  for (const Vec3& p : m.points) max_vertex = std::max(max_vertex, std::abs(e.sdf(p)));
  double max_centroid = 0.0, sum_edge = 0.0;
  for (const auto& t : m.cells) {
    const Vec3 c = (m.points[t[0]] + m.points[t[1]] + m.points[t[2]]) / 3.0;
    max_centroid = std::max(max_centroid, std::abs(e.sdf(c)));
    for (int k = 0; k < 3; ++k) sum_edge += (m.points[t[k]] - m.points[t[(k + 1) % 3]]).norm();
  }
  const double mean_edge = sum_edge / (3.0 * m.num_cells());
  // Vertices sit on the polygonal cylinders, at most one sagitta inside the circles.
  const double vertex_tol = e.max_sagitta + 1e-6;
  // A triangle spans a chord of at most ~1.5 mean edge lengths on the smallest circle.
  const double chord = 1.5 * mean_edge;
  const double centroid_tol = chord * chord / (8.0 * e.min_radius) + vertex_tol;
  EXPECT_LE(max_vertex, vertex_tol);
  EXPECT_LE(max_centroid, centroid_tol) << "mean edge " << mean_edge;
  RecordProperty("max_vertex_deviation_um", static_cast<int>(max_vertex * 1000));
  RecordProperty("max_centroid_deviation_um", static_cast<int>(max_centroid * 1000));
}

// Isotropic: edges are of even length and triangles are not slivers.
TEST_P(EverySample, EvenTriangleSize) {
  const TriMesh& m = sample(GetParam());
  std::vector<double> lengths;
  double min_angle = 180.0;
  for (const auto& t : m.cells) {
    for (int k = 0; k < 3; ++k) {
      const Vec3& a = m.points[t[k]];
      const Vec3 u = m.points[t[(k + 1) % 3]] - a, w = m.points[t[(k + 2) % 3]] - a;
      lengths.push_back(u.norm());
      const double ang = std::acos(std::clamp(u.dot(w) / (u.norm() * w.norm()), -1.0, 1.0));
      min_angle = std::min(min_angle, ang * 180.0 / kPi);
    }
  }
  std::sort(lengths.begin(), lengths.end());
  const double median = lengths[lengths.size() / 2];
  const double p02 = lengths[lengths.size() * 2 / 100], p98 = lengths[lengths.size() * 98 / 100];
  EXPECT_GT(p02, 0.4 * median);
  EXPECT_LT(p98, 2.0 * median);
  EXPECT_GT(min_angle, 10.0);
  RecordProperty("min_angle_deg_x10", static_cast<int>(min_angle * 10));
}

// Same triangles on every run, whatever the state of the heap (CGAL's corefinement breaks some
// ties by comparing addresses; the samples module canonicalizes its result).
TEST_P(EverySample, Deterministic) {
  const TriMesh& a = sample(GetParam());
  std::vector<std::vector<char>> junk;
  for (int i = 0; i < 500; ++i) junk.emplace_back(static_cast<std::size_t>(64 + 97 * i));
  for (std::size_t i = 0; i < junk.size(); i += 2) junk[i] = {};
  const TriMesh b = samples::make_sample(GetParam());
  ASSERT_EQ(a.points.size(), b.points.size());
  ASSERT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) ASSERT_EQ(a.points[i], b.points[i]) << i;
  for (std::size_t i = 0; i < a.cells.size(); ++i) ASSERT_EQ(a.cells[i], b.cells[i]) << i;
}

INSTANTIATE_TEST_SUITE_P(Builtin, EverySample, ::testing::ValuesIn(names()),
                         [](const auto& param_info) {
                           std::string s = param_info.param;
                           std::replace(s.begin(), s.end(), '-', '_');
                           return s;
                         });

// A user edge length gives a different, still valid mesh.
TEST(Samples, CoarserEdgeLengthStaysValid) {
  samples::SampleOptions opt;
  opt.target_edge_length = 3.0;
  const TriMesh m = samples::make_sample("flange", opt);
  const auto r = polycube::core::analyze_surface(m);
  EXPECT_TRUE(r.closed && r.manifold && r.consistently_oriented);
  EXPECT_EQ(r.genus, 2);
  EXPECT_LT(m.num_cells(), sample("flange").num_cells());
  EXPECT_FALSE(self_intersects(m));
}

}  // namespace
