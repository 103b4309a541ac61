//! Tests of the polycube deformation (construct/deform.h) and its certification
//! (construct/certify.h), with an independent certifier (certifier.h). The untangling engine it
//! uses is tested in tests/solve/test_untangle.cpp.
#include "construct/certify.h"
#include "construct/construct.h"
#include "construct/deform.h"
#include "support/certifier.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/predeform.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/polycube_map.h"
#include "core/topology.h"
#include "quality/distortion.h"
#include "support/shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

namespace polycube {
namespace {

using core::Vec3;

using test::independent_check;
using test::Verdict;

// --- fixtures ---------------------------------------------------------------------------------

//! Closed triangulated surface of the cube [0,s]^3 with n x n squares per face (outward).
core::TriMesh cube_surface(int n, double s = 1.0) { return test::make_box(s, s, s, n); }

//! Boundary triangles (volume indices, outward) of a tet mesh and labels from their normals.
void normal_labels(const core::TetMesh& mesh, std::vector<core::Tri>& tris, std::vector<int>& labels) {
  const core::TetBoundary b = core::boundary(mesh);
  tris.clear();
  labels.clear();
  for (const auto& s : b.surface.cells) {
    const core::Tri t{b.vertex_map[s[0]], b.vertex_map[s[1]], b.vertex_map[s[2]]};
    tris.push_back(t);
    const Vec3 n = (mesh.points[t[1]] - mesh.points[t[0]]).cross(mesh.points[t[2]] - mesh.points[t[0]]);
    labels.push_back(core::dominant_axis_label(n));
  }
}

// --- deformation and certification ------------------------------------------------------------

struct Constructed {
  construct::DeformResult def;
  construct::Certificate cert;
  quality::MapDistortion dist;
};

Constructed deform_and_certify(const core::TetMesh& mesh, const std::vector<core::Tri>& tris,
                               const std::vector<int>& labels, const construct::DeformOptions& o = {}) {
  Constructed c;
  c.def = construct::deform_to_polycube(mesh, tris, labels, o);
  core::PolycubeMap map;
  map.tets = c.def.mesh.cells;
  map.model = c.def.mesh.points;
  map.polycube = c.def.polycube;
  c.cert = construct::certify_polycube_map(map, c.def.boundary, c.def.labels);
  quality::DistortionOptions dopt;
  dopt.normalize_volume = true;
  c.dist = quality::map_distortion(c.def.mesh, c.def.polycube, dopt);
  const Verdict v = independent_check(map.tets, map.model, map.polycube, c.def.boundary, c.def.labels);
  EXPECT_EQ(v.bad_model, 0);
  EXPECT_EQ(v.bad_polycube, 0);
  EXPECT_EQ(v.off_plane, 0);
  EXPECT_EQ(v.unlabeled, 0);
  EXPECT_EQ(v.boundary_faces, static_cast<int>(c.def.boundary.size()));
  return c;
}

TEST(Deform, BoxIsCertifiedNearIdentity) {
  const auto tr = construct::tetrahedralize(cube_surface(6, 10.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  const Constructed c = deform_and_certify(tr.mesh, tris, labels);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_EQ(c.def.num_charts, 6);
  EXPECT_EQ(c.dist.invalid, 0);
  EXPECT_LT(c.dist.isometric.max, 1.05);
  EXPECT_LT(c.dist.isometric.average, 1.01);
}

//! A cube surface pushed onto a sphere, tetrahedralized, labeled by its normals, repaired.
struct LabeledSphere {
  core::TetMesh mesh;
  std::vector<core::Tri> tris;
  std::vector<int> labels;
};
LabeledSphere labeled_sphere() {
  core::TriMesh s = cube_surface(8, 2.0);
  for (Vec3& p : s.points) p = (p - Vec3(1, 1, 1)).normalized() * 10.0;
  LabeledSphere out;
  out.mesh = construct::tetrahedralize(s).mesh;
  normal_labels(out.mesh, out.tris, out.labels);
  core::TriMesh surf;
  surf.points = out.mesh.points;
  for (const auto& t : out.tris) surf.cells.push_back(t);
  if (!construct::check_labeling(surf, out.labels).valid()) {
    const auto rep = construct::repair_labeling(surf, out.labels);
    if (!rep.valid()) throw core::SolverError("labeling repair failed on the sphere fixture");
    out.labels = rep.labels;
  }
  return out;
}

TEST(Deform, SphereLikeShapeIsCertified) {
  const LabeledSphere sp = labeled_sphere();
  const Constructed c = deform_and_certify(sp.mesh, sp.tris, sp.labels);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_EQ(c.dist.invalid, 0);
  EXPECT_LT(c.dist.isometric.max, 5.0);
}

TEST(Deform, PlanarityFlowGivesACertifiedSphere) {
  // The same sphere-like shape with the planarity flow as the first polycube: the flow never
  // inverts a tet, and after the snap and the untangling the map is certified.
  const LabeledSphere sp = labeled_sphere();
  construct::DeformOptions o;
  o.first.method = mapping::FirstPolycubeMethod::PlanarityFlow;
  const Constructed c = deform_and_certify(sp.mesh, sp.tris, sp.labels, o);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  EXPECT_GT(c.def.flow_iterations, 0);
  EXPECT_LE(c.def.flow_residual, 0.05);
  EXPECT_EQ(c.dist.invalid, 0);
}

//! Number of boundary triangles of label l at corner vertex v, for every (corner, chart).
std::vector<int> corner_fans(const std::vector<core::Tri>& tris, const std::vector<int>& labels) {
  std::map<int, std::array<int, 6>> at;
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int v : tris[t]) {
      auto& c = at.try_emplace(v, std::array<int, 6>{}).first->second;
      ++c[labels[t]];
    }
  std::vector<int> fans;
  for (const auto& [v, c] : at) {
    const bool corner = (c[0] + c[1] > 0) && (c[2] + c[3] > 0) && (c[4] + c[5] > 0);
    if (!corner) continue;
    for (int k : c)
      if (k > 0) fans.push_back(k);
  }
  return fans;
}

TEST(Deform, CornerFansAreWidened) {
  // The cube's corners have a one- or two-triangle fan per chart; min_fan asks for 4.
  const auto tr = construct::tetrahedralize(cube_surface(3, 10.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  const std::vector<int> before = corner_fans(tris, labels);
  ASSERT_EQ(before.size(), 24u);  // 8 corners x 3 charts
  EXPECT_LT(*std::min_element(before.begin(), before.end()), 4);
  construct::DeformOptions o;
  o.min_fan = 4;
  const Constructed c = deform_and_certify(tr.mesh, tris, labels, o);
  EXPECT_TRUE(c.cert.certified()) << c.cert.reason();
  const std::vector<int> after = corner_fans(c.def.boundary, c.def.labels);
  ASSERT_EQ(after.size(), 24u);
  EXPECT_GE(*std::min_element(after.begin(), after.end()), 4);
  EXPECT_GT(c.def.split_fan_edges, 0);
}

TEST(Predeform, TurnsNormalsTowardsTheAxes) {
  // A sphere: its normals are as far from the axes as a closed surface gets on average.
  core::TriMesh s = cube_surface(8, 2.0);
  for (Vec3& p : s.points) p = (p - Vec3(1, 1, 1)).normalized() * 10.0;
  const auto tr = construct::tetrahedralize(s);
  const core::TetBoundary b = core::boundary(tr.mesh);
  std::vector<core::Tri> tris;
  for (const auto& t : b.surface.cells) tris.push_back({b.vertex_map[t[0]], b.vertex_map[t[1]], b.vertex_map[t[2]]});
  construct::PredeformOptions o;
  o.iterations = 30;
  const construct::PredeformResult r = construct::predeform(tr.mesh, tris, o);
  ASSERT_EQ(r.points.size(), tr.mesh.points.size());
  EXPECT_GT(r.iterations, 0);
  EXPECT_GT(r.misalignment_before, 0.05);
  EXPECT_LT(r.misalignment_after, 0.5 * r.misalignment_before);
  // Recompute the figure here: area-weighted 1 - max |n . axis| of the deformed surface.
  double sum = 0, area = 0;
  for (const auto& t : tris) {
    const Vec3 n = (r.points[t[1]] - r.points[t[0]]).cross(r.points[t[2]] - r.points[t[0]]);
    sum += n.norm() - n.cwiseAbs().maxCoeff();
    area += n.norm();
  }
  EXPECT_NEAR(sum / area, r.misalignment_after, 1e-12);
  // As rigid as possible: the sphere becomes a rounded cube of about its volume (measured:
  // 0.84 of it), it neither collapses nor inflates.
  auto volume = [&](const std::vector<Vec3>& P) {
    double v = 0;
    for (const auto& c : tr.mesh.cells) v += (P[c[1]] - P[c[0]]).dot((P[c[2]] - P[c[0]]).cross(P[c[3]] - P[c[0]])) / 6;
    return v;
  };
  EXPECT_GT(volume(r.points) / volume(tr.mesh.points), 0.7);
  EXPECT_LT(volume(r.points) / volume(tr.mesh.points), 1.1);
  // Deterministic.
  const construct::PredeformResult again = construct::predeform(tr.mesh, tris, o);
  EXPECT_EQ(again.points, r.points);
}

TEST(Construct, RotatedBoxIsAlignedAndKeepsItsPositions) {
  // A box given at an angle to the axes: the construction rotates it back before the labeling
  // (one chart per face), and the written model keeps the input's coordinates bit for bit.
  core::TriMesh s = cube_surface(4, 10.0);
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (Vec3& p : s.points) p = Q * p;
  const construct::ConstructResult r = construct::construct_polycube(s);
  EXPECT_FALSE(r.axis_rotation.rotation.isIdentity());
  EXPECT_LT(r.axis_rotation.energy_after, r.axis_rotation.energy_before);
  EXPECT_EQ(r.charts, 6);
  EXPECT_EQ(r.corners, 8);
  const Verdict v = independent_check(r.map.tets, r.map.model, r.map.polycube, r.boundary, r.labels);
  EXPECT_TRUE(test::certified(v)) << "bad model " << v.bad_model << ", bad polycube " << v.bad_polycube
                                  << ", off plane " << v.off_plane << ", wrong facing " << v.wrong_facing;
  std::set<std::array<double, 3>> model;
  for (const Vec3& p : r.map.model) model.insert({p.x(), p.y(), p.z()});
  for (const Vec3& p : s.points) EXPECT_EQ(model.count({p.x(), p.y(), p.z()}), 1u);
}

TEST(Construct, PlanListsTheCompactnessScheduleThenThePredeformedRetry) {
  construct::ConstructOptions o;
  o.labeling.compactness = 2.0;
  const std::vector<construct::Attempt> plan = construct::plan_attempts(o);
  ASSERT_EQ(plan.size(), 6u);  // compactness 1, 2, 0.5 times the user's; then the same pre-deformed
  const double expected[] = {2.0, 4.0, 1.0};
  for (std::size_t i = 0; i < plan.size(); ++i) {
    EXPECT_EQ(plan[i].compactness, expected[i % 3]) << i;
    EXPECT_EQ(plan[i].retry, i >= 3) << i;
    EXPECT_EQ(plan[i].predeform_iterations, i >= 3 ? o.predeform_retry : 0) << i;
    EXPECT_EQ(plan[i].unfold_moves, i >= 3 ? o.predeform_retry_unfold_moves : 0) << i;
  }
  EXPECT_EQ(plan[0].name(), "compactness 2");
  EXPECT_EQ(plan[4].name(), "pre-deformed, compactness 4");
  // A pre-deformation asked for by the user: no retry pass; the attempts start from it.
  o.predeform.iterations = 5;
  const std::vector<construct::Attempt> asked = construct::plan_attempts(o);
  ASSERT_EQ(asked.size(), 3u);
  for (const auto& a : asked) EXPECT_EQ(a.predeform_iterations, 5);
  o.predeform.iterations = 0;
  o.predeform_retry = 0;
  o.retry_compactness_factors.clear();
  EXPECT_EQ(construct::plan_attempts(o).size(), 1u);
}

TEST(Construct, ReportDescribesTheKeptAttempt) {
  // A box certifies in the first attempt: the report names it and its own repair figures.
  const construct::ConstructResult r = construct::construct_polycube(cube_surface(3, 10.0));
  EXPECT_EQ(r.attempts, 1);
  EXPECT_EQ(r.attempt.name(), construct::plan_attempts({})[0].name());
  EXPECT_FALSE(r.attempt.retry);
  EXPECT_EQ(r.predeform.iterations, 0);  // the kept attempt had no pre-deformation
  EXPECT_EQ(r.repair_moves, 0);          // the normals of a box give a valid labeling at once
  EXPECT_TRUE(r.certificate.certified());
}

TEST(Certify, RejectsInvertedAndOffPlaneMaps) {
  const auto tr = construct::tetrahedralize(cube_surface(3, 1.0));
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  normal_labels(tr.mesh, tris, labels);
  core::PolycubeMap map;
  map.tets = tr.mesh.cells;
  map.model = tr.mesh.points;
  map.polycube = tr.mesh.points;
  EXPECT_TRUE(construct::certify_polycube_map(map, tris, labels).certified());
  // A boundary vertex moved off its plane by one ulp.
  core::PolycubeMap off = map;
  const int v = tris.front()[0];
  const int a = labels.front() / 2;
  off.polycube[v][a] = std::nextafter(off.polycube[v][a], 2.0);
  const auto c1 = construct::certify_polycube_map(off, tris, labels);
  EXPECT_FALSE(c1.certified());
  EXPECT_GT(c1.off_plane, 0);
  EXPECT_THROW(construct::require_certified(c1), core::GeometryError);
  // An interior vertex pushed outside: tets inverted.
  core::PolycubeMap inv = map;
  const core::TetBoundary b = core::boundary(tr.mesh);
  std::vector<char> on_b(map.model.size(), 0);
  for (int w : b.vertex_map) on_b[w] = 1;
  int interior = -1;
  for (int i = 0; i < static_cast<int>(on_b.size()) && interior < 0; ++i)
    if (!on_b[i]) interior = i;
  ASSERT_GE(interior, 0);
  inv.polycube[interior] = Vec3(5, 5, 5);
  const auto c2 = construct::certify_polycube_map(inv, tris, labels);
  EXPECT_FALSE(c2.certified());
  EXPECT_GT(c2.inverted_polycube, 0);
  // Wrong labels (a +X face labeled -X) face the wrong way.
  std::vector<int> bad = labels;
  for (int& l : bad)
    if (l == 0) l = 1;
  EXPECT_GT(construct::certify_polycube_map(map, tris, bad).wrong_facing, 0);
}

}  // namespace
}  // namespace polycube
