#pragma once
//! \file polycube_map.h
//! \brief The polycube map: one tet connectivity carrying two geometries (ARCHITECTURE §4).
//!
//! A polycube map f: S -> P is stored piecewise linearly on a tetrahedral mesh: tet t maps
//! model-space tet (model[tets[t][0]], ..., model[tets[t][3]]) affinely onto polycube-space tet
//! (polycube[tets[t][0]], ...). The map is valid when no tet is inverted or flat in either
//! space and the polycube-space boundary is a closed surface made of axis-aligned triangles
//! (checked by structure::validate_map). On disk it is two MEDIT files with identical
//! Tetrahedra blocks (io/polycube_map_io.h).

#include "core/types.h"

#include <vector>

namespace polycube::core {

//! One tet connectivity with model-space and polycube-space vertex positions.
struct PolycubeMap {
  std::vector<Tet> tets;    //!< #T tets, indices into both position arrays (orderings: elements.h)
  std::vector<Vec3> model;  //!< #V model-space positions
  std::vector<Vec3> polycube;  //!< #V polycube-space positions (same length as model)

  [[nodiscard]] int num_vertices() const { return static_cast<int>(model.size()); }
  [[nodiscard]] int num_tets() const { return static_cast<int>(tets.size()); }

  //! The model-space tet mesh (copies the positions).
  [[nodiscard]] TetMesh model_mesh() const;
  //! The polycube-space tet mesh (copies the positions).
  [[nodiscard]] TetMesh polycube_mesh() const;
};

//! Axis labels of the field's convention: 0..5 = +X, -X, +Y, -Y, +Z, -Z.
//! label = 2 * axis + (sign < 0 ? 1 : 0).
constexpr int axis_label(int axis, int sign) { return 2 * axis + (sign < 0 ? 1 : 0); }
constexpr int label_axis(int label) { return label / 2; }
constexpr int label_sign(int label) { return (label % 2 == 0) ? 1 : -1; }
//! "+X", "-X", "+Y", "-Y", "+Z", "-Z" (or "?" outside 0..5).
const char* label_name(int label);
//! "x", "y", "z" (or "?" outside 0..2).
const char* axis_name(int axis);

//! The label of the opposite direction (+X <-> -X, ...).
constexpr int opposite_label(int label) { return label ^ 1; }
//! Unit direction of a label (0..5).
Vec3 label_direction(int label);
//! Triangle t (indices into P) faces the direction of `label` strictly in positions P: its
//! normal has a positive component along the label's direction.
bool faces_label(const std::vector<Vec3>& P, const Tri& t, int label);

//! Label of the axis closest to a direction: the dominant component of n and its sign
//! (ties go to the lower axis). A zero vector gives +X.
int dominant_axis_label(const Vec3& n);

//! Build a map from two tet meshes. Only the sizes are checked here (connectivity equality and
//! validity are the callers' checks: io::read_polycube_map, structure::validate_map).
//! \throw InputError when the point counts differ or the connectivities differ (names the first
//!        differing tet)
PolycubeMap make_polycube_map(const TetMesh& model, const TetMesh& polycube);

//! Check the sizes and indices of a map: same number of model and polycube positions, at least
//! one tet, every index in [0, #V), every coordinate finite.
//! \throw InputError naming the first problem
void check_map_indices(const PolycubeMap& map);

}  // namespace polycube::core
