#pragma once
//! \file ghost_tets.h
//! \brief Ghost tets of a labeled boundary: one per boundary triangle, the triangle and an apex
//! at height h above the triangle's chart plane along its label (ARCHITECTURE §6.2 step 5).
//!
//! With the apex's label-axis coordinate tied to the chart plane, a ghost tet is positive
//! exactly when its triangle faces its label. The untangling's barrier then keeps the boundary
//! from folding over itself (a triangle turning to face away from its label), which the real
//! tets alone do not see: every real tet can be positive while the boundary is folded. Every
//! stage that untangles a map with its charts on planes (the deformation, the planarity flow,
//! the local repair, the boundary-first placement and the simplification's fit) builds its
//! ghost tets here; each ties the apexes to its own variables.

#include "core/types.h"

#include <vector>

namespace polycube::mapping {

//! Where a ghost apex sits above its triangle.
enum class GhostBase {
  Centroid,     //!< above the triangle's centroid
  FirstVertex,  //!< above the triangle's first vertex (a lifted triangle: the tet's Jacobian is
                //!< the triangle's 2D Jacobian plus the unit normal)
};

//! The direction of a ghost apex in the reference shape.
enum class GhostDirection {
  Normal,  //!< the reference triangle's unit normal (the reference is the model)
  Label,   //!< the label's axis direction (the reference is a polycube already)
};

//! Ghost tets of a set of boundary triangles.
struct GhostTets {
  std::vector<core::Tet> tets;          //!< #B (t0, t1, t2, first_apex + f): positive when t faces its label
  std::vector<core::Vec3> reference;    //!< #B apex positions of the reference shapes
};

//! Build the ghost tets of `tris`.
//! \param points      #V reference positions of the triangles' vertices
//! \param tris        #B outward boundary triangles (indices into points)
//! \param labels      #B labels in 0..5
//! \param h           apex height (length of `points`)
//! \param first_apex  vertex index of the first apex (apex f gets first_apex + f)
GhostTets ghost_tets(const std::vector<core::Vec3>& points, const std::vector<core::Tri>& tris,
                     const std::vector<int>& labels, double h, int first_apex, GhostBase base = GhostBase::Centroid,
                     GhostDirection direction = GhostDirection::Normal);

//! Where the apex's label-axis coordinate is measured from.
enum class ApexLift {
  FromChartPlane,  //!< the first vertex's coordinate (exact when the chart is on its plane)
  FromBase,        //!< the base point's own coordinate (for charts not yet planar)
};

//! Start position of the apex of triangle t with `label` in positions P: the base point, its
//! label-axis coordinate lifted by h along the label.
core::Vec3 ghost_apex(const std::vector<core::Vec3>& P, const core::Tri& t, int label, double h,
                      GhostBase base = GhostBase::Centroid, ApexLift lift = ApexLift::FromChartPlane);

//! Mean boundary edge length of `tris` in `points`, times `fraction` (0 when fraction <= 0): the
//! ghost height as a fraction of the boundary's resolution.
double ghost_height(const std::vector<core::Vec3>& points, const std::vector<core::Tri>& tris, double fraction);

}  // namespace polycube::mapping
