// Topology of core/topology.h on meshes built in code.
#include "core/topology.h"

#include "core/errors.h"
#include "support/fixtures.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace polycube::core {
namespace {

using test::hex_grid;
using test::sphere;
using test::tetrahedralize;

// --- closed-form counts of a structured nx x ny x nz hex grid ---------------------------------
struct GridCounts {
  int vertices, edges, faces, boundary_faces, cells;
};
GridCounts grid_counts(int nx, int ny, int nz) {
  GridCounts c{};
  c.vertices = (nx + 1) * (ny + 1) * (nz + 1);
  // edges along x: nx per grid line, (ny+1)(nz+1) lines; same for y and z.
  c.edges = nx * (ny + 1) * (nz + 1) + (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
  // faces normal to x: (nx+1) planes of ny*nz faces; same for y and z.
  c.faces = (nx + 1) * ny * nz + nx * (ny + 1) * nz + nx * ny * (nz + 1);
  c.boundary_faces = 2 * (nx * ny + ny * nz + nz * nx);
  c.cells = nx * ny * nz;
  return c;
}

TetMesh single_tet() {
  TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
  m.cells = {{0, 1, 2, 3}};
  return m;
}

// --- single elements ---------------------------------------------------------------------------

TEST(Topology, SingleTet) {
  const TetMesh m = single_tet();
  const auto et = unique_edges(m);
  EXPECT_EQ(et.num_edges(), 6);
  const auto ft = unique_faces(m);
  ASSERT_EQ(ft.num_faces(), 4);
  for (int f = 0; f < 4; ++f) {
    EXPECT_TRUE(ft.is_boundary(f));
    EXPECT_EQ(ft.cell_faces[0][f], f);  // first appearance order
    EXPECT_EQ(ft.face_local[f][0], f);
  }
  const TetBoundary b = boundary(m);
  EXPECT_EQ(b.surface.num_cells(), 4);
  EXPECT_EQ(b.surface.num_points(), 4);
  EXPECT_NEAR(signed_volume(b.surface), 1.0 / 6.0, 1e-15);
  const VolumeReport r = analyze_volume(m);
  EXPECT_EQ(r.inverted_cells, 0);
  EXPECT_EQ(r.boundary_faces, 4);
  EXPECT_EQ(r.euler_characteristic, 1);
  EXPECT_TRUE(r.boundary.closed);
  EXPECT_EQ(r.boundary.genus, 0);

  TetMesh inv = m;
  std::swap(inv.cells[0][1], inv.cells[0][2]);
  EXPECT_EQ(analyze_volume(inv).inverted_cells, 1);
  EXPECT_NEAR(signed_volume(boundary(inv).surface), -1.0 / 6.0, 1e-15);
}

TEST(Topology, SingleHex) {
  const HexMesh m = hex_grid(1, 1, 1);
  EXPECT_EQ(unique_edges(m).num_edges(), 12);
  const auto ft = unique_faces(m);
  EXPECT_EQ(ft.num_faces(), 6);
  const HexBoundary b = boundary(m);
  EXPECT_EQ(b.surface.num_cells(), 6);
  EXPECT_EQ(b.surface.num_points(), 8);
  EXPECT_NEAR(signed_volume(b.surface), 1.0, 1e-14);
  const SurfaceReport s = analyze_surface(b.surface);
  EXPECT_TRUE(s.closed);
  EXPECT_TRUE(s.manifold);
  EXPECT_TRUE(s.consistently_oriented);
  EXPECT_EQ(s.edges, 12);
  EXPECT_EQ(s.euler_characteristic, 2);
  EXPECT_EQ(s.genus, 0);
  const VolumeReport r = analyze_volume(m);
  EXPECT_EQ(r.inverted_cells, 0);

  // Moving vertex 6 through the opposite corner inverts corner Jacobians.
  HexMesh bad = m;
  bad.points[6] = Vec3(-0.5, -0.5, -0.5);
  EXPECT_EQ(analyze_volume(bad).inverted_cells, 1);
}

// --- structured hex grids ---------------------------------------------------------------------

void check_hex_grid(int nx, int ny, int nz) {
  SCOPED_TRACE(testing::Message() << nx << "x" << ny << "x" << nz);
  const HexMesh m = hex_grid(nx, ny, nz);
  const GridCounts want = grid_counts(nx, ny, nz);
  const auto et = unique_edges(m);
  EXPECT_EQ(et.num_edges(), want.edges);
  EXPECT_TRUE(std::is_sorted(et.edges.begin(), et.edges.end()));
  EXPECT_EQ(std::adjacent_find(et.edges.begin(), et.edges.end()), et.edges.end());
  for (const auto& e : et.edges) EXPECT_LT(e[0], e[1]);
  // cell_edges match the local edge table.
  for (int c = 0; c < m.num_cells(); ++c)
    for (int k = 0; k < 12; ++k) {
      const auto& e = et.edges[et.cell_edges[c][k]];
      const auto p = std::minmax(m.cells[c][kHexEdges[k][0]], m.cells[c][kHexEdges[k][1]]);
      EXPECT_EQ(e[0], p.first);
      EXPECT_EQ(e[1], p.second);
    }

  const auto ft = unique_faces(m);
  EXPECT_EQ(ft.num_faces(), want.faces);
  int nb = 0;
  for (int f = 0; f < ft.num_faces(); ++f) {
    nb += ft.is_boundary(f) ? 1 : 0;
    // faces[f] is the local face of its first cell; both cells list the face.
    const int c0 = ft.face_cells[f][0];
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(ft.faces[f][i], m.cells[c0][kHexFaces[ft.face_local[f][0]][i]]);
    for (int s = 0; s < 2; ++s)
      if (ft.face_cells[f][s] >= 0) {
        EXPECT_EQ(ft.cell_faces[ft.face_cells[f][s]][ft.face_local[f][s]], f);
      }
    if (!ft.is_boundary(f)) {
      EXPECT_LT(ft.face_cells[f][0], ft.face_cells[f][1]);
    }
  }
  EXPECT_EQ(nb, want.boundary_faces);
  // First-appearance numbering: the first new face id of each cell never decreases.
  int seen = -1;
  for (const auto& cf : ft.cell_faces)
    for (int f : cf) {
      EXPECT_LE(f, seen + 1);
      seen = std::max(seen, f);
    }

  const VolumeReport r = analyze_volume(m);
  EXPECT_EQ(r.vertices, want.vertices);
  EXPECT_EQ(r.cells, want.cells);
  EXPECT_EQ(r.edges, want.edges);
  EXPECT_EQ(r.faces, want.faces);
  EXPECT_EQ(r.boundary_faces, want.boundary_faces);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.inverted_cells, 0);
  EXPECT_EQ(r.nonmanifold_faces, 0);
  EXPECT_EQ(r.euler_characteristic, 1);  // a ball
  EXPECT_TRUE(r.boundary.closed);
  EXPECT_TRUE(r.boundary.manifold);
  EXPECT_TRUE(r.boundary.consistently_oriented);
  EXPECT_EQ(r.boundary.genus, 0);
  EXPECT_EQ(r.boundary.faces, want.boundary_faces);
  // Boundary vertices: all but the (nx-1)(ny-1)(nz-1) interior ones.
  EXPECT_EQ(r.boundary.vertices, want.vertices - (nx - 1) * (ny - 1) * (nz - 1));

  const HexBoundary b = boundary(m);
  EXPECT_NEAR(signed_volume(b.surface), nx * ny * nz, 1e-10);
  ASSERT_EQ(b.vertex_map.size(), b.surface.points.size());
  EXPECT_TRUE(std::is_sorted(b.vertex_map.begin(), b.vertex_map.end()));
  for (std::size_t i = 0; i < b.vertex_map.size(); ++i)
    EXPECT_EQ(b.surface.points[i], m.points[b.vertex_map[i]]);
  for (int f = 0; f < b.surface.num_cells(); ++f)
    for (int i = 0; i < 4; ++i)
      EXPECT_EQ(b.vertex_map[b.surface.cells[f][i]],
                m.cells[b.cell_of_face[f]][kHexFaces[b.local_face[f]][i]]);
  EXPECT_TRUE(std::is_sorted(b.cell_of_face.begin(), b.cell_of_face.end()));
}

TEST(Topology, HexGrid3x3x3) { check_hex_grid(3, 3, 3); }
TEST(Topology, HexGrid2x3x4) { check_hex_grid(2, 3, 4); }

TEST(Topology, HexGridAdjacency) {
  const HexMesh m = hex_grid(3, 3, 3);
  auto id = [](int i, int j, int k) { return i + 4 * (j + 4 * k); };
  const Adjacency vc = vertex_cells(m);
  ASSERT_EQ(vc.size(), 64);
  EXPECT_EQ(vc.degree(id(0, 0, 0)), 1);
  EXPECT_EQ(vc.degree(id(1, 0, 0)), 2);
  EXPECT_EQ(vc.degree(id(1, 1, 0)), 4);
  EXPECT_EQ(vc.degree(id(1, 1, 1)), 8);
  for (int v = 0; v < vc.size(); ++v) EXPECT_TRUE(std::is_sorted(vc[v].begin(), vc[v].end()));
  EXPECT_EQ(static_cast<int>(vc.items.size()), 27 * 8);

  const auto et = unique_edges(m);
  const Adjacency vv = vertex_vertices(et, m.num_points());
  EXPECT_EQ(vv.degree(id(0, 0, 0)), 3);
  EXPECT_EQ(vv.degree(id(1, 1, 1)), 6);
  for (int v = 0; v < vv.size(); ++v) {
    EXPECT_TRUE(std::is_sorted(vv[v].begin(), vv[v].end()));
    for (int w : vv[v]) EXPECT_NEAR((m.points[v] - m.points[w]).norm(), 1.0, 1e-15);
  }
  const auto n111 = vv[id(1, 1, 1)];
  EXPECT_EQ(std::vector<int>(n111.begin(), n111.end()),
            (std::vector<int>{id(1, 1, 0), id(1, 0, 1), id(0, 1, 1), id(2, 1, 1), id(1, 2, 1),
                              id(1, 1, 2)}));

  const Adjacency ec = edge_cells(et);
  ASSERT_EQ(ec.size(), et.num_edges());
  std::array<int, 5> by_degree{};
  for (int e = 0; e < ec.size(); ++e) ++by_degree[ec.degree(e)];
  // Edges of 4 cells: interior edges, 3 directions x 3 segments x 2x2 inner lines = 36.
  EXPECT_EQ(by_degree[4], 36);
  // Edges of 1 cell: the 12 cube edges x 3 segments.
  EXPECT_EQ(by_degree[1], 36);
  EXPECT_EQ(by_degree[2] + by_degree[1] + by_degree[4], et.num_edges());

  const Adjacency cc = cell_cells(m);
  EXPECT_EQ(cc.degree(13), 6);  // centre hex
  EXPECT_EQ(cc.degree(0), 3);   // corner hex
  EXPECT_EQ(std::vector<int>(cc[13].begin(), cc[13].end()),
            (std::vector<int>{4, 10, 12, 14, 16, 22}));
}

TEST(Topology, HexRingHasGenusOneBoundary) {
  // 3x3x1 grid without its centre column: a ring (solid torus).
  HexMesh m = hex_grid(3, 3, 1);
  m.cells.erase(m.cells.begin() + 4);
  const VolumeReport r = analyze_volume(m);
  EXPECT_EQ(r.isolated_vertices, 0);
  EXPECT_EQ(r.euler_characteristic, 0);  // solid torus
  EXPECT_TRUE(r.boundary.closed);
  EXPECT_TRUE(r.boundary.manifold);
  EXPECT_EQ(r.boundary.euler_characteristic, 0);
  EXPECT_EQ(r.boundary.genus, 1);
  EXPECT_NEAR(signed_volume(boundary(m).surface), 8.0, 1e-12);
}

// --- tetrahedralized cube ---------------------------------------------------------------------

TEST(Topology, TetrahedralizedCube) {
  const int n = 3;
  const double h = 0.5;
  const TetMesh m = tetrahedralize(hex_grid(n, n, n, h));
  const GridCounts g = grid_counts(n, n, n);
  for (int c = 0; c < m.num_cells(); ++c) ASSERT_GT(test::tet_volume(m, c), 0.0);

  const VolumeReport r = analyze_volume(m);
  EXPECT_EQ(r.cells, 6 * g.cells);
  // Edges: grid edges + one diagonal per grid face + one body diagonal per hex.
  EXPECT_EQ(r.edges, g.edges + g.faces + g.cells);
  // Faces: two triangles per grid face + 6 interior triangles per hex.
  EXPECT_EQ(r.faces, 2 * g.faces + 6 * g.cells);
  EXPECT_EQ(r.boundary_faces, 2 * g.boundary_faces);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.inverted_cells, 0);
  EXPECT_EQ(r.euler_characteristic, 1);
  EXPECT_TRUE(r.boundary.closed);
  EXPECT_TRUE(r.boundary.manifold);
  EXPECT_TRUE(r.boundary.orientable);
  EXPECT_TRUE(r.boundary.consistently_oriented);
  EXPECT_EQ(r.boundary.genus, 0);
  EXPECT_EQ(r.boundary.degenerate_faces, 0);

