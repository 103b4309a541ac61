// Structure extraction on analytic polycubes (L shape, box with a bump: a face with a hole).
#include "structure/analytic_maps.h"
#include "structure/structure.h"
#include "structure/structure_io.h"
#include "structure/validate.h"

#include <gtest/gtest.h>

#include <set>

namespace polycube::structure {
namespace {

using test::GridMap;
using test::Vec3;

//! Box [0,3]^2 x [0,1] with a unit cube on top of its middle ([1,2]^2 x [1,2]).
GridMap box_with_bump(int r) {
  return test::make_grid_map(
      test::uniform(0, 3, 3 * r), test::uniform(0, 3, 3 * r), test::uniform(0, 2, 2 * r),
      [](const Vec3& c) { return c.z() < 1 || (c.x() > 1 && c.x() < 2 && c.y() > 1 && c.y() < 2); },
      [](const Vec3& p) { return p; });
}

void expect_consistent(const PolycubeStructure& s, const core::PolycubeMap& m) {
  const double tol = 1e-12;
  for (const Corner& c : s.corners) {
    EXPECT_GE(c.charts.size(), 3u);
    EXPECT_EQ(s.vertex_corner[c.vertex], &c - s.corners.data());
  }
  for (const Edge& e : s.edges) {
    ASSERT_GE(e.axis, 0);
    ASSERT_GE(e.corners[0], 0);
    ASSERT_GE(e.corners[1], 0);
    const Vec3 d = s.corners[e.corners[1]].position - s.corners[e.corners[0]].position;
    // an edge runs along its axis only, and its length is the corner distance
    for (int a = 0; a < 3; ++a) {
      if (a != e.axis) {
        EXPECT_NEAR(d[a], 0.0, tol);
      }
    }
    EXPECT_NEAR(std::abs(d[e.axis]), e.length, tol);
    // every vertex of the chain lies on both charts' planes
    for (int v : e.vertices)
      for (int c : e.charts)
        EXPECT_NEAR(m.polycube[v][s.charts[c].axis], s.charts[c].coordinate, tol);
  }
  for (const Chart& c : s.charts) EXPECT_LE(c.deviation, tol);
  // the outer loop of each face is positive and the loops' areas add up to the chart area
  for (const Face& f : s.faces) {
    ASSERT_FALSE(f.loops.empty());
    EXPECT_GT(f.loops[0].area, 0.0);
    double a = 0.0;
    for (const Loop& l : f.loops) a += l.area;
    EXPECT_NEAR(a, s.charts[f.chart].area, 1e-9);
    for (std::size_t k = 1; k < f.loops.size(); ++k) EXPECT_LT(f.loops[k].area, 0.0);
  }
}

TEST(Structure, LShape) {
  const GridMap g = test::l_shape(2);
  ASSERT_NO_THROW(validate_map(g.map));
  const PolycubeStructure s = extract_structure(g.map);
  EXPECT_EQ(s.charts.size(), 8u);
  EXPECT_EQ(s.corners.size(), 12u);
  EXPECT_EQ(s.edges.size(), 18u);
  EXPECT_EQ(s.num_concave_edges(), 1);
  EXPECT_EQ(s.num_convex_edges(), 17);
  EXPECT_EQ(s.faces.size(), 8u);
  EXPECT_EQ(s.num_faces_with_holes(), 0);
  expect_consistent(s, g.map);

  // the concave edge is the inner vertical edge at x = y = 1
  for (const Edge& e : s.edges)
    if (!e.convex) {
      EXPECT_EQ(e.axis, 2);
      EXPECT_NEAR(s.corners[e.corners[0]].position.x(), 1.0, 1e-12);
      EXPECT_NEAR(s.corners[e.corners[0]].position.y(), 1.0, 1e-12);
      EXPECT_NEAR(e.length, 1.0, 1e-12);
    }
  double total_area = 0.0, total_length = 0.0;
  for (const Chart& c : s.charts) total_area += c.area;
  for (const Edge& e : s.edges) total_length += e.length;
  EXPECT_NEAR(total_area, test::kLArea, 1e-9);
  EXPECT_NEAR(total_length, 22.0, 1e-9);  // 8 (top) + 8 (bottom) + 6 vertical
  // every corner of the L has valence 3; its three edges have three distinct axes
  for (const Corner& c : s.corners) {
    ASSERT_EQ(c.edges.size(), 3u);
    std::set<int> axes;
    for (int e : c.edges) axes.insert(s.edges[e].axis);
    EXPECT_EQ(axes.size(), 3u);
  }
  // charts: the top is +Z at z = 1 with an L-shaped outline of 6 corners
  int tops = 0;
  for (std::size_t i = 0; i < s.charts.size(); ++i)
    if (s.charts[i].label == 4) {
      ++tops;
      EXPECT_NEAR(s.charts[i].coordinate, 1.0, 1e-12);
      EXPECT_NEAR(s.charts[i].area, 3.0, 1e-12);
      ASSERT_EQ(s.faces[i].loops.size(), 1u);
      EXPECT_EQ(s.faces[i].loops[0].corners.size(), 6u);
      EXPECT_NEAR(s.faces[i].loops[0].area, 3.0, 1e-12);
    }
  EXPECT_EQ(tops, 1);
}

TEST(Structure, FaceWithHole) {
  const GridMap g = box_with_bump(1);
  ASSERT_NO_THROW(validate_map(g.map));
  const PolycubeStructure s = extract_structure(g.map);
  EXPECT_EQ(s.charts.size(), 11u);
  EXPECT_EQ(s.corners.size(), 16u);
  EXPECT_EQ(s.edges.size(), 24u);
  EXPECT_EQ(s.num_concave_edges(), 4);
  EXPECT_EQ(s.num_faces_with_holes(), 1);
  expect_consistent(s, g.map);
  // Euler's formula for a sphere with one annular face: V - E + F - holes = 2
  EXPECT_EQ(static_cast<int>(s.corners.size()) - static_cast<int>(s.edges.size()) +
                static_cast<int>(s.faces.size()) - 1,
            2);
  for (const Face& f : s.faces)
    if (f.num_holes() == 1) {
      const Chart& c = s.charts[f.chart];
      EXPECT_EQ(c.label, 4);
      EXPECT_NEAR(c.coordinate, 1.0, 1e-12);
      EXPECT_NEAR(f.loops[0].area, 9.0, 1e-12);
      EXPECT_NEAR(f.loops[1].area, -1.0, 1e-12);
      EXPECT_EQ(f.loops[0].corners.size(), 4u);
      EXPECT_EQ(f.loops[1].corners.size(), 4u);
    }
  // the concave edges are the bump's bottom edges, at z = 1
  for (const Edge& e : s.edges)
    if (!e.convex) {
      EXPECT_NE(e.axis, 2);
      for (int c : e.corners) EXPECT_NEAR(s.corners[c].position.z(), 1.0, 1e-12);
    }
}

TEST(Structure, DeformedModelDoesNotChangeTheStructure) {
  // the structure is a polycube-space notion: a sheared model gives the same counts
  const GridMap g =
      test::l_shape(2, [](const Vec3& p) { return Vec3(p.x() + 0.3 * p.z(), p.y(), p.z()); });
  const PolycubeStructure s = extract_structure(g.map);
  EXPECT_EQ(s.charts.size(), 8u);
  EXPECT_EQ(s.corners.size(), 12u);
  EXPECT_EQ(s.edges.size(), 18u);
}

TEST(Structure, Deterministic) {
  const GridMap g = box_with_bump(2);
  const PolycubeStructure a = extract_structure(g.map);
  const PolycubeStructure b = extract_structure(g.map);
  EXPECT_EQ(structure_to_vtk(a, g.map.polycube), structure_to_vtk(b, g.map.polycube));
}

TEST(Structure, VtkHasOneCellPerItem) {
  const GridMap g = test::l_shape(1);
  const PolycubeStructure s = extract_structure(g.map);
  const std::string vtk = structure_to_vtk(s, g.map.polycube);
  std::size_t segments = 0;
  for (const Edge& e : s.edges) segments += e.vertices.size() - 1;
  const std::size_t cells = s.triangles.size() + segments + s.corners.size();
  EXPECT_NE(vtk.find("CELL_TYPES " + std::to_string(cells) + "\n"), std::string::npos);
  EXPECT_NE(vtk.find("# vtk DataFile Version 3.0"), std::string::npos);
}

}  // namespace
}  // namespace polycube::structure
