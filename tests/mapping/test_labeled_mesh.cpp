//! Tests of the labeled tet mesh (mapping/labeled_mesh.h), the ghost tets (mapping/ghost_tets.h),
//! the charts (core/charts.h) and the global untangling (mapping/untangle_map.h).
#include "construct/tetrahedralize.h"
#include "core/charts.h"
#include "core/errors.h"
#include "core/polycube_map.h"
#include "core/topology.h"
#include "mapping/first_polycube.h"
#include "mapping/ghost_tets.h"
#include "mapping/labeled_mesh.h"
#include "mapping/untangle_map.h"
#include "support/shapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace polycube {
namespace {

using core::Vec3;

double volume(const core::TetMesh& m) {
  double v = 0;
  for (const auto& c : m.cells) {
    const auto& p = m.points;
    v += (p[c[1]] - p[c[0]]).dot((p[c[2]] - p[c[0]]).cross(p[c[3]] - p[c[0]])) / 6.0;
  }
  return v;
}

//! A 4 x 3 x 2 box tet mesh with its boundary labeled by the normals.
mapping::LabeledTetMesh labeled_box() {
  const auto tr = construct::tetrahedralize(test::make_box(4, 3, 2, 2));
  const core::TetBoundary b = core::boundary(tr.mesh);
  std::vector<core::Tri> tris = core::boundary_triangles(b);
  std::vector<int> labels;
  for (const auto& t : tris) {
    const auto& p = tr.mesh.points;
    labels.push_back(core::dominant_axis_label((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]])));
  }
  // Given in reverse order, with one triangle's orientation flipped: the labels must follow.
  std::reverse(tris.begin(), tris.end());
  std::reverse(labels.begin(), labels.end());
  std::swap(tris[0][1], tris[0][2]);
  return mapping::label_tet_mesh(tr.mesh, tris, labels);
}

TEST(Charts, BoxHasSixChartsNumberedByTheirFirstTriangle) {
  const core::TriMesh box = test::make_box(1, 1, 1, 2);
  std::vector<int> labels;
  for (const auto& t : box.cells) {
    const auto& p = box.points;
    labels.push_back(core::dominant_axis_label((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]])));
  }
  const core::TriangleCharts charts = core::triangle_charts(box.cells, labels);
  ASSERT_EQ(charts.count, 6);
  int next = 0;
  for (std::size_t t = 0; t < box.cells.size(); ++t) {
    const int c = charts.triangle_chart[t];
    ASSERT_LE(c, next) << "chart numbers must appear in the order of their first triangle";
    if (c == next) ++next;
    for (std::size_t u = 0; u < t; ++u)
      EXPECT_EQ(charts.triangle_chart[u] == c, labels[u] == labels[t]) << "triangles " << u << ", " << t;
  }
}

TEST(Charts, OneLabelSplitByAnotherGivesTwoCharts) {
  // A strip of four triangles labeled 0, 0, 2, 0 along shared edges: charts {0, 1}, {2}, {3}.
  const std::vector<core::Tri> tris{{0, 1, 2}, {1, 3, 2}, {2, 3, 4}, {3, 5, 4}};
  const core::TriangleCharts charts = core::triangle_charts(tris, {0, 0, 2, 0});
  EXPECT_EQ(charts.count, 3);
  EXPECT_EQ(charts.triangle_chart, (std::vector<int>{0, 0, 1, 2}));
}

TEST(LabeledMesh, LabelsFollowTheirTrianglesAndChartsAreTheBoxFaces) {
  const mapping::LabeledTetMesh lm = labeled_box();
  const auto& p = lm.mesh.points;
  ASSERT_EQ(lm.boundary, core::boundary_triangles(core::boundary(lm.mesh)));
  for (std::size_t f = 0; f < lm.boundary.size(); ++f) {
    const auto& t = lm.boundary[f];
    EXPECT_EQ(lm.labels[f], core::dominant_axis_label((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]))) << f;
    const core::Tet& c = lm.mesh.cells[lm.boundary_cell[f]];
    for (int v : t) EXPECT_NE(std::find(c.begin(), c.end(), v), c.end()) << "owner of triangle " << f;
  }
  EXPECT_EQ(lm.charts.num_charts, 6);
  EXPECT_EQ(lm.charts.num_groups, 6);  // opposite faces never touch
  // Every vertex of a face carries that face's group on the face's axis.
  for (std::size_t f = 0; f < lm.boundary.size(); ++f)
    for (int v : lm.boundary[f])
      EXPECT_GE(lm.charts.vertex_group[3 * static_cast<std::size_t>(v) + core::label_axis(lm.labels[f])], 0);
  // A box corner is on three groups, an interior vertex on none.
  int corners = 0, free_vertices = 0;
  for (int v = 0; v < lm.mesh.num_points(); ++v) {
    int n = 0;
    for (int a = 0; a < 3; ++a) n += lm.charts.vertex_group[3 * static_cast<std::size_t>(v) + a] >= 0;
    corners += n == 3;
    free_vertices += n == 0;
  }
  EXPECT_EQ(corners, 8);
  EXPECT_GT(free_vertices, 0);
}

