#include "core/types.h"

#include <Eigen/Geometry>

#include <algorithm>

namespace polycube::core {

const char* cell_type_name(CellType t) {
  switch (t) {
    case CellType::Triangle: return "triangle";
    case CellType::Quad: return "quad";
    case CellType::Tetra: return "tet";
    case CellType::Hexa: return "hex";
  }
  return "?";
}

namespace {
template <CellType T, class Cells>
Mesh<T> wrap(const MeshData& d, const Cells& cells, const std::vector<int>& labels) {
  Mesh<T> m;
  m.points = d.points;
  m.cells = cells;
  if (labels.size() == cells.size()) m.labels = labels;
  return m;
}
}  // namespace

TriMesh triangles_of(const MeshData& d) {
  return wrap<CellType::Triangle>(d, d.triangles, d.triangle_labels);
}
QuadMesh quads_of(const MeshData& d) { return wrap<CellType::Quad>(d, d.quads, d.quad_labels); }
TetMesh tets_of(const MeshData& d) { return wrap<CellType::Tetra>(d, d.tets, d.tet_labels); }
HexMesh hexes_of(const MeshData& d) { return wrap<CellType::Hexa>(d, d.hexes, d.hex_labels); }

template <CellType T>
MeshData to_mesh_data(const Mesh<T>& m) {
  MeshData d;
  d.points = m.points;
  if constexpr (T == CellType::Triangle) {
    d.triangles = m.cells;
    d.triangle_labels = m.labels;
  } else if constexpr (T == CellType::Quad) {
    d.quads = m.cells;
    d.quad_labels = m.labels;
  } else if constexpr (T == CellType::Tetra) {
    d.tets = m.cells;
    d.tet_labels = m.labels;
  } else {
    d.hexes = m.cells;
    d.hex_labels = m.labels;
  }
  return d;
}
template MeshData to_mesh_data(const TriMesh&);
template MeshData to_mesh_data(const QuadMesh&);
template MeshData to_mesh_data(const TetMesh&);
template MeshData to_mesh_data(const HexMesh&);

bool positive_tet(const std::vector<Vec3>& P, const Tet& c) {
  return (P[c[1]] - P[c[0]]).dot((P[c[2]] - P[c[0]]).cross(P[c[3]] - P[c[0]])) > 0;
}

BoundingBox bounding_box(const std::vector<Vec3>& points) {
  BoundingBox b;
  if (points.empty()) return b;
  b.min = b.max = points.front();
  for (const Vec3& p : points) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  }
  return b;
}

}  // namespace polycube::core
