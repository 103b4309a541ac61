#pragma once
//! \file types.h
//! \brief Index-based mesh types shared by every module (ARCHITECTURE §4).
//!
//! Connectivity is kept apart from geometry: a mesh is a vector of points and a vector of
//! fixed-size index arrays, plus optional per-element integer labels. Topology (edges, faces,
//! adjacency) is computed on request by topology.h, never stored here.

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace polycube::core {

using Vec3 = Eigen::Vector3d;

//! Element kinds. The local vertex orderings are in elements.h.
enum class CellType { Triangle, Quad, Tetra, Hexa };

//! Number of vertices of an element kind.
constexpr int vertex_count(CellType t) {
  switch (t) {
    case CellType::Triangle: return 3;
    case CellType::Quad: return 4;
    case CellType::Tetra: return 4;
    case CellType::Hexa: return 8;
  }
  return 0;
}

//! Dimension of an element kind (2 for surface cells, 3 for volume cells).
constexpr int dimension(CellType t) {
  return (t == CellType::Triangle || t == CellType::Quad) ? 2 : 3;
}

//! Human-readable name ("triangle", "quad", "tet", "hex").
const char* cell_type_name(CellType t);

//! A mesh made of one element kind.
//! \tparam T element kind; cells are arrays of vertex_count(T) indices into points.
template <CellType T>
struct Mesh {
  static constexpr CellType cell_type = T;
  static constexpr int N = vertex_count(T);
  using Cell = std::array<int, N>;

  std::vector<Vec3> points;  //!< #V vertex positions
  std::vector<Cell> cells;   //!< #C cells, indices into points (orderings: elements.h)
  std::vector<int> labels;   //!< empty, or #C integer labels (MEDIT references)

  [[nodiscard]] int num_points() const { return static_cast<int>(points.size()); }
  [[nodiscard]] int num_cells() const { return static_cast<int>(cells.size()); }
  [[nodiscard]] bool empty() const { return cells.empty(); }
};

using TriMesh = Mesh<CellType::Triangle>;
using QuadMesh = Mesh<CellType::Quad>;
using TetMesh = Mesh<CellType::Tetra>;
using HexMesh = Mesh<CellType::Hexa>;

using Tri = TriMesh::Cell;
using Quad = QuadMesh::Cell;
using Tet = TetMesh::Cell;
using Hex = HexMesh::Cell;

//! A named scalar field over points or cells (written as VTK point/cell data).
struct Field {
  std::string name;
  std::vector<double> values;  //!< one value per point, or per cell
};

//! Everything one mesh file can hold: shared points and one block per element kind.
//!
//! This is what readers return and writers take. Cell data index the cells of all blocks in
//! the fixed order triangles, quads, tets, hexes (concatenated, empty blocks skipped), which is
//! also the order VTK and Gmsh files are written in.
struct MeshData {
  std::vector<Vec3> points;
  std::vector<int> point_labels;  //!< empty or #V (MEDIT vertex references)

  std::vector<std::array<int, 2>> edges;
  std::vector<int> edge_labels;
  std::vector<Tri> triangles;
  std::vector<int> triangle_labels;
  std::vector<Quad> quads;
  std::vector<int> quad_labels;
  std::vector<Tet> tets;
  std::vector<int> tet_labels;
  std::vector<Hex> hexes;
  std::vector<int> hex_labels;

  std::vector<Field> point_data;  //!< each with #V values
  std::vector<Field> cell_data;   //!< each with num_cells() values (order: see above)

  //! Number of 2D and 3D cells (edges are not counted).
  [[nodiscard]] std::size_t num_cells() const {
    return triangles.size() + quads.size() + tets.size() + hexes.size();
  }
};

//! Wrap one element block of a MeshData as a Mesh (copies points; labels kept if present).
TriMesh triangles_of(const MeshData& d);
QuadMesh quads_of(const MeshData& d);
TetMesh tets_of(const MeshData& d);
HexMesh hexes_of(const MeshData& d);

//! Build a MeshData holding one mesh.
template <CellType T>
MeshData to_mesh_data(const Mesh<T>& m);

//! Axis-aligned bounding box of a point set.
struct BoundingBox {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(0.0);
  [[nodiscard]] Vec3 extent() const { return max - min; }
  [[nodiscard]] double diagonal() const { return (max - min).norm(); }
};

//! Bounding box of points (all zero when empty).
BoundingBox bounding_box(const std::vector<Vec3>& points);

//! Is tet c strictly positively oriented at positions P (floating point, not an exact predicate)?
bool positive_tet(const std::vector<Vec3>& P, const Tet& c);

}  // namespace polycube::core
