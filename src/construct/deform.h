#pragma once
//! \file deform.h
//! \brief Deformation of a labeled tet mesh into a polycube (ARCHITECTURE §6.2 steps 4–5):
//! every chart planar at one shared coordinate along its axis, distortion as low as possible,
//! no inverted tet.
//!
//! Steps:
//! 1. charts and chart groups (mapping/labeled_mesh.h): the coordinate of each chart along its
//!    label's axis is one unknown shared by all its vertices (charts of one axis that touch at a
//!    vertex share it too). These are exact constraints (solve::LinearReduction).
//! 2. boundary edges inside a chart whose two ends are tied to one chart coordinate of an
//!    in-plane axis (a chord joining two points of one polycube edge: the chart would have to
//!    fold over that edge) are split at their midpoint, and boundary triangles whose three
//!    vertices are tied that way are split at their centroid (the tets around are split too;
//!    this keeps the mesh conforming and positively oriented); then the interior faces around
//!    an interior vertex whose neighbours all lie on one chart plane are split at their
//!    centroid (the plane would flatten every tet around it); then, at each polycube corner,
//!    the edges opposite the corner in a chart's fan are split until the fan has
//!    DeformOptions::min_fan triangles (a chart may have to open to 270° at a corner);
//! 3. the first polycube (mapping/first_polycube.h): as-rigid-as-possible least squares, or the
//!    foldover-free planarity flow;
//! 4. the repairs in order until one leaves a valid map (mapping/): the boundary-first
//!    placement (by default first), the global elliptic untangling of Garanzha et al. 2021
//!    with the model tets as references (it also lowers the distortion while staying
//!    foldover-free), the local repair of what it leaves; when tets stay inverted, the edges of
//!    those tets are split (local refinement) and the round restarts from the current positions
//!    (DeformOptions::refine_rounds).
//! The polycube coordinate of a chart vertex along the chart's axis equals the chart's unknown
//! bit for bit.

#include "core/errors.h"
#include "core/types.h"
#include "mapping/first_polycube.h"
#include "mapping/untangle_map.h"
#include "solve/untangle.h"

#include <string>
#include <utility>
#include <vector>

namespace polycube::construct {

//! When the boundary-first placement (mapping/boundary_first.h) is tried.
enum class BoundaryFirst {
  Off,           //!< never
  AfterRepairs,  //!< when the global untangling and the local repairs leave failures
  First,         //!< right after the first polycube; the untangling and the repairs are the fallback
};

//! The elliptic optimization's settings for a deformation: a small initial ε, since no
//! coordinate is fixed (a large ε would make a shrunken polycube cheap); a small positive
//! min det target, which keeps the exact certification away from round-off; and a stall rule,
//! since stuck tets creep towards det 0 forever.
solve::UntangleOptions deform_untangle_defaults();

//! Options of deform_to_polycube().
struct DeformOptions {
  mapping::FirstPolycubeOptions first;                     //!< step 3
  solve::UntangleOptions untangle = deform_untangle_defaults();  //!< step 4
  mapping::LocalRepairOptions local_repair;                //!< when the untangling leaves failures
  BoundaryFirst boundary_first = BoundaryFirst::First;
  //! When the boundary-first placement leaves tets inverted, split their edges and place
  //! again, at most this many times.
  int boundary_first_refinements = 3;
  //! The free-boundary optimization after a valid boundary-first placement stops at this
  //! fraction of `untangle.tolerance` (the energy is dominated by the many good tets while the
  //! few bad ones still improve), after at most this many outer iterations.
  double boundary_first_relax_tolerance = 0.01;
  int boundary_first_relax_iterations = 40;
  //! When tets stay inverted, split the edges of those tets and optimize again, at most this
  //! many times.
  int refine_rounds = 1;
  //! At every polycube corner, split boundary edges until each chart's fan around the corner
  //! has at least this many triangles (0 or 1: never), so a chart can open to 270° there.
  int min_fan = 4;
  //! Height of the ghost tets (mapping/ghost_tets.h) as a fraction of the mean boundary edge
  //! length; 0 = no ghost tets (and no boundary-first placement).
  double ghost_height = 0.5;
};

//! Result of deform_to_polycube().
struct DeformResult {
  core::TetMesh mesh;                       //!< the model tet mesh (refined when triangles were split)
  std::vector<core::Tri> boundary;          //!< #B outward boundary triangles (volume indices)
  std::vector<int> labels;                  //!< #B labels in {0..5}
  std::vector<core::Vec3> polycube;         //!< #V polycube positions
  std::vector<int> triangle_chart;          //!< #B chart of each boundary triangle
  int num_charts = 0;                       //!< charts (edge-connected, one label)
  int num_chart_variables = 0;              //!< chart coordinates after merging touching charts
  int split_triangles = 0;                  //!< boundary triangles split by step 2
  int split_faces = 0;                      //!< interior faces split around locked vertices (step 2)
  int split_edges = 0;                      //!< boundary edges split by step 2
  int split_fan_edges = 0;                  //!< boundary edges split to widen corner fans
  int refined_edges = 0;                    //!< edges split by the local refinement of step 4
  int reopened_fans = 0;                    //!< flipped corner fans placed on their long sweep
  bool boundary_first = false;              //!< the map came from the boundary-first placement
  solve::UntangleResult untangle;           //!< the elliptic optimization's report
  int inverted_after_linear = 0;            //!< tets inverted after the linear step
  int flow_iterations = 0;                  //!< outer iterations of the planarity flow (0: ARAP)
  double flow_residual = 0;                 //!< its final plane residual (local edge lengths)
  double seconds_linear = 0;                //!< time of steps 1–3
  double seconds_untangle = 0;              //!< time of step 4
};

//! The labeling cannot be realized by any polycube of this mesh (two vertices forced onto one
//! point, triangles forced onto a polycube edge): vertices() names the volume vertices where.
class UnrealizableLabeling : public core::GeometryError {
 public:
  UnrealizableLabeling(const std::string& what, std::vector<int> vertices)
      : core::GeometryError(what), vertices_(std::move(vertices)) {}
  [[nodiscard]] const std::vector<int>& vertices() const { return vertices_; }

 private:
  std::vector<int> vertices_;
};

//! Deform a tet mesh with a labeled boundary into a polycube.
//! \param mesh      positively oriented tet mesh (#V, #T)
//! \param boundary  its boundary triangles (#B, volume vertex indices, any order and orientation)
//! \param labels    #B labels in {0..5} = {+X, −X, +Y, −Y, +Z, −Z}
//! \param initial   optional #V starting positions (e.g. predeform()): they give the chart
//!                  coordinates' first values and the first rotations of the linear step
//! \throw core::InputError when boundary is not exactly the set of boundary faces of mesh, or a
//!        label is out of range
//! \throw UnrealizableLabeling when the labeling forces two distinct vertices onto one point
//!        (names them); an untangling failure is NOT thrown: check result.untangle.untangled
//!        (and certify the map, certify.h)
DeformResult deform_to_polycube(const core::TetMesh& mesh, const std::vector<core::Tri>& boundary,
                                const std::vector<int>& labels, const DeformOptions& options = {},
                                const std::vector<core::Vec3>* initial = nullptr);

}  // namespace polycube::construct