  const TetBoundary b = boundary(m);
  const double cube = std::pow(n * h, 3);
  EXPECT_NEAR(signed_volume(b.surface), cube, 1e-12 * cube);
  // Every boundary triangle points away from the cube centre.
  const Vec3 centre = Vec3::Constant(0.5 * n * h);
  for (const auto& f : b.surface.cells) {
    const Vec3& p0 = b.surface.points[f[0]];
    const Vec3 normal = (b.surface.points[f[1]] - p0).cross(b.surface.points[f[2]] - p0);
    const Vec3 c = (p0 + b.surface.points[f[1]] + b.surface.points[f[2]]) / 3.0;
    EXPECT_GT(normal.dot(c - centre), 0.0);
  }
  // Face topology is consistent with the local tables.
  const auto ft = unique_faces(m);
  for (int f = 0; f < ft.num_faces(); ++f)
    for (int s = 0; s < 2; ++s)
      if (ft.face_cells[f][s] >= 0) {
        std::array<int, 3> a = ft.faces[f], b2{};
        for (int i = 0; i < 3; ++i)
          b2[i] = m.cells[ft.face_cells[f][s]][kTetFaces[ft.face_local[f][s]][i]];
        std::sort(a.begin(), a.end());
        std::sort(b2.begin(), b2.end());
        EXPECT_EQ(a, b2);
      }
}

