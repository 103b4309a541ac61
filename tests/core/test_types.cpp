// Element tables of elements.h and the basic mesh types of types.h.
#include "core/elements.h"
#include "core/topology.h"
#include "core/types.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <set>

namespace polycube::core {
namespace {

// Unit cube in the canonical hex order (elements.h diagram).
const std::array<Vec3, 8> kCube{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
// Reference tet: origin, x, y, z.
const std::array<Vec3, 4> kTet{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};

template <std::size_t K, std::size_t N>
Vec3 polygon_normal(const std::array<int, K>& f, const std::array<Vec3, N>& p) {
  Vec3 n = Vec3::Zero();  // Newell's normal: exact for planar polygons, any orientation
  for (std::size_t i = 0; i < K; ++i) n += p[f[i]].cross(p[f[(i + 1) % K]]);
  return n;
}

template <std::size_t K, std::size_t N>
Vec3 centroid(const std::array<int, K>& f, const std::array<Vec3, N>& p) {
  Vec3 c = Vec3::Zero();
  for (int v : f) c += p[v];
  return c / static_cast<double>(K);
}

TEST(ElementTables, HexIsPositiveOnUnitCube) {
  const Vec3 d = (kCube[1] - kCube[0]).cross(kCube[3] - kCube[0]);
  EXPECT_GT(d.dot(kCube[4] - kCube[0]), 0.0);
}

TEST(ElementTables, HexFacesPointOutward) {
  const Vec3 centre(0.5, 0.5, 0.5);
  for (int f = 0; f < 6; ++f) {
    const Vec3 n = polygon_normal(kHexFaces[f], kCube);
    const Vec3 c = centroid(kHexFaces[f], kCube);
    EXPECT_GT(n.dot(c - centre), 0.0) << "hex face " << f;
    // Unit square faces: |Newell normal| = 2 * area = 2, parallel to the offset.
    EXPECT_NEAR(n.norm(), 2.0, 1e-12);
    EXPECT_NEAR(n.normalized().dot((c - centre).normalized()), 1.0, 1e-12) << "hex face " << f;
  }
}

TEST(ElementTables, HexFaceNamesMatchComment) {
  // bottom (z-), top (z+), front (y-), right (x+), back (y+), left (x-)
  const std::array<Vec3, 6> dirs{Vec3(0, 0, -1), Vec3(0, 0, 1), Vec3(0, -1, 0),
                                 Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(-1, 0, 0)};
  for (int f = 0; f < 6; ++f)
    EXPECT_NEAR(polygon_normal(kHexFaces[f], kCube).normalized().dot(dirs[f]), 1.0, 1e-12) << f;
}

TEST(ElementTables, HexOppositeFaces) {
  for (int f = 0; f < 6; ++f) {
    const int g = kHexOppositeFace[f];
    EXPECT_EQ(kHexOppositeFace[g], f);
    std::set<int> all(kHexFaces[f].begin(), kHexFaces[f].end());
    all.insert(kHexFaces[g].begin(), kHexFaces[g].end());
    EXPECT_EQ(all.size(), 8u) << "opposite faces " << f << ", " << g << " must be disjoint";
  }
}

TEST(ElementTables, EveryHexEdgeInExactlyTwoFaces) {
  std::set<std::pair<int, int>> table_edges;
  for (const auto& e : kHexEdges) table_edges.insert(std::minmax(e[0], e[1]));
  EXPECT_EQ(table_edges.size(), 12u);
  for (const auto& e : kHexEdges) {
    int count = 0;
    for (const auto& f : kHexFaces)
      for (int i = 0; i < 4; ++i)
        if (std::minmax(f[i], f[(i + 1) % 4]) == std::minmax(e[0], e[1])) ++count;
    EXPECT_EQ(count, 2) << "hex edge " << e[0] << "-" << e[1];
  }
  // And every face side is a table edge; hex edges are unit-length cube edges.
  for (const auto& f : kHexFaces)
    for (int i = 0; i < 4; ++i) EXPECT_TRUE(table_edges.count(std::minmax(f[i], f[(i + 1) % 4])));
  for (const auto& e : kHexEdges) EXPECT_NEAR((kCube[e[0]] - kCube[e[1]]).norm(), 1.0, 1e-15);
}

TEST(ElementTables, HexCornerJacobiansPositiveOnUnitCube) {
  for (int i = 0; i < 8; ++i) {
    const auto& nb = kHexCornerNeighbors[i];
    const double det =
        (kCube[nb[0]] - kCube[i]).dot((kCube[nb[1]] - kCube[i]).cross(kCube[nb[2]] - kCube[i]));
    EXPECT_NEAR(det, 1.0, 1e-15) << "corner " << i;
    for (int n : nb) EXPECT_NEAR((kCube[n] - kCube[i]).norm(), 1.0, 1e-15) << "neighbour of " << i;
  }
}

TEST(ElementTables, TetFacesPointOutwardAndAreOpposite) {
  const Vec3 d = (kTet[1] - kTet[0]).cross(kTet[2] - kTet[0]);
  ASSERT_GT(d.dot(kTet[3] - kTet[0]), 0.0);
  const Vec3 centre = 0.25 * (kTet[0] + kTet[1] + kTet[2] + kTet[3]);
  for (int f = 0; f < 4; ++f) {
    const Vec3 n = polygon_normal(kTetFaces[f], kTet);
    EXPECT_GT(n.dot(centroid(kTetFaces[f], kTet) - centre), 0.0) << "tet face " << f;
    EXPECT_EQ(std::count(kTetFaces[f].begin(), kTetFaces[f].end(), f), 0)
        << "face " << f << " opposite vertex " << f;
  }
}

TEST(ElementTables, EveryTetEdgeInExactlyTwoFaces) {
  for (const auto& e : kTetEdges) {
    int count = 0;
    for (const auto& f : kTetFaces)
      for (int i = 0; i < 3; ++i)
        if (std::minmax(f[i], f[(i + 1) % 3]) == std::minmax(e[0], e[1])) ++count;
    EXPECT_EQ(count, 2);
  }
}

TEST(ElementTables, PerKindConstants) {
  EXPECT_EQ(edge_count(CellType::Triangle), static_cast<int>(kTriEdges.size()));
  EXPECT_EQ(edge_count(CellType::Quad), static_cast<int>(kQuadEdges.size()));
  EXPECT_EQ(edge_count(CellType::Tetra), static_cast<int>(kTetEdges.size()));
  EXPECT_EQ(edge_count(CellType::Hexa), static_cast<int>(kHexEdges.size()));
  EXPECT_EQ(face_count(CellType::Tetra), 4);
  EXPECT_EQ(face_count(CellType::Hexa), 6);
  EXPECT_EQ(vertex_count(CellType::Hexa), 8);
  EXPECT_EQ(dimension(CellType::Quad), 2);
  EXPECT_EQ(dimension(CellType::Tetra), 3);
}

TEST(MeshTypes, MeshDataRoundTrip) {
  HexMesh h;
  h.points.assign(kCube.begin(), kCube.end());
  h.cells.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  h.labels = {7};
  const MeshData d = to_mesh_data(h);
  EXPECT_EQ(d.hexes.size(), 1u);
  EXPECT_EQ(d.num_cells(), 1u);
  const HexMesh back = hexes_of(d);
  EXPECT_EQ(back.cells, h.cells);
  EXPECT_EQ(back.labels, h.labels);
  EXPECT_TRUE(tets_of(d).empty());
  const BoundingBox b = bounding_box(h.points);
  EXPECT_DOUBLE_EQ(b.diagonal(), std::sqrt(3.0));
}

}  // namespace
}  // namespace polycube::core
