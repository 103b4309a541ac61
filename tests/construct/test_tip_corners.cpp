//! Tests of the sharp tips made polycube corners (construct/tip_corners.h) and of the labels the
//! labeling repair holds (RepairOptions::held).
#include "construct/coarse_surface.h"
#include "construct/construct.h"
#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/polycube_estimate.h"
#include "construct/tetrahedralize.h"
#include "construct/tip_corners.h"
#include "core/polycube_map.h"
#include "core/topology.h"
#include "support/shapes.h"

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

namespace polycube {
namespace {

using core::Vec3;

//! The regular tetrahedron whose edges are diagonals of the faces of a cube: each of its faces
//! ties three axes.
core::TriMesh cube_diagonal_tetrahedron() {
  core::TriMesh m;
  m.points = {{0, 0, 0}, {10, 10, 0}, {10, 0, 10}, {0, 10, 10}};
  m.cells = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return m;
}

Vec3 unit_normal(const core::TriMesh& s, int t) {
  const auto& c = s.cells[t];
  return (s.points[c[1]] - s.points[c[0]]).cross(s.points[c[2]] - s.points[c[0]]).normalized();
}

//! A convex corner's three charts, counter-clockwise seen from outside, have directions of
//! positive determinant (+X, +Y, +Z does; +X, +Z, +Y would be a corner turned inside out).
double corner_determinant(int a, int b, int c) {
  Eigen::Matrix3d m;
  m << core::label_direction(a), core::label_direction(b), core::label_direction(c);
  return m.determinant();
}

TEST(TipCorners, ACubesCornersAreTipsLabelledByTheirOwnFaces) {
  const core::TriMesh box = test::make_box(2.0, 1.0, 1.0, 3);
  const std::vector<construct::TipCorner> tips = construct::find_tip_corners(box);
  ASSERT_EQ(tips.size(),
            8u);  // the vertices along the edges and inside the faces are flat or straight
  for (const construct::TipCorner& tip : tips) {
    EXPECT_NEAR(tip.angle_sum, 1.5 * std::numbers::pi, 1e-12);
    ASSERT_EQ(tip.ring.size(), tip.ring_labels.size());
    for (std::size_t i = 0; i < tip.ring.size(); ++i)
      EXPECT_EQ(tip.ring_labels[i], core::dominant_axis_label(unit_normal(box, tip.ring[i])));
  }
}

TEST(TipCorners, ATetrahedronsTipsGetTheConvexCornerThatFitsTheirFacesBest) {
  for (const core::TriMesh& tet : {test::regular_tetrahedron(), cube_diagonal_tetrahedron()}) {
    const std::vector<construct::TipCorner> tips = construct::find_tip_corners(tet);
    ASSERT_EQ(tips.size(), 4u);
    for (const construct::TipCorner& tip : tips) {
      EXPECT_NEAR(tip.angle_sum, std::numbers::pi, 1e-12);  // three angles of 60°
      ASSERT_EQ(tip.ring.size(), 3u);
      const auto& l = tip.ring_labels;
      EXPECT_EQ(
          (std::set<int>{core::label_axis(l[0]), core::label_axis(l[1]), core::label_axis(l[2])}
               .size()),
          3u);
      EXPECT_GT(corner_determinant(l[0], l[1], l[2]), 0.0)
          << "tip " << tip.vertex << " is a corner turned inside out";
      // No convex corner fits the three faces better (the angles are equal, so the fit is the
      // sum of n·axis).
      const auto fit = [&](int a, int b, int c) {
        return unit_normal(tet, tip.ring[0]).dot(core::label_direction(a)) +
               unit_normal(tet, tip.ring[1]).dot(core::label_direction(b)) +
               unit_normal(tet, tip.ring[2]).dot(core::label_direction(c));
      };
      for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b)
          for (int c = 0; c < 6; ++c) {
            const std::set<int> axes{core::label_axis(a), core::label_axis(b), core::label_axis(c)};
            if (axes.size() == 3 && corner_determinant(a, b, c) > 0) {
              EXPECT_LE(fit(a, b, c), fit(l[0], l[1], l[2]) + 1e-12);
            }
          }
    }
  }
}

TEST(TipCorners, TipsWhoseFacesTieTheAxesTakeTheCornerTheyPointTo) {
  // Every face of this tetrahedron is equally far from three axes, so every sign choice fits a
  // tip equally; the tips point to four different corners of the cube around it, and take them.
  const core::TriMesh tet = cube_diagonal_tetrahedron();
  const Vec3 centre = (tet.points[0] + tet.points[1] + tet.points[2] + tet.points[3]) / 4.0;
  std::set<std::array<int, 3>> corners;
  for (const construct::TipCorner& tip : construct::find_tip_corners(tet)) {
    std::array<int, 3> signs{};
    for (int l : tip.ring_labels) signs[core::label_axis(l)] = l % 2 == 0 ? 1 : -1;
    const Vec3 points = tet.points[tip.vertex] - centre;
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(signs[a], points[a] > 0 ? 1 : -1) << "tip " << tip.vertex << " axis " << a;
    corners.insert(signs);
  }
  EXPECT_EQ(corners.size(), 4u);
}

TEST(TipCorners, TheTwoEndsOfARidgeGiveItsFacesTheSameLabels) {
  // A wedge: its ridge's ends point straight between two corners (-X or +X, ±Y, +Z), both of
  // which fit equally. Ends that chose differently would twist the ridge's polycube edge.
  // Which end decides first and where each ring starts depend on the numbering: every cyclic
  // shift of the vertex numbers and of the triangles' order is tried.
  const std::vector<Vec3> points{{0, 0, 0},  {0, 10, 0},  {0, 5, 8},
                                 {20, 0, 0}, {20, 10, 0}, {20, 5, 8}};
  const std::vector<core::Tri> cells{{0, 2, 1}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3},
                                     {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  for (int shift = 0; shift < 8; ++shift) {
    core::TriMesh wedge;
    wedge.points.resize(6);
    for (int v = 0; v < 6; ++v) wedge.points[(v + shift) % 6] = points[v];
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const core::Tri& t = cells[(c + static_cast<std::size_t>(shift)) % cells.size()];
      wedge.cells.push_back({(t[0] + shift) % 6, (t[1] + shift) % 6, (t[2] + shift) % 6});
    }
    // Refined, as construct does: the two ends' rings share no triangle.
    construct::SurfaceRefinement done;
    wedge = construct::subdivide_to(wedge, 6.0, 1000000, done);
    ASSERT_EQ(done.levels, 2);
    // And numbered as the boundary of its tet mesh, which construct labels.
    wedge = core::boundary(construct::tetrahedralize(wedge).mesh).surface;
    const std::vector<construct::TipCorner> tips = construct::find_tip_corners(wedge);
    ASSERT_EQ(tips.size(), 6u);  // 90 + 90 + 58 degrees at each
    const auto tip_at = [&](const Vec3& p) {
      return *std::find_if(tips.begin(), tips.end(), [&](const construct::TipCorner& t) {
        return wedge.points[t.vertex] == p;
      });
    };
    const int ridge_a = tip_at(points[2]).vertex, ridge_b = tip_at(points[5]).vertex;
    const construct::TipCorner a = tip_at(points[2]), b = tip_at(points[5]);
    int shared = 0;
    for (std::size_t i = 0; i < a.ring.size(); ++i)
      for (std::size_t j = 0; j < b.ring.size(); ++j) {
        const Vec3 n = unit_normal(wedge, a.ring[i]);
        const bool same_plane =
            n.dot(unit_normal(wedge, b.ring[j])) > 1.0 - 1e-12 &&
            std::abs(n.dot(wedge.points[ridge_b] - wedge.points[ridge_a])) < 1e-12;
        if (!same_plane) continue;
        ++shared;
        EXPECT_EQ(a.ring_labels[i], b.ring_labels[j])
            << "shift " << shift << ": ring triangles " << a.ring[i] << " and " << b.ring[j];
      }
    EXPECT_GE(shared, 2) << "shift " << shift;  // both slanted sides
  }
}

TEST(TipCorners, SteeredTrianglesLieInTheirSectorsPlaneWithinAThirdOfAnEdge) {
  construct::SurfaceRefinement done;
  const core::TriMesh tet =
      construct::subdivide_to(test::regular_tetrahedron(), 10.0 / 8.0, 1000000, done);
  ASSERT_EQ(done.levels, 3);
  std::vector<construct::TipCorner> tips = construct::find_tip_corners(tet);
  ASSERT_EQ(tips.size(), 4u);  // the new vertices are flat
  const std::vector<int> steered = construct::tip_corner_labels(tet, tips);
  ASSERT_EQ(steered.size(), tet.cells.size());
  std::vector<int> per_sector(12, 0);
  for (int t = 0; t < tet.num_cells(); ++t) {
    if (steered[t] < 0) continue;
    // The one tip and ring triangle it belongs to: the same plane, within the tip's radius.
    int owners = 0;
    for (std::size_t k = 0; k < tips.size(); ++k) {
      EXPECT_NEAR(tips[k].radius, 10.0 / 3.0, 1e-12);  // the nearest other corner is a tip, 10 away
      const Vec3 centroid = (tet.points[tet.cells[t][0]] + tet.points[tet.cells[t][1]] +
                             tet.points[tet.cells[t][2]]) /
                            3.0;
      if ((centroid - tet.points[tips[k].vertex]).norm() > tips[k].radius) continue;
      for (std::size_t i = 0; i < tips[k].ring.size(); ++i)
        if (unit_normal(tet, t).dot(unit_normal(tet, tips[k].ring[i])) > 1.0 - 1e-9) {
          ++owners;
          EXPECT_EQ(steered[t], tips[k].ring_labels[i]);
          ++per_sector[3 * k + i];
        }
    }
    EXPECT_EQ(owners, 1) << "triangle " << t;
  }
  // Each sector holds its ring triangle and more: the triangles within a third of an edge.
  for (int n : per_sector) EXPECT_GT(n, 1);
  EXPECT_EQ(construct::steering_penalty(steered).size(), tet.cells.size());
  EXPECT_TRUE(construct::steering_penalty(std::vector<int>(tet.cells.size(), -1)).empty());
}

TEST(TipCorners, TheRepairKeepsTheHeldTipsCornersAndReachesAValidLabeling) {
  construct::SurfaceRefinement done;
  const core::TriMesh tet =
      construct::subdivide_to(test::regular_tetrahedron(), 10.0 / 16.0, 1000000, done);
  std::vector<construct::TipCorner> tips = construct::find_tip_corners(tet);
  const std::vector<int> held = construct::tip_corner_labels(tet, tips);
  construct::LabelingOptions lopt;
  lopt.penalty = construct::steering_penalty(held);
  const construct::LabelingResult cut = construct::graph_cut_labeling(tet, lopt);
  construct::RepairOptions ropt;
  ropt.energy = lopt;
  ropt.held = held;
  const construct::RepairResult r = construct::repair_labeling(tet, cut.labels, ropt);
  EXPECT_TRUE(r.valid()) << (r.check.defects.empty() ? "" : r.check.defects.front().reason);
  for (int t = 0; t < tet.num_cells(); ++t)
    if (held[t] >= 0) {
      EXPECT_EQ(r.labels[t], held[t]) << "triangle " << t;
    }
  // So every tip is a valid corner of the labeling.
  const std::vector<int>& corners = r.check.layout.corners;
  for (const construct::TipCorner& tip : tips)
    EXPECT_TRUE(std::binary_search(corners.begin(), corners.end(), tip.vertex))
        << "tip " << tip.vertex;
  // The unfolding against the estimate's folds (the pre-deformed attempts') leaves them too.
  const construct::UnfoldResult free = construct::unfold_labeling(tet, r.labels, 50);
  const construct::UnfoldResult kept = construct::unfold_labeling(tet, r.labels, 50, held);
  int moved_held = 0;
  for (int t = 0; t < tet.num_cells(); ++t) {
    moved_held += held[t] >= 0 && free.labels[t] != held[t];
    if (held[t] >= 0) {
      EXPECT_EQ(kept.labels[t], held[t]) << "triangle " << t;
    }
  }
  EXPECT_GT(moved_held, 0);  // left free, it does move them (47 of them here)
  EXPECT_GT(kept.moves, 0);
}

TEST(CoarseSurface, ATetrahedronConstructsWithItsTipsAtPolycubeCorners) {
  construct::ConstructOptions o;
  o.min_tets = 2000;  // enough for this shape, and quick
  for (const core::TriMesh& tet : {test::regular_tetrahedron(), cube_diagonal_tetrahedron()}) {
    const construct::ConstructResult r = construct::construct_polycube(tet, o);
    EXPECT_TRUE(r.certificate.certified());
    EXPECT_GT(r.coarse_refinement.levels, 0);
    // The tips are the map's first four points (the surface's vertices come first, as they
    // were); around each, the boundary carries one label per axis.
    for (int tip = 0; tip < 4; ++tip) {
      ASSERT_EQ(r.map.model[tip], tet.points[tip]);
      std::set<int> axes, labels;
      for (std::size_t b = 0; b < r.boundary.size(); ++b)
        if (std::find(r.boundary[b].begin(), r.boundary[b].end(), tip) != r.boundary[b].end()) {
          labels.insert(r.labels[b]);
          axes.insert(core::label_axis(r.labels[b]));
        }
      EXPECT_EQ(labels.size(), 3u) << "tip " << tip;
      EXPECT_EQ(axes.size(), 3u) << "tip " << tip;
    }
  }
}

//! A triangular bipyramid: an equilateral equator of radius 10, apexes 12 above and below.
core::TriMesh bipyramid() {
  core::TriMesh m;
  const double h = 5.0 * std::sqrt(3.0);
  m.points = {{10, 0, 0}, {-5, h, 0}, {-5, -h, 0}, {0, 0, 12}, {0, 0, -12}};
  m.cells = {{0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {1, 0, 4}, {2, 1, 4}, {0, 2, 4}};
  return m;
}

// TetGen 1.5 (Debian's build keeps its assert()s) aborts on this surface split 4 to 256 times:
// tetrahedralize() runs it in a process of its own, so the abort is reported, not suffered.
TEST(CoarseSurface, TetGenStoppingOnASplitSurfaceIsAnErrorNotACrash) {
  construct::SurfaceRefinement done;
  const core::TriMesh split = construct::subdivide_to(bipyramid(), 5.0, 1000000, done);
  try {
    const construct::TetrahedralizeResult r = construct::tetrahedralize(split);
    EXPECT_EQ(core::boundary(r.mesh).surface.num_cells(),
              split.num_cells());  // a TetGen without the bug
  } catch (const construct::TetgenFailed& e) {
    EXPECT_NE(std::string(e.what()).find("TetGen"), std::string::npos) << e.what();
  }
}

TEST(CoarseSurface, ATriangularBipyramidConstructs) {
  // Where TetGen stops on the split surface, construct splits it once more and goes on.
  construct::ConstructOptions o;
  o.min_tets = 2000;
  const construct::ConstructResult r = construct::construct_polycube(bipyramid(), o);
  EXPECT_TRUE(r.certificate.certified());
  EXPECT_EQ(r.tip_corners, 5);  // the two apexes and the three vertices of the equator
}

}  // namespace
}  // namespace polycube