TEST(Topology, Deterministic) {
  const TetMesh m = tetrahedralize(hex_grid(2, 3, 2));
  const auto f1 = unique_faces(m), f2 = unique_faces(m);
  EXPECT_EQ(f1.faces, f2.faces);
  EXPECT_EQ(f1.face_cells, f2.face_cells);
  EXPECT_EQ(f1.cell_faces, f2.cell_faces);
  const auto e1 = unique_edges(m), e2 = unique_edges(m);
  EXPECT_EQ(e1.edges, e2.edges);
  EXPECT_EQ(e1.cell_edges, e2.cell_edges);
  const auto b1 = boundary(m), b2 = boundary(m);
  EXPECT_EQ(b1.surface.cells, b2.surface.cells);
  EXPECT_EQ(b1.vertex_map, b2.vertex_map);
}

// --- components -------------------------------------------------------------------------------

TEST(Topology, ComponentsThroughFacesOnly) {
  // Tets connect through shared faces only.
  TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, -1, -1)};
  m.cells = {{0, 1, 2, 3}, {0, 1, 4, 2}};  // the second tet shares face 0-1-2: one component
  EXPECT_EQ(connected_components(m).count, 1);
  m.points.emplace_back(0, -1, 0);
  m.cells[1] = {0, 1, 5, 4};  // now it shares only the edge 0-1
  const Components c = connected_components(m);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.cell_component, (std::vector<int>{0, 1}));
  EXPECT_EQ(cell_cells(m).degree(0), 0);
}

