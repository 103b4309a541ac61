#pragma once
//! \file topology.h
//! \brief Topology computed on request: unique edges and faces, adjacency, boundary extraction,
//! connected components, surface and volume diagnosis, consistent orientation.
//!
//! Every function here is sort-based (O(n log n)) and deterministic: results never depend on
//! hash or allocation order. Local edge and face orders are those of elements.h.
//!
//! Conventions used by all functions:
//! - "cells" are the elements of a Mesh<T> (triangles/quads of a surface, tets/hexes of a volume);
//! - a surface's cells are also called faces; an edge of a surface is manifold when exactly two
//!   faces share it, boundary when one does, non-manifold when three or more do;
//! - functions that index per-vertex arrays check cell indices first and throw InputError when a
//!   cell references a vertex outside [0, #V) (see check_indices).

#include "core/elements.h"
#include "core/types.h"

#include <array>
#include <span>
#include <utility>
#include <vector>

namespace polycube::core {

// --- per-kind constants -----------------------------------------------------------------------

//! Number of edges of an element kind (3, 4, 6, 12).
constexpr int edge_count(CellType t) {
  switch (t) {
    case CellType::Triangle:
      return 3;
    case CellType::Quad:
      return 4;
    case CellType::Tetra:
      return 6;
    case CellType::Hexa:
      return 12;
  }
  return 0;
}

//! Number of faces of a volume element kind (4 for tets, 6 for hexes; 0 for surface kinds).
constexpr int face_count(CellType t) {
  return t == CellType::Tetra ? 4 : (t == CellType::Hexa ? 6 : 0);
}

//! Number of vertices of one face of a volume element kind (3 for tets, 4 for hexes).
constexpr int face_vertex_count(CellType t) {
  return t == CellType::Tetra ? 3 : (t == CellType::Hexa ? 4 : 0);
}

//! The surface cell kind of the faces of a volume kind (Tetra -> Triangle, Hexa -> Quad).
constexpr CellType face_cell_type(CellType t) {
  return t == CellType::Hexa ? CellType::Quad : CellType::Triangle;
}

//! Local edge table of a kind: kTriEdges, kQuadEdges, kTetEdges or kHexEdges.
template <CellType T>
constexpr const auto& local_edges() {
  if constexpr (T == CellType::Triangle)
    return kTriEdges;
  else if constexpr (T == CellType::Quad)
    return kQuadEdges;
  else if constexpr (T == CellType::Tetra)
    return kTetEdges;
  else
    return kHexEdges;
}

//! Local face table of a volume kind: kTetFaces or kHexFaces.
template <CellType T>
constexpr const auto& local_faces() {
  static_assert(dimension(T) == 3, "local_faces: volume kinds only");
  if constexpr (T == CellType::Tetra)
    return kTetFaces;
  else
    return kHexFaces;
}

// --- validation and clean-up ------------------------------------------------------------------

//! Check that every cell index lies in [0, #V) and that labels are empty or #C long.
//! \throw InputError naming the first offending cell and index.
template <CellType T>
void check_indices(const Mesh<T>& m);

//! Remove points no cell references, renumbering cells; the order of kept points is preserved.
//! \return old_to_new  #V_old, new index of each old point or -1 when removed
//! \throw InputError on out-of-range indices
template <CellType T>
std::vector<int> remove_unreferenced_points(Mesh<T>& m);

// --- unique edges and faces -------------------------------------------------------------------

//! Unique edges of a mesh of any kind.
template <CellType T>
struct EdgeTopology {
  static constexpr int kEdgesPerCell = edge_count(T);
  //! #E by 2 vertex pairs (a < b), sorted lexicographically. A cell with a repeated vertex
  //! (degenerate) can produce a self-loop edge (a == a); nothing else does.
  std::vector<std::array<int, 2>> edges;
  //! #C by kEdgesPerCell: edge ids of each cell in the local order of local_edges<T>().
  std::vector<std::array<int, kEdgesPerCell>> cell_edges;

  [[nodiscard]] int num_edges() const { return static_cast<int>(edges.size()); }
};

//! Unique edges of a mesh (any kind). O(C log C).
template <CellType T>
EdgeTopology<T> unique_edges(const Mesh<T>& m);

//! Unique faces of a volume mesh (tets -> triangle faces, hexes -> quad faces).
template <CellType T>
struct FaceTopology {
  static_assert(dimension(T) == 3, "FaceTopology: volume kinds only");
  static constexpr int kFacesPerCell = face_count(T);
  static constexpr int kFaceSize = face_vertex_count(T);
  using Face = std::array<int, kFaceSize>;

