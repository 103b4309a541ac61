//! Tests of the planarity flow (mapping/planarity_flow.h) and the reopening of flipped corner
//! fans (mapping/corner_fans.h).
#include "mapping/corner_fans.h"
#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "mapping/planarity_flow.h"
#include "construct/tetrahedralize.h"
#include "construct/turning_points.h"
#include "support/shapes.h"
#include "core/errors.h"
#include "support/fixtures.h"
#include "core/polycube_map.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace polycube {
namespace {

using core::Vec3;

//! Boundary triangles (volume indices, outward) of a tet mesh and labels from their normals.
std::pair<std::vector<core::Tri>, std::vector<int>> labeled_boundary(const core::TetMesh& mesh) {
  const core::TetBoundary b = core::boundary(mesh);
  std::pair<std::vector<core::Tri>, std::vector<int>> out;
  for (const auto& s : b.surface.cells) {
    const auto& p = b.surface.points;
    out.first.push_back({b.vertex_map[s[0]], b.vertex_map[s[1]], b.vertex_map[s[2]]});
    out.second.push_back(core::dominant_axis_label((p[s[1]] - p[s[0]]).cross(p[s[2]] - p[s[0]])));
  }
  return out;
}

TEST(PlanarityFlow, NoisyBoxFlowsOntoPlanesWithoutFolding) {
  // A box tet mesh whose boundary vertices are pushed off their faces by noise of a fifth of an
  // edge: the flow, started from the noisy positions as the reference, must bring every face's
  // vertices back onto one plane per face without inverting a tet.
  const auto tr = construct::tetrahedralize(test::make_box(10, 6, 4, 5));
  core::TetMesh mesh = tr.mesh;
  const auto [tris, labels] = labeled_boundary(mesh);
  const int nv = mesh.num_points();
  // One chart group per label (a box's six faces): group of (v, axis).
  std::vector<int> group(3 * static_cast<std::size_t>(nv), -1);
  for (std::size_t f = 0; f < tris.size(); ++f)
    for (int v : tris[f]) group[3 * static_cast<std::size_t>(v) + labels[f] / 2] = labels[f];
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.4, 0.4);
  std::vector<char> on_boundary(static_cast<std::size_t>(nv), 0);
  for (const auto& t : tris)
    for (int v : t) on_boundary[v] = 1;
  for (int v = 0; v < nv; ++v)
    if (on_boundary[v])
      for (int d = 0; d < 3; ++d)
        if (group[3 * static_cast<std::size_t>(v) + d] >= 0) mesh.points[v][d] += u(rng);
  for (const auto& c : mesh.cells)
    ASSERT_GT(test::tet_det(mesh.points, c), 0.0) << "fixture: noise inverted a tet";
  mapping::PlanarityFlowOptions o;
  o.iterations = 60;
  const auto r = mapping::planarity_flow(mesh, mesh.points, group, 6, tris, labels, 0.5, o);
  ASSERT_EQ(r.points.size(), mesh.points.size());
  EXPECT_EQ(r.inverted, 0);
  EXPECT_LE(r.residual, o.tolerance);
  for (const auto& c : mesh.cells) EXPECT_GT(test::tet_det(r.points, c), 0.0);
  // Independently: each face's coordinate spread, against the longest edge of the mesh (the
  // residual is in local mean edge lengths).
  double longest = 0;
  for (const auto& c : mesh.cells)
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) longest = std::max(longest, (mesh.points[c[i]] - mesh.points[c[j]]).norm());
  for (int g = 0; g < 6; ++g) {
    double lo = 1e300, hi = -1e300;
    for (int v = 0; v < nv; ++v)
      if (group[3 * static_cast<std::size_t>(v) + g / 2] == g) {
        lo = std::min(lo, r.points[v][g / 2]);
        hi = std::max(hi, r.points[v][g / 2]);
      }
    EXPECT_LE(hi - lo, 2.0 * o.tolerance * longest) << "face " << g;
    EXPECT_LE(lo, hi) << "face " << g << " has no vertex";
  }
  // Every boundary triangle faces its label (the ghost tets keep the boundary unfolded).
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto& t = tris[f];
    const Vec3 n = (r.points[t[1]] - r.points[t[0]]).cross(r.points[t[2]] - r.points[t[0]]);
    EXPECT_GT(n.dot(core::label_direction(labels[f])), 0.0) << "triangle " << f;
  }
  // Deterministic.
  const auto again = mapping::planarity_flow(mesh, mesh.points, group, 6, tris, labels, 0.5, o);
  EXPECT_EQ(again.points, r.points);
}

