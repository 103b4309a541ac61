#pragma once
//! \file label_surface.h
//! \brief The labeling stage on its own (ARCHITECTURE §6.2 steps 1–3): tetrahedralize a closed
//! surface (or prepare a given tet mesh), optionally pre-deform it, label its boundary by graph
//! cut, repair the labeling to validity, and score the result with the fast polycube estimate.
//! This is what `polycube label` runs; construct_polycube() runs the same steps inside its plan
//! of attempts, followed by the deformation.

#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/polycube_estimate.h"
#include "construct/predeform.h"
#include "construct/tetrahedralize.h"
#include "core/topology.h"
#include "core/types.h"

#include <vector>

namespace polycube::construct {

//! Options of label_surface().
struct LabelSurfaceOptions {
  TetrahedralizeOptions tetrahedralize;  //!< surface inputs only
  //! Normal-driven pre-deformation (iterations 0: off). When on, the fidelity term of the
  //! labeling reads the normals of the pre-deformed surface (`labeling.data_normals` is
  //! replaced), as in construct_polycube().
  PredeformOptions predeform;
  LabelingOptions labeling;  //!< fidelity/compactness trade-off, boundary smoothing
  RepairOptions repair;      //!< its `energy` is replaced by the labeling options actually used
};

//! Wall time of the steps (seconds).
struct LabelSurfaceTimes {
  double tetrahedralize = 0;    //!< TetGen + boundary refinement (or input preparation)
  double label_and_repair = 0;  //!< pre-deformation (when on), graph cut and repair
};

//! Result of label_surface(). The labeling may be invalid: valid() says so and `check.defects`
//! gives every remaining defect with its reason.
struct LabelSurfaceResult {
  core::TetMesh mesh;  //!< #V points, #T tets: positively oriented, boundary refined, no labels
  //! The mesh's boundary: `surface` (#B triangles, outward; the indices of `check`'s corners
  //! and defect vertices refer to its points) and `vertex_map` (volume vertex of each of them).
  core::TetBoundary boundary;
  std::vector<core::Tri> boundary_triangles;  //!< #B boundary triangles in volume vertex indices
  std::vector<int> labels;                    //!< #B repaired labels, in {0..5}
  std::vector<int> initial_labels;            //!< #B labels of the graph cut, before the repair
  LabelingCheck check;                        //!< charts, corners, boundaries and defects of `labels`
  int initial_defects = 0;                    //!< defects of `initial_labels`
  int repair_moves = 0;                       //!< moves accepted by the repair
  double fidelity = 0;                        //!< labeling_fidelity() of `labels` (model normals)
  double fidelity_before_repair = 0;          //!< labeling_fidelity() of `initial_labels`
  PolycubeEstimate estimate;                  //!< fast polycube estimate of `labels`
  //! Figures of the pre-deformation and its #V positions (empty points and zero figures when off).
  PredeformResult predeform;
  int tetgen_tets = 0;  //!< tets made by TetGen (0 for tet-mesh inputs)
  RefineStats refine;   //!< boundary refinement work
  LabelSurfaceTimes seconds;
  [[nodiscard]] bool valid() const { return check.valid(); }
};

//! Tetrahedralize the volume bounded by a closed surface, then label and repair its boundary.
//! Deterministic.
//! \param surface  #V points, #F triangles: closed, manifold, not self-intersecting
//! \throw core::InputError when the surface cannot be tetrahedralized (check_closed_surface())
//! \throw core::GeometryError when TetGen fails or the pre-deformation meets a flat tet
//! \throw core::SolverError when a linear system of the pre-deformation cannot be factorized
//! An invalid labeling is not an error: see LabelSurfaceResult::valid().
LabelSurfaceResult label_surface(const core::TriMesh& surface, const LabelSurfaceOptions& options = {});

//! Same from a tet mesh: checked and oriented by prepare_tet_mesh(), then refine_boundary().
//! Its labels are ignored.
//! \throw core::InputError when prepare_tet_mesh() refuses the mesh; otherwise as above
LabelSurfaceResult label_surface(core::TetMesh mesh, const LabelSurfaceOptions& options = {});

}  // namespace polycube::construct