TEST(Topology, ComponentsOfDisjointGrids) {
  HexMesh a = hex_grid(2, 1, 1);
  const HexMesh b = hex_grid(1, 1, 1, 0.5);
  const int off = a.num_points();
  for (const auto& p : b.points) a.points.push_back(p + Vec3(5, 0, 0));
  for (auto c : b.cells) {
    for (int& v : c) v += off;
    a.cells.insert(a.cells.begin(), c);  // the small cube becomes cell 0
  }
  const Components c = connected_components(a);
  EXPECT_EQ(c.count, 2);
  EXPECT_EQ(c.cell_component, (std::vector<int>{0, 1, 1}));
  const VolumeReport r = analyze_volume(a);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.boundary.components, 2);
  EXPECT_EQ(r.boundary.genus, 0);
  EXPECT_EQ(r.boundary.euler_characteristic, 4);
  EXPECT_NEAR(signed_volume(boundary(a).surface), 2.125, 1e-12);
}

// --- surfaces ---------------------------------------------------------------------------------

TEST(Surface, TorusGenusOne) {
  const QuadMesh q = test::torus_quads(12, 8);
  const SurfaceReport rq = analyze_surface(q);
  EXPECT_EQ(rq.vertices, 96);
  EXPECT_EQ(rq.edges, 2 * 96);
  EXPECT_EQ(rq.euler_characteristic, 0);
  EXPECT_TRUE(rq.closed);
  EXPECT_TRUE(rq.manifold);
  EXPECT_TRUE(rq.orientable);
  EXPECT_TRUE(rq.consistently_oriented);
  EXPECT_EQ(rq.genus, 1);
  EXPECT_EQ(rq.components, 1);
  EXPECT_EQ(rq.degenerate_faces, 0);

  const TriMesh t = test::split_quads(q);
  const SurfaceReport rt = analyze_surface(t);
  EXPECT_EQ(rt.edges, 3 * 96);
  EXPECT_EQ(rt.euler_characteristic, 0);
  EXPECT_EQ(rt.genus, 1);
  // Volume of the polyhedral torus is close to 2 pi^2 R r^2 (12x8 facets: within 20%).
  const double exact = 2 * std::numbers::pi * std::numbers::pi * 2.0 * 0.49;
  EXPECT_GT(signed_volume(t), 0.8 * exact);
  EXPECT_LT(signed_volume(t), exact);
  EXPECT_NEAR(signed_volume(t), signed_volume(q), 1e-9);  // same split
}

