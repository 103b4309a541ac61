#pragma once
//! \file tetrahedralize.h
//! \brief Tetrahedralization of a closed surface with TetGen, and the boundary refinement that
//! makes every boundary labeling realizable (ARCHITECTURE §6.2 step 1).
//!
//! After refinement a tet mesh satisfies two properties:
//! - no tet has more than one boundary facet;
//! - no interior edge joins two boundary vertices (an edge is interior when it is not an edge of
//!   a boundary triangle).
//! Otherwise a polycube deformation could be forced to flatten a tet.

#include "core/errors.h"
#include "core/types.h"

#include <string>

namespace polycube::construct {

//! TetGen failed on a surface that check_closed_surface() accepts: an error code, or an abort on
//! one of its internal checks (it runs in a process of its own, so the abort stays there).
class TetgenFailed : public core::GeometryError {
 public:
  using core::GeometryError::GeometryError;
};

//! Options of tetrahedralize().
struct TetrahedralizeOptions {
  //! Bound on the radius-edge ratio of the tets (TetGen -q); 0 disables quality refinement.
  //! Values below ~1.1 may not terminate in TetGen and are clamped to 1.1.
  double quality = 2.0;
  //! Bound on the volume of a tet as a fraction of the bounding-box volume (TetGen -a);
  //! 0 = no bound. Tets touching a coarse surface may stay larger: the surface is kept as it
  //! is (no Steiner point on it), which limits the refinement next to it.
  double max_volume = 0.0;
  //! Apply refine_boundary() to TetGen's output (default on; off only for diagnosis).
  bool refine = true;
};

//! What the boundary refinement did.
struct RefineStats {
  int split_edges = 0;  //!< interior edges joining two boundary vertices split at their midpoint
  int split_tets = 0;   //!< tets with several boundary facets split at their centroid
};

//! Result of tetrahedralize().
struct TetrahedralizeResult {
  //! The tet mesh, positively oriented; its boundary triangles are the input triangles (TetGen's
  //! -Y flag: no Steiner point on the surface).
  core::TetMesh mesh;
  int tetgen_tets = 0;  //!< tets made by TetGen before the refinement
  RefineStats refine;   //!< the refinement's work
};

//! Counts of the two boundary defects refine_boundary() removes.
struct BoundaryDefects {
  int tets_with_several_boundary_facets = 0;
  int interior_edges_between_boundary_vertices = 0;
  [[nodiscard]] bool ok() const {
    return tets_with_several_boundary_facets == 0 && interior_edges_between_boundary_vertices == 0;
  }
};

//! Refuse a surface that cannot be tetrahedralized: empty, out-of-range or degenerate faces,
//! open (boundary edges), non-manifold edges or vertices, non-orientable, or self-intersecting
//! (CGAL exact predicates).
//! \throw core::InputError naming the first reason found (with counts)
void check_closed_surface(const core::TriMesh& surface);

//! Tetrahedralize the volume enclosed by a closed, manifold surface with TetGen, preserving the
//! surface (no Steiner point on the boundary), then refine_boundary().
//! \param surface  #V points and #F triangles (any consistent orientation)
//! \throw core::InputError when check_closed_surface() refuses the surface
//! \throw TetgenFailed when TetGen fails (its reason is in the message)
TetrahedralizeResult tetrahedralize(const core::TriMesh& surface,
                                    const TetrahedralizeOptions& options = {});

//! Check a tet mesh given as input and orient it positively: refuses an empty mesh,
//! out-of-range indices, faces shared by three or more tets, flat tets, a mix of positive and
//! negative tets, and a boundary that is not a closed manifold surface.
//! \throw core::InputError with the reason
void prepare_tet_mesh(core::TetMesh& mesh);

//! Split tets and edges until no tet has several boundary facets and no interior edge joins two
//! boundary vertices. Inserted points are interior (edge midpoints, tet centroids); the boundary
//! triangles are unchanged; positively oriented tets stay positively oriented.
//! \pre mesh is a valid tet mesh (see prepare_tet_mesh)
RefineStats refine_boundary(core::TetMesh& mesh);

//! Count the defects refine_boundary() removes (for reports and tests).
BoundaryDefects boundary_defects(const core::TetMesh& mesh);

}  // namespace polycube::construct
