#pragma once
//! \file deform.h
//! \brief Deformation of a labeled tet mesh into a polycube (ARCHITECTURE §6.2 steps 4–5):
//! every chart planar at one shared coordinate along its axis, distortion as low as possible,
//! no inverted tet.
//!
//! Steps:
//! 1. charts = edge-connected boundary triangles with one label; the coordinate of each chart
//!    along its label's axis is one unknown shared by all its vertices (charts of one axis that
//!    touch at a vertex share it too). These are exact constraints (solve::LinearReduction).
//! 2. boundary edges inside a chart whose two ends are tied to one chart coordinate of an
//!    in-plane axis (a chord joining two points of one polycube edge: the chart would have to
//!    fold over that edge) are split at their midpoint, and boundary triangles whose three
//!    vertices are tied that way are split at their centroid (the tets around are split too;
//!    this keeps the mesh conforming and positively oriented); then, at each polycube corner,
//!    the edges opposite the corner in a chart's fan are split until the fan has
//!    DeformOptions::min_fan triangles (a chart may have to open to 270° at a corner);
//! 3. an as-rigid-as-possible least-squares solve (local rotations, one sparse factorization)
//!    gives a first polycube;
//! 4. the elliptic energy of Garanzha et al. 2021 (solve/untangle.h), with the model tets as
//!    references, untangles it and then lowers the distortion while staying foldover-free;
//!    when tets stay inverted, the edges of those tets are split (local refinement) and the
//!    optimization restarts from the current positions (DeformOptions::refine_rounds).
//! The polycube coordinate of a chart vertex along the chart's axis equals the chart's unknown
//! bit for bit.

#include "construct/planarity_flow.h"
#include "core/errors.h"
#include "core/types.h"
#include "solve/untangle.h"

#include <string>
#include <utility>
#include <vector>

namespace polycube::construct {

//! Options of deform_to_polycube().
struct DeformOptions {
  int arap_iterations = 15;        //!< local/global iterations of the first (linear) step
  int max_iterations = 150;        //!< outer iterations of the elliptic optimization
  int newton_steps = 2;            //!< Newton steps per outer iteration
  double volume_weight = 1.0;      //!< λ of the elliptic energy (volume term)
  //! Initial ε of the elliptic energy: small, since no coordinate is fixed (a large ε would
  //! make a shrunken polycube cheap).
  double initial_epsilon = 0.05;
  double tolerance = 1e-4;         //!< relative energy decrease that stops the optimization
  //! Minimum det J (relative to the model tet) that counts as untangled: a small positive
  //! margin keeps the exact certification away from round-off.
  double min_det = 1e-6;
  //! When tets stay inverted, split the edges of those tets and optimize again, at most this
  //! many times.
  int refine_rounds = 1;
  //! The untangling gives up when, for 20 outer iterations, the inverted tets neither get
  //! fewer nor their min det rises by this much (stuck tets creep towards det 0 forever).
  double stall_min_det_rise = 0.005;
  //! At every polycube corner, split boundary edges until each chart's fan around the corner
  //! has at least this many triangles (0 or 1: never), so a chart can open to 270° there.
  int min_fan = 4;
  //! Height of the ghost tets (one per boundary triangle, apex above its chart plane; they
  //! keep the boundary from folding over itself), as a fraction of the mean boundary edge
  //! length; 0 = no ghost tets.
  double ghost_height = 0.5;
  //! First polycube by the foldover-free planarity flow (planarity_flow.h) instead of the
  //! as-rigid-as-possible least squares.
  bool flow = false;
  //! When the untangling leaves failures, first place the chart fans that stayed flipped at
  //! concave corners on their long sweep (corner_fans.h), then untangle locally.
  bool reopen_fans = true;
  //! When the local repairs leave failures, build the polycube boundary first (edge chains
  //! straight between their corners, charts untangled in 2D inside them), then the volume with
  //! the boundary fixed (boundary_first.h).
  bool boundary_first = true;
  //! When the boundary-first placement leaves tets inverted, split their edges and place
  //! again, at most this many times.
  int boundary_first_refinements = 3;
  //! Place the boundary first right after the first polycube (the free-boundary untangling,
  //! then the local repairs, are the fallback when it fails); false: only after them.
  bool boundary_first_start = true;
  //! The free-boundary optimization after a valid boundary-first placement stops at this
  //! fraction of `tolerance` (the energy is dominated by the many good tets while the few bad
  //! ones still improve), after at most this many outer iterations.
  double boundary_first_relax_tolerance = 0.01;
  int boundary_first_relax_iterations = 40;
  PlanarityFlowOptions flow_options;
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