TEST(Surface, TwoToriGenusTwo) {
  const QuadMesh a = test::torus_quads(8, 6);
  QuadMesh m = a;
  for (const auto& p : a.points) m.points.push_back(p + Vec3(10, 0, 0));
  for (auto c : a.cells) {
    for (int& v : c) v += a.num_points();
    m.cells.push_back(c);
  }
  const SurfaceReport r = analyze_surface(m);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.genus, 2);  // sum over components
}

TEST(Surface, SphereWithHoleIsOpen) {
  TriMesh m = sphere(1);
  m.cells.erase(m.cells.begin() + 5);
  const SurfaceReport r = analyze_surface(m);
  EXPECT_FALSE(r.closed);
  EXPECT_EQ(r.boundary_edges, 3);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.euler_characteristic, 1);  // disk
  EXPECT_EQ(r.genus, -1);
  EXPECT_TRUE(r.manifold);
  EXPECT_TRUE(r.consistently_oriented);
}

TEST(Surface, AnnulusHasTwoLoops) {
  // 4x4 grid without its 2x2 centre cells (8 triangles).
  TriMesh m = test::tri_grid(4);
  std::vector<Tri> kept;
  for (int f = 0; f < m.num_cells(); ++f) {
    const int q = f / 2, i = q % 4, j = q / 4;
    if (!(i >= 1 && i <= 2 && j >= 1 && j <= 2)) kept.push_back(m.cells[f]);
  }
  m.cells = kept;
  const SurfaceReport r = analyze_surface(m);
  EXPECT_EQ(r.boundary_loops, 2);
  EXPECT_EQ(r.boundary_edges, 16 + 8);
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_EQ(r.isolated_vertices, 1);  // the grid centre vertex
  EXPECT_TRUE(r.manifold);
}

TEST(Surface, NonManifoldEdge) {
  TriMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, -1, 0), Vec3(0.5, 0, 1)};
  m.cells = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const SurfaceReport r = analyze_surface(m);
  EXPECT_EQ(r.nonmanifold_edges, 1);
  EXPECT_FALSE(r.manifold);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundary_edges, 6);
  EXPECT_EQ(r.genus, -1);
  TriMesh copy = m;
  EXPECT_FALSE(orient_consistently(copy));
  EXPECT_EQ(copy.cells, m.cells);
}

TEST(Surface, BowTieVertex) {
  TriMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(-1, 0, 0), Vec3(-1, -1, 0)};
  m.cells = {{0, 1, 2}, {0, 3, 4}};
  const SurfaceReport r = analyze_surface(m);
  EXPECT_EQ(r.nonmanifold_vertices, 1);
  EXPECT_EQ(r.nonmanifold_edges, 0);
  EXPECT_FALSE(r.manifold);
  EXPECT_EQ(r.components, 2);
  EXPECT_EQ(r.boundary_edges, 6);

  // Two closed tetrahedra touching at one vertex: closed, but not vertex-manifold, so no genus.
  TriMesh two;
  two.points = {Vec3(0, 0, 0),  Vec3(1, 0, 0),  Vec3(0, 1, 0), Vec3(0, 0, 1),
                Vec3(-1, 0, 0), Vec3(0, -1, 0), Vec3(0, 0, -1)};
  two.cells = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1},
               {4, 5, 6}, {0, 6, 5}, {0, 4, 6}, {0, 5, 4}};
  const SurfaceReport r2 = analyze_surface(two);
  EXPECT_TRUE(r2.closed);
  EXPECT_EQ(r2.nonmanifold_vertices, 1);
  EXPECT_FALSE(r2.manifold);
  EXPECT_EQ(r2.genus, -1);
}