TEST(PlanarityFlow, RejectsMismatchedSizes) {
  const auto tr = construct::tetrahedralize(test::make_box(1, 1, 1, 1));
  std::vector<int> group(3, -1);
  EXPECT_THROW(mapping::planarity_flow(tr.mesh, tr.mesh.points, group, 0, {}, {}, 0.0), core::InputError);
}

//! A box surface, labels from its normals.
TEST(CornerFans, FlippedConcaveFanIsPlacedOnItsLongSweep) {
  // Corner C at the origin; a +Z chart fan of 4 triangles from spoke s0 on +x to s4 on -y, which
  // must sweep 270 degrees counter-clockwise (a concave corner) but was left on the short,
  // clockwise 90 degrees: every triangle faces -Z. Two more triangles (+X, +Y) make C a corner.
  std::vector<Vec3> P{{0, 0, 0}, {1, 0, 0}};
  const double pi = std::acos(-1.0);
  for (int i = 1; i <= 3; ++i) P.emplace_back(std::cos(-i * pi / 8), std::sin(-i * pi / 8), 0.0);
  P.emplace_back(0, -1, 0);                       // s4 = vertex 5
  P.emplace_back(0, 0, -1);                       // 6, below C (for the side charts)
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  for (int i = 1; i <= 4; ++i) {
    tris.push_back({0, i, i + 1});
    labels.push_back(4);
  }
  tris.push_back({0, 6, 1});
  labels.push_back(0);
  tris.push_back({0, 5, 6});
  labels.push_back(2);
  auto faces = [&](const std::vector<Vec3>& Q, int f) {
    const auto& t = tris[f];
    return (Q[t[1]] - Q[t[0]]).cross(Q[t[2]] - Q[t[0]]).z() > 0;
  };
  for (int f = 0; f < 4; ++f) ASSERT_FALSE(faces(P, f)) << "fixture: the fan must start flipped";
  std::vector<Vec3> Q = P;
  const auto r = mapping::reopen_flipped_fans(tris, labels, Q);
  EXPECT_EQ(r.fans, 1);
  EXPECT_EQ(r.vertices, (std::vector<int>{2, 3, 4}));
  for (int f = 0; f < 4; ++f) EXPECT_TRUE(faces(Q, f)) << "fan triangle " << f;
  for (int v : {0, 1, 5, 6}) EXPECT_EQ(Q[v], P[v]) << "vertex " << v << " must stay";
  for (int i = 1; i <= 3; ++i) {
    EXPECT_EQ(Q[i + 1].z(), 0.0);                       // stays in the chart plane
    EXPECT_NEAR(Q[i + 1].head<2>().norm(), 1.0, 1e-12);  // at its distance from the corner
    const double angle = std::atan2(Q[i + 1].y(), Q[i + 1].x());
    const double expected = i * 3 * pi / 8;  // 270 degrees in 4 equal steps
    EXPECT_NEAR(std::remainder(angle - expected, 2 * pi), 0.0, 1e-12) << "spoke " << i;
  }
  // A fan that faces its label is left alone.
  std::vector<Vec3> again = Q;
  EXPECT_EQ(mapping::reopen_flipped_fans(tris, labels, again).fans, 0);
  EXPECT_EQ(again, Q);
}

}  // namespace
}  // namespace polycube
