// Singularities and base-complex domains on meshes whose answer is known by hand.
#include "quality/domains.h"
#include "quality/singularities.h"

#include "core/topology.h"
#include "quality_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace polycube::quality {
namespace {

using test::gridded_box;
using test::padded_box;
using test::voxel_polycube;

//! The L-shaped polycube: three unit cubes in an L, one unit high.
const std::vector<std::array<int, 3>> kLShape{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};

TEST(HexSingularities, GriddedBox) {
  // Singular edges: the 12 box edges (one hex each, boundary valence 1), n mesh edges per box
  // edge. Singular vertices: the 8 corners (3 singular edges); the other vertices on box
  // edges have 2, all others 0.
  for (int n = 1; n <= 4; ++n) {
    const auto s = hex_singularities(gridded_box(1, 1, 1, n));
    EXPECT_EQ(s.singular_edges, 12 * n) << n;
    EXPECT_EQ(s.boundary_singular_edges, 12 * n);
    EXPECT_EQ(s.interior_singular_edges, 0);
    EXPECT_EQ(s.singular_vertices, 8) << n;
    ASSERT_EQ(s.boundary_valence.size(), 1u);
    EXPECT_EQ(s.boundary_valence.at(1), 12 * n);
  }
}

TEST(HexSingularities, LShape) {
  // Polycube edges of the L: top and bottom L outlines (perimeter 8 units each) and the six
  // vertical edges (1 unit): 22 units, all convex (1 hex) except the vertical concave edge at
  // (1,1) (3 hexes). 12 polycube corners, each with 3 singular edges.
  for (int n = 1; n <= 3; ++n) {
    const auto s = hex_singularities(voxel_polycube(kLShape, n));
    EXPECT_EQ(s.singular_edges, 22 * n) << n;
    EXPECT_EQ(s.boundary_valence.at(1), 21 * n);
    EXPECT_EQ(s.boundary_valence.at(3), n);
    EXPECT_EQ(s.singular_vertices, 12) << n;
  }
}

TEST(HexSingularities, PaddedBox) {
  // After pillowing a gridded box, the outer boundary edges have 2 hexes (regular); the old box
  // edges become interior edges with 3 hexes (the core hex and two padding hexes), and so do the
  // 8 edges joining each old corner to its outer copy (3 padding hexes around a corner).
  // Singular vertices: the 8 old corners (3 + 1 singular edges) and the 8 outer corners (1).
  for (int n = 1; n <= 3; ++n) {
    const auto s = hex_singularities(padded_box(n));
    EXPECT_EQ(s.singular_edges, 12 * n + 8) << n;
    EXPECT_EQ(s.boundary_singular_edges, 0);
    EXPECT_EQ(s.interior_valence.at(3), 12 * n + 8);
    EXPECT_EQ(s.singular_vertices, 16) << n;
  }
}

TEST(HexDomains, GriddedBoxIsOneBlock) {
  for (int n = 1; n <= 4; ++n) {
    const auto d = hex_domains(gridded_box(1, 1, 1, n));
    EXPECT_EQ(d.domains, 1) << n;
    EXPECT_EQ(d.separating_faces, 0);
  }
  // A box made of two voxels is still one block: the interface has no singular edge.
  EXPECT_EQ(hex_domains(gridded_box(2, 1, 1, 2)).domains, 1);
  EXPECT_EQ(hex_domains(gridded_box(3, 2, 1, 1)).domains, 1);
}

TEST(HexDomains, LShapeSameCountAtEveryResolution) {
  // The only interior-reaching singular edge is the concave vertical edge at (1,1) (3 hexes).
  // Its two interior faces start the sheets x = 1 (0 <= y <= 1) and y = 1 (0 <= x <= 1), which
  // run to the boundary; the convex edges' faces are all on the boundary. So the blocks are the
  // three unit cubes: #D = 3, whatever the resolution.
  for (int n = 1; n <= 4; ++n) {
    const auto m = voxel_polycube(kLShape, n);
    const auto d = hex_domains(m);
    EXPECT_EQ(d.domains, 3) << "resolution " << n;
    EXPECT_EQ(d.separating_faces, 2 * n * n) << n;  // two unit squares of n x n faces
    // Each block is one voxel: n^3 hexes, all with the voxel's block id.
    ASSERT_EQ(d.block_id.size(), m.cells.size());
    for (int v = 0; v < 3; ++v) {
      const int id = d.block_id[v * n * n * n];
      for (int c = v * n * n * n; c < (v + 1) * n * n * n; ++c) ASSERT_EQ(d.block_id[c], id);
    }
    EXPECT_EQ(std::set<int>(d.block_id.begin(), d.block_id.end()).size(), 3u);
    EXPECT_EQ(d.block_id[0], 0);  // numbered by lowest hex
  }
}

TEST(HexDomains, PaddedBoxHasSevenBlocks) {
  // Sheets from the 12 old box edges (3 hexes): two faces of each lie on the old box surface,
  // and the surface sheets cover all of it (they cross the old face interiors, whose edges are
  // regular, and stop at the old box edges); the third face (between the two padding hexes)
  // starts a diagonal strip that runs out to the boundary and stops at the corner edges. The
  // traced faces thus cut the mesh into the core box and the six padding slabs: #D = 7.
  for (int n = 1; n <= 3; ++n) {
    const auto m = padded_box(n);
    const auto d = hex_domains(m);
    EXPECT_EQ(d.domains, 7) << n;
    EXPECT_EQ(d.separating_faces, 6 * n * n + 12 * n) << n;
    // The core hexes (the first n^3) form one block.
    for (int c = 1; c < n * n * n; ++c) ASSERT_EQ(d.block_id[c], d.block_id[0]);
  }
}

TEST(HexDomains, TwoSeparateBoxes) {
  // Two disjoint boxes: two components, one block each.
  core::HexMesh a = gridded_box(1, 1, 1, 2);
  const core::HexMesh b = gridded_box(1, 1, 1, 2);
  const int off = a.num_points();
  for (const auto& p : b.points) a.points.push_back(p + core::Vec3(5, 0, 0));
  for (auto c : b.cells) {
    for (int& v : c) v += off;
    a.cells.push_back(c);
  }
  EXPECT_EQ(hex_domains(a).domains, 2);
}

TEST(HexDomains, ReusesTopologyAndCanDropLabels) {
  const auto m = voxel_polycube(kLShape, 2);
  const auto t = hex_topology(m);
  const auto s = hex_singularities(m, t);
  const auto d = hex_domains(m, t, s, DomainOptions{false});
  EXPECT_EQ(d.domains, 3);
  EXPECT_TRUE(d.block_id.empty());
  EXPECT_TRUE(d.face_traced.empty());
  const auto full = hex_domains(m);
  const auto f = full.field();
  EXPECT_EQ(f.name, "block_id");
  EXPECT_EQ(f.values.size(), m.cells.size());
}

TEST(HexDomains, Deterministic) {
  const auto m = padded_box(2);
  const auto a = hex_domains(m), b = hex_domains(m);
  EXPECT_EQ(a.block_id, b.block_id);
  EXPECT_EQ(a.face_traced, b.face_traced);
}

TEST(QuadSingularitiesAndDomains, CubeSurface) {
  // The boundary of a gridded cube: the 8 corners have 3 quads (singular), every other vertex 4.
  // Separatrices from the corners run along the cube edges: 6 patches.
  for (int n = 1; n <= 4; ++n) {
    const auto q = core::boundary(gridded_box(1, 1, 1, n)).surface;
    const auto s = quad_singularities(q);
    EXPECT_EQ(s.singular_vertices, 8) << n;
    EXPECT_EQ(s.interior_valence.at(3), 8);
    const auto d = quad_domains(q);
    EXPECT_EQ(d.domains, 6) << n;
    EXPECT_EQ(d.separating_edges, 12 * n);
  }
}

TEST(QuadSingularitiesAndDomains, LShapeSurface) {
  // 12 polycube corners: 10 convex (3 quads) and the two ends of the concave edge (5 quads).
  // Patches: each of the top and bottom L faces is cut in 3 squares by the separatrices leaving
  // the concave corners along x = 1 and y = 1; these continue down the walls x = 0 and y = 0,
  // cutting each in 2; the four other walls stay whole: 3 + 3 + 2 + 2 + 4 = 14.
  for (int n = 1; n <= 4; ++n) {
    const auto q = core::boundary(voxel_polycube(kLShape, n)).surface;
    const auto s = quad_singularities(q);
    EXPECT_EQ(s.singular_vertices, 12) << n;
    EXPECT_EQ(s.interior_valence.at(3), 10);
    EXPECT_EQ(s.interior_valence.at(5), 2);
    EXPECT_EQ(quad_domains(q).domains, 14) << n;
  }
}

TEST(QuadSingularitiesAndDomains, OpenGridWithBoundary) {
  // A flat n x n grid of quads: the 4 corners have 1 quad (boundary, != 2): singular. Boundary
  // separatrices run along the border; the grid is one patch.
  const auto box = gridded_box(1, 1, 1, 3);
  const auto surface = core::boundary(box).surface;
  core::QuadMesh q;
  q.points = surface.points;
  for (const auto& c : surface.cells) {
    bool bottom = true;
    for (int v : c) bottom = bottom && q.points[v].z() == 0.0;
    if (bottom) q.cells.push_back(c);
  }
  ASSERT_EQ(q.num_cells(), 9);
  const auto s = quad_singularities(q);
  EXPECT_EQ(s.singular_vertices, 4);
  EXPECT_EQ(s.boundary_singular_vertices, 4);
  EXPECT_EQ(s.boundary_valence.at(1), 4);
  EXPECT_EQ(quad_domains(q).domains, 1);
}

}  // namespace
}  // namespace polycube::quality