TEST(LabeledMesh, AVertexThatSeesOnlyOneChartPlaneGetsAFaceSplitTowardsTheInside) {
  // A bipyramid: a cap tet (a, b, c, e) over a tet (a, b, c, d), the cap split at its centroid
  // v as the refinement after TetGen does. The cap's three outer faces form one +Z chart, so a,
  // b, c and e share its plane and v, whose neighbours are those four, sees nothing else: every
  // position of v leaves its tets flat. Splitting the inner face (a, b, c) gives v a neighbour
  // that also sees d, off the plane.
  core::TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0.3, 0.3, 0.3), Vec3(0.3, 0.3, -1)};
  const int a = 0, b = 1, c = 2, e = 3, d = 4, v = 5;
  m.points.push_back((m.points[a] + m.points[b] + m.points[c] + m.points[e]) / 4.0);
  const auto positive = [&](core::Tet t) {
    const auto& p = m.points;
    if ((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])) < 0) std::swap(t[0], t[1]);
    return t;
  };
  for (const core::Tet& t : {core::Tet{v, b, c, e}, core::Tet{a, v, c, e}, core::Tet{a, b, v, e}, core::Tet{a, b, c, v},
                             core::Tet{a, b, c, d}})
    m.cells.push_back(positive(t));
  const std::vector<core::Tri> tris = core::boundary_triangles(core::boundary(m));
  std::vector<int> labels;
  for (const auto& t : tris) {
    const bool cap = std::find(t.begin(), t.end(), e) != t.end();
    const auto& p = m.points;
    labels.push_back(core::dominant_axis_label(cap ? Vec3(0, 0, 1) : Vec3((p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]))));
  }
  mapping::LabeledTetMesh lm = mapping::label_tet_mesh(m, tris, labels);
  const std::vector<mapping::LockedVertex> locked = mapping::locked_interior_vertices(lm);
  ASSERT_EQ(locked.size(), 1u);
  EXPECT_EQ(locked[0].vertex, v);
  EXPECT_EQ(locked[0].face, (std::array<int, 3>{a, b, c}));
  std::vector<char> touched(lm.mesh.cells.size(), 0);
  const double before = volume(lm.mesh);
  ASSERT_TRUE(mapping::split_interior_face(lm, locked[0].face, touched));
  EXPECT_EQ(lm.mesh.num_cells(), 9);  // the two tets on the face became three each
  EXPECT_NEAR(volume(lm.mesh), before, 1e-12);
  for (const auto& t : lm.mesh.cells) {
    const auto& p = lm.mesh.points;
    EXPECT_GT((p[t[1]] - p[t[0]]).dot((p[t[2]] - p[t[0]]).cross(p[t[3]] - p[t[0]])), 0.0);
  }
  mapping::refresh_boundary(lm);
  mapping::update_charts(lm);
  EXPECT_TRUE(mapping::locked_interior_vertices(lm).empty());
  EXPECT_FALSE(mapping::split_interior_face(lm, {a, b, e}, touched));  // a boundary face has one tet
}

TEST(LabeledMesh, MismatchedBoundaryIsRefused) {
  mapping::LabeledTetMesh lm = labeled_box();
  std::vector<core::Tri> tris = lm.boundary;
  std::vector<int> labels = lm.labels;
  EXPECT_THROW(mapping::label_tet_mesh(lm.mesh, {tris.begin() + 1, tris.end()}, {labels.begin() + 1, labels.end()}),
               core::InputError);
  labels[3] = 6;
  EXPECT_THROW(mapping::label_tet_mesh(lm.mesh, tris, labels), core::InputError);
}