  //! #F faces, each with the vertex order it has in its first cell (outward for that cell when
  //! the cell is positively oriented). Numbered by first appearance, scanning cells in order and
  //! local faces in order.
  std::vector<Face> faces;
  //! #F by 2: the cells sharing each face; [0] is the first cell (the face's orientation owner),
  //! [1] the other cell or -1 on the boundary.
  std::vector<std::array<int, 2>> face_cells;
  //! #F by 2: local face index (into local_faces<T>()) of the face in face_cells[f][0] and
  //! face_cells[f][1] (-1 on the boundary).
  std::vector<std::array<int, 2>> face_local;
  //! #C by kFacesPerCell: face ids of each cell in the local order of local_faces<T>().
  std::vector<std::array<int, kFacesPerCell>> cell_faces;

  [[nodiscard]] int num_faces() const { return static_cast<int>(faces.size()); }
  [[nodiscard]] bool is_boundary(int fid) const { return face_cells[fid][1] < 0; }
};

//! Unique faces of a tet or hex mesh. O(C log C). Faces are identified by their vertex set.
//! \throw GeometryError when a face is shared by more than two cells (names the face's vertices
//!        and the cells)
template <CellType T>
FaceTopology<T> unique_faces(const Mesh<T>& m);

// --- adjacency --------------------------------------------------------------------------------

//! Compressed adjacency lists (CSR): the items of i are items[offsets[i] .. offsets[i+1]).
struct Adjacency {
  std::vector<int> offsets{0};  //!< size()+1 increasing offsets, offsets[0] == 0
  std::vector<int> items;       //!< offsets.back() items