TriMesh mobius(int k) {
  TriMesh m;
  for (int i = 0; i < k; ++i) {
    const double u = 2 * std::numbers::pi * i / k;
    for (double s : {-0.3, 0.3}) {
      const double r = 1.0 + s * std::cos(u / 2);
      m.points.emplace_back(r * std::cos(u), r * std::sin(u), s * std::sin(u / 2));
    }
  }
  for (int i = 0; i < k; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    const int c = i + 1 < k ? 2 * (i + 1) : 1;  // the twist: top meets bottom
    const int d = i + 1 < k ? 2 * (i + 1) + 1 : 0;
    m.cells.push_back({a, b, d});
    m.cells.push_back({a, d, c});
  }
  return m;
}

TEST(Surface, MobiusStripIsNonOrientable) {
  const TriMesh m = mobius(16);
  const SurfaceReport r = analyze_surface(m);
  EXPECT_FALSE(r.orientable);
  EXPECT_FALSE(r.consistently_oriented);
  EXPECT_FALSE(r.closed);
  EXPECT_TRUE(r.manifold);
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_EQ(r.boundary_edges, 2 * 16);
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_EQ(r.genus, -1);
  TriMesh copy = m;
  EXPECT_FALSE(orient_consistently(copy));
  EXPECT_EQ(copy.cells, m.cells);
}

TEST(Surface, DegenerateFaces) {
  TriMesh m = test::tri_grid(2);
  m.points.emplace_back(3, 0, 0);
  m.points.emplace_back(4, 0, 0);
  m.cells.push_back({2, 9, 10});  // collinear points (2,0,0), (3,0,0), (4,0,0)
  m.cells.push_back({0, 0, 1});   // repeated index
  const SurfaceReport r = analyze_surface(m);
  EXPECT_EQ(r.degenerate_faces, 2);
}

// --- orientation ------------------------------------------------------------------------------

TEST(Orientation, FixesRandomFlipsOfSphere) {
  const TriMesh ref = sphere(3);  // 512 triangles
  const double v0 = signed_volume(ref);
  ASSERT_GT(v0, 0.9 * 4.0 / 3.0 * std::numbers::pi);
  ASSERT_TRUE(analyze_surface(ref).consistently_oriented);

  std::mt19937 rng(12345);
  for (int trial = 0; trial < 4; ++trial) {
    TriMesh m = ref;
    int flipped = 0;
    for (int f = 0; f < m.num_cells(); ++f)
      if (rng() % 2 || (trial == 3)) {  // trial 3: every face flipped (inside out)
        std::swap(m.cells[f][1], m.cells[f][2]);
        ++flipped;
      }
    ASSERT_GT(flipped, 0);
    if (trial < 3) {
      EXPECT_FALSE(analyze_surface(m).consistently_oriented);
    }
    EXPECT_TRUE(orient_consistently(m));
    const SurfaceReport r = analyze_surface(m);
    EXPECT_TRUE(r.consistently_oriented);
    EXPECT_EQ(r.genus, 0);
    EXPECT_NEAR(signed_volume(m), v0, 1e-12);
    // Same orientation as the reference, face by face (as vertex sets in cyclic order).
    for (int f = 0; f < m.num_cells(); ++f) {
      const Vec3& p0 = m.points[m.cells[f][0]];
      const Vec3 n = (m.points[m.cells[f][1]] - p0).cross(m.points[m.cells[f][2]] - p0);
      const Vec3& q0 = ref.points[ref.cells[f][0]];
      const Vec3 nr = (ref.points[ref.cells[f][1]] - q0).cross(ref.points[ref.cells[f][2]] - q0);
      EXPECT_GT(n.dot(nr), 0.0);
      EXPECT_EQ(m.cells[f][0], ref.cells[f][0]);  // flips keep vertex 0
    }
  }
}