TEST(LabeledMesh, SplittingABoundaryEdgeKeepsTheMeshConformingAndTheLabels) {
  mapping::LabeledTetMesh lm = labeled_box();
  const double v0 = volume(lm.mesh);
  const int nv = lm.mesh.num_points();
  const std::size_t nb = lm.boundary.size();
  const core::Tri t = lm.boundary[0];
  const int label = lm.labels[0];
  std::vector<Vec3> other = lm.mesh.points;
  const int split = mapping::split_edges(lm, {{std::min(t[0], t[1]), std::max(t[0], t[1])}}, &other);
  mapping::refresh_boundary(lm);
  mapping::update_charts(lm);
  EXPECT_EQ(split, 1);
  EXPECT_EQ(lm.mesh.num_points(), nv + 1);
  EXPECT_EQ(other[nv], 0.5 * (other[t[0]] + other[t[1]]));
  EXPECT_EQ(lm.boundary.size(), nb + 2);  // both boundary triangles of the edge split in two
  EXPECT_NEAR(volume(lm.mesh), v0, 1e-12 * v0);
  for (const auto& c : lm.mesh.cells) EXPECT_TRUE(core::positive_tet(lm.mesh.points, c));
  EXPECT_EQ(lm.boundary, core::boundary_triangles(core::boundary(lm.mesh)));  // conforming: no hanging node
  int on_new = 0;
  for (std::size_t f = 0; f < lm.boundary.size(); ++f)
    if (std::find(lm.boundary[f].begin(), lm.boundary[f].end(), nv) != lm.boundary[f].end()) {
      ++on_new;
      EXPECT_EQ(lm.labels[f], label);
    }
  EXPECT_EQ(on_new, 4);
  EXPECT_EQ(lm.charts.num_charts, 6);
}

TEST(GhostTets, PositiveExactlyWhenTheTriangleFacesItsLabel) {
  const std::vector<Vec3> P{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  const core::Tri up{0, 1, 2}, down{0, 2, 1};
  for (mapping::GhostBase base : {mapping::GhostBase::Centroid, mapping::GhostBase::FirstVertex})
    for (int label : {4, 5})  // +Z, -Z
      for (const core::Tri& t : {up, down}) {
        std::vector<Vec3> Q = P;
        Q.push_back(mapping::ghost_apex(P, t, label, 0.25, base));
        const mapping::GhostTets g = mapping::ghost_tets(P, {t}, {label}, 0.25, 3, base);
        ASSERT_EQ(g.tets.size(), 1u);
        EXPECT_EQ(g.tets[0][3], 3);
        EXPECT_EQ(Q[3].z(), 1.0 + (label == 4 ? 0.25 : -0.25));
        EXPECT_EQ(core::positive_tet(Q, g.tets[0]), core::faces_label(P, t, label)) << "label " << label;
      }
}

TEST(GhostTets, ReferenceApexIsAtHeightHAlongTheNormalOrTheLabel) {
  const std::vector<Vec3> P{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  const auto normal = mapping::ghost_tets(P, {{0, 1, 2}}, {5}, 0.5, 3);
  EXPECT_TRUE(normal.reference[0].isApprox(Vec3(2.0 / 3.0, 2.0 / 3.0, 0.5)));
  const auto along_label =
      mapping::ghost_tets(P, {{0, 1, 2}}, {5}, 0.5, 3, mapping::GhostBase::FirstVertex, mapping::GhostDirection::Label);
  EXPECT_EQ(along_label.reference[0], Vec3(0, 0, -0.5));
  EXPECT_DOUBLE_EQ(mapping::ghost_height(P, {{0, 1, 2}}, 0.5), 0.5 * (2 + 2 + 2 * std::sqrt(2.0)) / 3.0);
  EXPECT_EQ(mapping::ghost_height(P, {{0, 1, 2}}, 0.0), 0.0);
}

TEST(UntangleMap, BoxPolycubeIsUntangledWithEveryChartExactlyPlanar) {
  const mapping::LabeledTetMesh lm = labeled_box();
  const mapping::FirstPolycube first = mapping::first_polycube(lm, lm.mesh.points, 0.0, false);
  std::vector<Vec3> P = first.points;
  mapping::UntangleMapOptions o;
  o.ghost_height = mapping::ghost_height(lm.mesh.points, lm.boundary, 0.5);
  o.untangle.min_det_target = 1e-6;
  const solve::UntangleResult r = mapping::untangle_globally(lm, P, o);
  EXPECT_TRUE(r.untangled);
  EXPECT_EQ(mapping::failures(lm, P), 0);
  // Every chart group's coordinate is one value, bit for bit.
  std::vector<std::set<double>> values(static_cast<std::size_t>(lm.charts.num_groups));
  for (int v = 0; v < lm.mesh.num_points(); ++v)
    for (int a = 0; a < 3; ++a) {
      const int g = lm.charts.vertex_group[3 * static_cast<std::size_t>(v) + a];
      if (g >= 0) values[g].insert(P[v][a]);
    }
  for (const auto& s : values) EXPECT_EQ(s.size(), 1u);
}

}  // namespace
}  // namespace polycube