  //! Items of entry i.
  [[nodiscard]] std::span<const int> operator[](int i) const {
    return {items.data() + offsets[i], static_cast<std::size_t>(offsets[i + 1] - offsets[i])};
  }
  //! Number of entries.
  [[nodiscard]] int size() const { return static_cast<int>(offsets.size()) - 1; }
  //! Number of items of entry i.
  [[nodiscard]] int degree(int i) const { return offsets[i + 1] - offsets[i]; }
};

//! Adjacency from (entry, item) pairs: `entries` entries, each with its items sorted and each
//! item once.
Adjacency adjacency_from_pairs(int entries, std::vector<std::pair<int, int>> pairs);

//! Vertex -> incident cells (#V entries, cells sorted, each cell once).
//! \throw InputError on out-of-range indices
template <CellType T>
Adjacency vertex_cells(const Mesh<T>& m);

//! Edge -> incident cells (#E entries, cells sorted, each cell once).
template <CellType T>
Adjacency edge_cells(const EdgeTopology<T>& et);

//! Vertex -> neighbouring vertices through edges (1-ring; #V entries = num_points, sorted,
//! self-loops of degenerate cells skipped).
template <CellType T>
Adjacency vertex_vertices(const EdgeTopology<T>& et, int num_points);

//! Cell -> neighbouring cells (sorted, each once): surfaces through shared edges (including
//! non-manifold ones), volumes through shared faces. The same relation as connected_components.
template <CellType T>
Adjacency cell_cells(const Mesh<T>& m);

// --- boundary ---------------------------------------------------------------------------------

//! Boundary of a tet mesh as a triangle surface, outward for positively oriented tets.
struct TetBoundary {
  TriMesh surface;                //!< boundary vertices only; labels = owning cell's label if any
  std::vector<int> vertex_map;    //!< #Vs: volume vertex of each surface vertex (increasing)
  std::vector<int> cell_of_face;  //!< #Fs: volume cell owning each boundary face
  std::vector<int> local_face;    //!< #Fs: its local face index (kTetFaces)
};

//! Boundary of a hex mesh as a quad surface, outward for positively oriented hexes.
struct HexBoundary {
  QuadMesh surface;               //!< boundary vertices only; labels = owning cell's label if any
  std::vector<int> vertex_map;    //!< #Vs: volume vertex of each surface vertex (increasing)
  std::vector<int> cell_of_face;  //!< #Fs: volume cell owning each boundary face
  std::vector<int> local_face;    //!< #Fs: its local face index (kHexFaces)
};

//! Faces of exactly one cell, ordered by cell then local face; each with its local vertex order.
//! \throw GeometryError when a face is shared by more than two cells
//! \throw InputError on out-of-range indices
TetBoundary boundary(const TetMesh& m);

//! The boundary triangles of `b` in volume vertex indices (outward, in `b`'s face order).
std::vector<Tri> boundary_triangles(const TetBoundary& b);
HexBoundary boundary(const HexMesh& m);

// --- components -------------------------------------------------------------------------------

//! Connected components of cells.
struct Components {
  int count = 0;
  //! #C component id of each cell; components numbered by their lowest cell (cell 0 is in 0).
  std::vector<int> cell_component;
};

//! Components of cells: surfaces connected through shared edges, volumes through shared faces
//! (a shared vertex alone does not connect).
template <CellType T>
Components connected_components(const Mesh<T>& m);

// --- surface diagnosis ------------------------------------------------------------------------

//! Full diagnosis of a triangle or quad surface.
struct SurfaceReport {
  int vertices = 0;              //!< #V (all points, referenced or not)
  int faces = 0;                 //!< #F
  int edges = 0;                 //!< unique edges
  int components = 0;            //!< face components through shared edges
  int boundary_edges = 0;        //!< edges of exactly one face
  int boundary_loops = 0;        //!< connected components of the boundary-edge graph
  int nonmanifold_edges = 0;     //!< edges of three or more faces
  int nonmanifold_vertices = 0;  //!< vertices whose faces form more than one edge-connected fan
  int degenerate_faces = 0;      //!< repeated vertex index or (near-)zero area, see analyze_surface
  int isolated_vertices = 0;     //!< points no face references
  bool closed = false;           //!< no boundary edge (and at least one face)
  bool manifold = false;         //!< edge- and vertex-manifold
  bool orientable = false;       //!< a consistent orientation exists (through manifold edges)
  bool consistently_oriented = false;  //!< every manifold edge is traversed once each way
  int euler_characteristic = 0;        //!< V - E + F with V = referenced vertices only
  //! Sum over components of (2 - chi_c) / 2 when the surface is closed, manifold and
  //! orientable; -1 otherwise.
  int genus = -1;
};

//! Diagnose a TriMesh or QuadMesh. A face is degenerate when it repeats a vertex index or when
//! its area is at most 1e-12 times its longest edge squared (quads: norm of the vector area of
//! the split 0-1-2, 0-2-3).
//! \throw InputError on out-of-range indices
template <CellType T>
SurfaceReport analyze_surface(const Mesh<T>& m);

//! Orient the faces of a TriMesh or QuadMesh consistently, component by component: the lowest
//! face of each component keeps its orientation and the others follow by BFS across manifold
//! edges; then each closed component is flipped, if needed, so its enclosed signed volume is
//! positive (outward normals). Flipping reverses the vertex order keeping vertex 0.
//! \return false, leaving the mesh unchanged, when a component is non-orientable or has a
//!         non-manifold edge; true otherwise
//! \throw InputError on out-of-range indices
template <CellType T>
bool orient_consistently(Mesh<T>& m);

//! Signed volume enclosed by a closed surface (divergence theorem, positive for outward normals;
//! quads split 0-1-2, 0-2-3). Computed relative to the bounding-box centre for accuracy.
double signed_volume(const TriMesh& m);
double signed_volume(const QuadMesh& m);

// --- volume diagnosis -------------------------------------------------------------------------

//! Diagnosis of a tet or hex mesh.
struct VolumeReport {
  int vertices = 0;           //!< #V (all points)
  int cells = 0;              //!< #C
  int edges = 0;              //!< unique edges
  int faces = 0;              //!< unique faces
  int boundary_faces = 0;     //!< faces of exactly one cell
  int nonmanifold_faces = 0;  //!< faces of three or more cells (the mesh is broken when > 0)
  int components = 0;         //!< cell components through shared faces
  int isolated_vertices = 0;  //!< points no cell references
  //! Cells with non-positive orientation: tets with signed volume <= 0, hexes with any corner
  //! Jacobian determinant (kHexCornerNeighbors) <= 0.
  int inverted_cells = 0;
  int euler_characteristic = 0;  //!< V - E + F - C with V = referenced vertices only
  SurfaceReport boundary;        //!< report of the boundary surface (faces of exactly one cell)
};

//! Diagnose a volume mesh. Does not throw on non-manifold faces: they are counted and left out
//! of the boundary.
//! \throw InputError on out-of-range indices
VolumeReport analyze_volume(const TetMesh& m);
VolumeReport analyze_volume(const HexMesh& m);

}  // namespace polycube::core