TEST(Orientation, QuadTorusInsideOut) {
  QuadMesh m = test::torus_quads(10, 6);
  const double v0 = signed_volume(m);
  ASSERT_GT(v0, 0.0);
  std::mt19937 rng(7);
  for (auto& c : m.cells)
    if (rng() % 3) std::reverse(c.begin() + 1, c.end());
  ASSERT_FALSE(analyze_surface(m).consistently_oriented);
  EXPECT_TRUE(orient_consistently(m));
  EXPECT_TRUE(analyze_surface(m).consistently_oriented);
  EXPECT_NEAR(signed_volume(m), v0, 1e-12 * v0);
}

TEST(Orientation, OpenSurfaceFollowsLowestFace) {
  TriMesh m = test::tri_grid(5);
  std::mt19937 rng(99);
  for (int f = 1; f < m.num_cells(); ++f)
    if (rng() % 2) std::swap(m.cells[f][1], m.cells[f][2]);
  // Flip face 0 too: the result must follow face 0 (normals -z), not the majority.
  std::swap(m.cells[0][1], m.cells[0][2]);
  EXPECT_TRUE(orient_consistently(m));
  for (int f = 0; f < m.num_cells(); ++f) {
    const Vec3& p0 = m.points[m.cells[f][0]];
    EXPECT_LT((m.points[m.cells[f][1]] - p0).cross(m.points[m.cells[f][2]] - p0).z(), 0.0);
  }
}

// --- validation -------------------------------------------------------------------------------

TEST(Validation, OutOfRangeIndexThrowsInputError) {
  TetMesh m = single_tet();
  m.cells[0][2] = 7;
  EXPECT_THROW(unique_edges(m), InputError);
  EXPECT_THROW(analyze_volume(m), InputError);
  EXPECT_THROW(boundary(m), InputError);
  m.cells[0][2] = -1;
  EXPECT_THROW(vertex_cells(m), InputError);
  TriMesh t = sphere(0);
  t.labels = {1, 2};
  EXPECT_THROW(analyze_surface(t), InputError);
}

TEST(Validation, FaceOfThreeCellsThrows) {
  TetMesh m;
  m.points = {Vec3(0, 0, 0), Vec3(1, 0, 0),  Vec3(0, 1, 0),
              Vec3(0, 0, 1), Vec3(0, 0, -1), Vec3(0.2, 0.2, 1)};
  m.cells = {{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}};
  try {
    (void)unique_faces(m);
    FAIL() << "expected GeometryError";
  } catch (const GeometryError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("3 cells (0, 1, 2)"), std::string::npos) << what;
  }
  EXPECT_THROW(boundary(m), GeometryError);
  const VolumeReport r = analyze_volume(m);  // reports, does not throw
  EXPECT_EQ(r.nonmanifold_faces, 1);
  EXPECT_EQ(r.components, 1);
}

TEST(Cleanup, RemoveUnreferencedPoints) {
  HexMesh m = hex_grid(2, 1, 1);
  m.cells.erase(m.cells.begin());  // the first hex: its 4 left vertices become unused
  m.labels = {3};
  const std::vector<Vec3> before = m.points;
  const HexMesh orig = m;
  const auto old_to_new = remove_unreferenced_points(m);
  EXPECT_EQ(m.num_points(), 8);
  EXPECT_EQ(std::count(old_to_new.begin(), old_to_new.end(), -1), 4);
  for (int k = 0; k < 8; ++k) EXPECT_EQ(m.points[m.cells[0][k]], before[orig.cells[0][k]]);
  EXPECT_EQ(m.labels, (std::vector<int>{3}));
  EXPECT_EQ(analyze_volume(m).isolated_vertices, 0);
  EXPECT_EQ(analyze_volume(orig).isolated_vertices, 4);
}

TEST(Boundary, LabelsFollowOwningCell) {
  HexMesh m = hex_grid(2, 1, 1);
  m.labels = {10, 20};
  const HexBoundary b = boundary(m);
  ASSERT_EQ(b.surface.labels.size(), b.surface.cells.size());
  for (std::size_t f = 0; f < b.cell_of_face.size(); ++f)
    EXPECT_EQ(b.surface.labels[f], m.labels[b.cell_of_face[f]]);
  EXPECT_EQ(b.surface.num_cells(), 10);
}

}  // namespace
}  // namespace polycube::core
