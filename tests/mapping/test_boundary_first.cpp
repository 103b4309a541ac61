//! Tests of the boundary-first placement of a polycube map (mapping/boundary_first.h).
#include "mapping/boundary_first.h"
#include "support/fixtures.h"
#include "core/polycube_map.h"
#include "core/topology.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace polycube {
namespace {

using core::Vec3;

//! An 8×8×8 grid of unit cubes with the octant x, y, z ≥ 4 removed (a concave corner at
//! (4, 4, 4), three concave edges), 6 tets per cube, its boundary labeled by the normals and one
//! chart group per (axis, plane).
struct NotchedCube {
  core::TetMesh mesh;
  std::vector<core::Tri> tris;
  std::vector<int> labels;
  std::vector<int> group;
  std::vector<char> on_boundary;

  [[nodiscard]] int mask(int v) const {
    int m = 0;
    for (int d = 0; d < 3; ++d) m |= group[3 * static_cast<std::size_t>(v) + d] >= 0 ? 1 << d : 0;
    return m;
  }
};

NotchedCube notched_cube() {
  core::HexMesh h = test::hex_grid(8, 8, 8);
  std::vector<core::Hex> kept;
  for (const auto& c : h.cells) {
    const Vec3& p = h.points[c[0]];
    if (!(p.x() >= 4 && p.y() >= 4 && p.z() >= 4)) kept.push_back(c);
  }
  h.cells = kept;
  NotchedCube s;
  const core::TetMesh all = test::tetrahedralize(h);
  std::vector<int> index(all.points.size(), -1);
  for (const auto& c : all.cells)
    for (int v : c)
      if (index[v] < 0) {
        index[v] = s.mesh.num_points();
        s.mesh.points.push_back(all.points[v]);
      }
  for (const auto& c : all.cells) s.mesh.cells.push_back({index[c[0]], index[c[1]], index[c[2]], index[c[3]]});
  const core::TetBoundary b = core::boundary(s.mesh);
  const auto nv = static_cast<std::size_t>(s.mesh.num_points());
  s.group.assign(3 * nv, -1);
  s.on_boundary.assign(nv, 0);
  for (const auto& t : b.surface.cells) {
    const core::Tri tri{b.vertex_map[t[0]], b.vertex_map[t[1]], b.vertex_map[t[2]]};
    const auto& p = s.mesh.points;
    const int label = core::dominant_axis_label((p[tri[1]] - p[tri[0]]).cross(p[tri[2]] - p[tri[0]]));
    s.tris.push_back(tri);
    s.labels.push_back(label);
    const int a = label / 2;
    for (int v : tri) {
      s.group[3 * static_cast<std::size_t>(v) + a] = 100 * a + static_cast<int>(std::lround(p[v][a]));
      s.on_boundary[v] = 1;
    }
  }
  return s;
}

TEST(BoundaryFirst, ScrambledPolycubeGetsStraightEdgesAndNoInvertedTet) {
  const NotchedCube s = notched_cube();
  const int nv = s.mesh.num_points();
  // The polycube: the model stretched along x; then every polycube-edge vertex pushed back and
  // forth along its edge (chains with turning points), chart vertices moved in their plane and
  // interior vertices moved freely, by up to 0.45–0.6 edge lengths. Corners and chart
  // coordinates stay exact.
  std::vector<Vec3> exact = s.mesh.points;
  for (Vec3& p : exact) p.x() *= 1.3;
  std::vector<Vec3> P = exact;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int corners = 0;
  for (int v = 0; v < nv; ++v) {
    const int m = s.on_boundary[v] ? s.mask(v) : 0;
    if (m == 7) ++corners;
    for (int d = 0; d < 3; ++d)
      if (!(m & (1 << d))) P[v][d] += (s.on_boundary[v] && m != (m & -m) ? 0.45 : 0.6) * u(rng);
  }
  EXPECT_EQ(corners, 14);  // 7 box corners and 7 at the notch
  int inverted = 0;
  for (const auto& c : s.mesh.cells) inverted += test::tet_det(P, c) <= 0;
  ASSERT_GT(inverted, 100) << "fixture: the scrambled polycube should be badly tangled";

  solve::UntangleOptions o;
  o.min_det_target = 1e-6;
  const auto r = mapping::place_boundary_first(s.mesh.points, s.mesh.cells, s.tris, s.labels, s.group, P, o, 0.5, mapping::kFastPlacementSigma);
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_TRUE(r.reason.empty());
  EXPECT_EQ(r.tets_inverted, 0);
  EXPECT_EQ(r.charts_inverted, 0);
  // Independently: every tet positive, every triangle facing its label.
  for (const auto& c : s.mesh.cells) EXPECT_GT(test::tet_det(P, c), 0.0);
  for (std::size_t f = 0; f < s.tris.size(); ++f) EXPECT_TRUE(core::faces_label(P, s.tris[f], s.labels[f]));
  // Chart coordinates untouched bit for bit; edge vertices back on their uniform positions (the
  // model's arc-length fractions along straight, uniformly subdivided edges).
  for (int v = 0; v < nv; ++v) {
    if (!s.on_boundary[v]) continue;
    const int m = s.mask(v);
    for (int d = 0; d < 3; ++d) {
      if (m & (1 << d)) {
        EXPECT_EQ(P[v][d], exact[v][d]);
      }
      if (m != (m & -m)) {
        EXPECT_NEAR(P[v][d], exact[v][d], 1e-12) << "edge vertex " << v;
      }
    }
  }
}

TEST(BoundaryFirst, MirroredPolycubeHasItsChartPlanesPutBackInTheModelsOrder) {
  // The polycube mirrored in x: every polycube edge along x runs the other way than in the
  // model, so every chart polygon with such an edge winds the wrong way round. Step 0 moves the
  // x planes back into the model's order; the placement is then valid.
  const NotchedCube s = notched_cube();
  std::vector<Vec3> P = s.mesh.points;
  for (Vec3& p : P) p.x() = -p.x();
  solve::UntangleOptions o;
  o.min_det_target = 1e-6;
  const auto r = mapping::place_boundary_first(s.mesh.points, s.mesh.cells, s.tris, s.labels, s.group, P, o, 0.5, mapping::kFastPlacementSigma);
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_GT(r.reversed_chains, 0);
  EXPECT_LT(r.reversed_chains, r.chains);  // the edges along y and z kept their direction
  for (const auto& c : s.mesh.cells) EXPECT_GT(test::tet_det(P, c), 0.0);
  for (std::size_t f = 0; f < s.tris.size(); ++f) EXPECT_TRUE(core::faces_label(P, s.tris[f], s.labels[f]));
  // The x planes (one per group) in the model's order again, each still exact on its chart.
  std::map<int, std::pair<double, double>> plane;  // group -> (model x, polycube x)
  for (int v = 0; v < s.mesh.num_points(); ++v) {
    const int g = s.group[3 * static_cast<std::size_t>(v)];
    if (g < 0) continue;
    const auto [it, fresh] = plane.try_emplace(g, s.mesh.points[v].x(), P[v].x());
    EXPECT_EQ(it->second.second, P[v].x()) << "vertex " << v << " left its chart's plane";
  }
  ASSERT_GE(plane.size(), 3u);
  for (const auto& [g1, a] : plane)
    for (const auto& [g2, b] : plane)
      if (a.first < b.first) {
        EXPECT_LT(a.second, b.second) << "planes " << g1 << " and " << g2;
      }
}

TEST(BoundaryFirst, SqueezedPolycubeEdgesAreLengthenedToAQuarterOfTheModels) {
  // The polycube squeezed to 2 % along x: no edge is reversed, but every edge along x is a
  // sliver of its model length, and the tets between the close x planes would be nearly flat.
  // Step 0 moves the x planes apart until each such edge has a quarter of its model length.
  const NotchedCube s = notched_cube();
  std::vector<Vec3> P = s.mesh.points;
  for (Vec3& p : P) p.x() *= 0.02;
  solve::UntangleOptions o;
  o.min_det_target = 1e-6;
  const auto r = mapping::place_boundary_first(s.mesh.points, s.mesh.cells, s.tris, s.labels, s.group, P, o, 0.5, mapping::kFastPlacementSigma);
  ASSERT_TRUE(r.valid) << r.reason;
  EXPECT_EQ(r.reversed_chains, 0);
  for (const auto& c : s.mesh.cells) EXPECT_GT(test::tet_det(P, c), 0.0);
  std::map<double, double> plane;  // model x -> polycube x, for the x chart planes
  for (int v = 0; v < s.mesh.num_points(); ++v)
    if (s.group[3 * static_cast<std::size_t>(v)] >= 0) plane[s.mesh.points[v].x()] = P[v].x();
  ASSERT_EQ(plane.size(), 3u);  // x = 0, the notch's floor at 4, and 8
  for (auto a = plane.begin(), b = std::next(a); b != plane.end(); ++a, ++b)
    EXPECT_GE(b->second - a->second, 0.25 * (b->first - a->first) * (1 - 1e-9))
        << "planes at model x " << a->first << " and " << b->first;
}

TEST(BoundaryFirst, OppositeChartsSharingAnEdgeAreRefusedAndLeftAsTheyWere) {
  // One triangle of a +X chart labelled -X: no polycube has such a boundary, so the placement
  // must fail with the reason and leave P alone.
  NotchedCube s = notched_cube();
  std::size_t f = 0;
  while (s.labels[f] != 0) ++f;
  s.labels[f] = 1;
  std::vector<Vec3> P = s.mesh.points;
  for (Vec3& p : P) p.x() *= 1.3;
  const std::vector<Vec3> before = P;
  const auto r = mapping::place_boundary_first(s.mesh.points, s.mesh.cells, s.tris, s.labels, s.group, P, {}, 0.5, mapping::kFastPlacementSigma);
  EXPECT_FALSE(r.valid);
  EXPECT_NE(r.reason.find("share an edge"), std::string::npos) << r.reason;
  EXPECT_EQ(P, before);
}

}  // namespace
}  // namespace polycube
