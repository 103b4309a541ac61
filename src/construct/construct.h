#pragma once
//! \file construct.h
//! \brief The whole polycube construction (ARCHITECTURE §6.2): tetrahedralize, label, repair
//! the labeling, deform, untangle, certify. The result is a certified core::PolycubeMap or an
//! exception with the reason; an uncertified map is never returned.

#include "construct/certify.h"
#include "construct/coarse_surface.h"
#include "construct/deform.h"
#include "construct/fine_surface.h"
#include "construct/labeling.h"
#include "construct/labeling_repair.h"
#include "construct/orientation.h"
#include "construct/predeform.h"
#include "construct/tetrahedralize.h"
#include "core/polycube_map.h"
#include "core/types.h"
#include "solve/untangle.h"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace polycube::construct {

//! One run of labeling, repair and deformation in construct's plan (see construct_from_prepared()).
struct Attempt {
  int predeform_iterations = 0;   //!< pre-deformation the labeling and the deformation start from (0: none)
  int unfold_moves = 0;           //!< ConstructOptions::unfold_moves of this attempt
  double compactness = 1.0;       //!< the labeling's compactness
  bool retry = false;             //!< of the pre-deformed pass (ConstructOptions::predeform_retry)
  [[nodiscard]] std::string name() const;  //!< e.g. "pre-deformed, compactness 2"
  friend bool operator==(const Attempt&, const Attempt&) = default;
};

//! Options of construct_polycube(). The first group is what a user sets; the rest are expert
//! settings of the steps (ARCHITECTURE §6.2), documented with the `construct --help-expert`
//! options that bind them.
struct ConstructOptions {
  TetrahedralizeOptions tetrahedralize;  //!< surface inputs only
  LabelingOptions labeling;              //!< fidelity/compactness trade-off
  //! Normal-driven pre-deformation: the labeling reads the normals of the pre-deformed
  //! surface, and the deformation starts from its positions (iterations 0: off).
  PredeformOptions predeform;
  //! Rotate the model so its normals cluster on the axes (orientation.h) before the labeling;
  //! the map keeps the input's model positions, the polycube is in the rotated frame.
  bool align_axes = true;
  //! Budget of the attempts, in seconds since the construction started (0: none). An attempt
  //! with others still planned stops (its untangling ends at its best state) halfway through
  //! what is left, the last one at the budget; no attempt starts past it. The best attempt is
  //! then certified, or the failure lists what was tried. A run that reaches the budget depends
  //! on the machine's speed; with 0 the result never does.
  double time_limit = 1800;
  //! Called when an attempt's deformation starts: (1-based index, attempts planned, the
  //! attempt, seconds since the construction started). For progress lines.
  std::function<void(int, int, const Attempt&, double)> on_attempt;

  // Expert settings.
  //! When `predeform` is off: plan the attempts a second time on a model pre-deformed by this
  //! many iterations (0: never), with at least `predeform_retry_unfold_moves` unfolding moves.
  int predeform_retry = 30;
  int predeform_retry_unfold_moves = 50;
  RepairOptions repair;                  //!< its `energy` is replaced by `labeling`
  DeformOptions deform;
  CertifyOptions certify;
  //! When the deformation leaves failures, the labeling is computed again with the
  //! compactness multiplied by each of these factors in turn (empty: no retry).
  std::vector<double> retry_compactness_factors{2.0, 0.5};
  //! After the repair, at most this many local relabellings against the folds of the fast
  //! polycube estimate (unfold_labeling(); 0: none). The pre-deformed retry uses at least
  //! `predeform_retry_unfold_moves`; in the first attempts it can trade a certifiable
  //! labeling for one that is not.
  int unfold_moves = 0;
  //! After the repair, at most this many local relabellings that remove backward steps of the
  //! chart boundaries (turning_points.h), measured on the pre-deformed surface when there is
  //! one (0: none).
  int straighten_moves = 0;
  //! Surface inputs: when TetGen's mesh (without a volume bound) has fewer tets than this, the
  //! surface is tetrahedralized again with a volume bound asking for about this many (0: never).
  int min_tets = 10000;
  //! Surface inputs: a surface of more triangles than `max_triangles` is decimated to
  //! `decimate_to` triangles before the tetrahedralization (fine_surface.h; 0: never), no vertex
  //! of the result farther from it than `decimation_tolerance` times its bounding-box diagonal.
  //! A hex mesh of H hexes has about 6 H^(2/3) boundary faces: 20,000 triangles are over four per
  //! face at 20,000 hexes. Only surfaces at least twice that fine are decimated: on a surface
  //! near the count the collapses would save little, and every collapse changes the labeling's
  //! input.
  int max_triangles = 40000;
  int decimate_to = 20000;
  double decimation_tolerance = 1e-3;
  //! Surface inputs: when no attempt reaches a valid labeling and an edge is longer than the
  //! bounding-box diagonal over this, every triangle is split into four until none is, and the
  //! construction starts again (coarse_surface.h; 0: never).
  double coarse_edge_ratio = 20.0;
  //! Steer the labeling so that every vertex at least as sharp as a cube's corner becomes a
  //! polycube corner (tip_corners.h). Construct turns it on for the surface it refined as too
  //! coarse, whose vertices are all features of the input; on a fine surface a sharp vertex is
  //! as likely to be noise.
  bool tip_corners = false;
  int max_attempts = 8;             //!< deformations in all, at most
  //! Testing only: the first this many deformed attempts count as failed whatever they gave,
  //! so the tests reach the fallback attempts and the budget on small inputs (the hidden
  //! `construct --inject-failure attempt-N`).
  int inject_failed_attempts = 0;
  //! Testing only: the first this many attempts that certify are refused as not certified
  //! (`construct --inject-failure uncertified-attempt-N`).
  int inject_uncertified_attempts = 0;
};

//! The attempts construct plans: the compactness schedule (1, then the retry factors) on the
//! options' labeling; then, when no pre-deformation was asked for, the same schedule on a
//! pre-deformed labeling. Construct labels them all, then deforms the first, then the others
//! in order of their labelings' promise (the fast estimate's folded area; the plan's order
//! between equals) until one gives a valid map.
std::vector<Attempt> plan_attempts(const ConstructOptions& options);

//! Wall time of each stage (seconds).
struct ConstructTimes {
  double decimate = 0;        //!< decimation of a surface finer than needed (fine_surface.h)
  double tetrahedralize = 0;  //!< TetGen + boundary refinement (or input preparation)
  double predeform = 0;       //!< normal-driven pre-deformation
  double label = 0;           //!< graph cut, its repair to validity and the estimate (cut_and_repair)
  double repair = 0;          //!< local moves on the deformed attempt's labeling (unfold, straighten)
  double deform = 0;          //!< chart constraints + linear (ARAP) step
  double untangle = 0;        //!< elliptic untangling and distortion reduction
  double certify = 0;         //!< exact certification + distortion measures
  double total = 0;
};

//! Result of construct_polycube(): a certified map and its figures.
struct ConstructResult {
  core::PolycubeMap map;            //!< certified
  std::vector<core::Tri> boundary;  //!< #B boundary triangles in core::boundary() order (outward)
  std::vector<int> labels;          //!< #B labels of `boundary`
  Certificate certificate;          //!< certified() is true
  int tetgen_tets = 0;              //!< tets made by TetGen (0 for tet-mesh inputs)
  RefineStats refine;               //!< boundary refinement work
  int split_triangles = 0;          //!< boundary triangles split by the deformation
  int split_edges = 0;              //!< boundary edges split by the deformation
  int split_faces = 0;              //!< interior faces split around vertices that see one chart plane only
  int refined_edges = 0;            //!< edges split by the local refinement of the untangling
  bool boundary_first = false;      //!< the map came from the boundary-first placement (boundary_first.h)
  int charts = 0;                   //!< charts of the final labeling
  int corners = 0;                  //!< polycube corners
  int boundaries = 0;               //!< polycube edges (chart boundaries)
  double fidelity = 0;              //!< area-weighted mean of 1 − n·axis (model normals)
  int repair_moves = 0;             //!< moves made by the labeling repair of the kept attempt
  double cut_compactness = 0;       //!< compactness of the kept attempt's graph cut: below the attempt's when
                                    //!< the looser cut was valid without repair (cut_and_repair)
  Attempt attempt;                  //!< the attempt whose map this is
  int attempts = 0;                 //!< attempts deformed
  std::string tried;                //!< why the other attempts failed ("; "-separated; empty: none did)
  PredeformResult predeform;        //!< figures of the kept attempt's pre-deformation (points cleared)
  AxisRotation axis_rotation;       //!< rotation applied before the labeling (identity: none)
  int inverted_after_linear = 0;    //!< tets inverted after the linear step (before untangling)
  solve::UntangleResult untangle;   //!< elliptic optimization report
  double isometric_average = 0;     //!< volume-weighted mean isometric distortion (volume-normalized)
  double isometric_max = 0;         //!< max isometric distortion (volume-normalized)
  double conformal_average = 0;
  double conformal_max = 0;
  ConstructTimes seconds;
  SurfaceRefinement coarse_refinement;  //!< surface inputs too coarse for the labeling (levels 0: none)
  SurfaceDecimation decimation;         //!< surface inputs finer than needed: the map is of the decimated solid
  int tip_corners = 0;                  //!< sharp tips made polycube corners (ConstructOptions::tip_corners)
};

//! No attempt reached a valid labeling (the defects of the first are in the message).
class NoValidLabeling : public core::SolverError {
 public:
  using core::SolverError::SolverError;
};

//! The map could not be certified: carries the best (uncertified) attempt for diagnosis, so a
//! caller can show where it failed (never to be used as a result).
class NotCertified : public core::GeometryError {
 public:
  NotCertified(const std::string& what, core::PolycubeMap map, std::vector<core::Tri> boundary, std::vector<int> labels)
      : core::GeometryError(what), map_(std::move(map)), boundary_(std::move(boundary)), labels_(std::move(labels)) {}
  [[nodiscard]] const core::PolycubeMap& map() const { return map_; }
  [[nodiscard]] const std::vector<core::Tri>& boundary() const { return boundary_; }  //!< volume indices
  [[nodiscard]] const std::vector<int>& labels() const { return labels_; }            //!< one per boundary triangle

 private:
  core::PolycubeMap map_;
  std::vector<core::Tri> boundary_;
  std::vector<int> labels_;
};

//! Construct a certified polycube map of the volume bounded by a closed surface.
//! \throw core::InputError when the surface is open, non-manifold, self-intersecting, ...
//! \throw core::SolverError when no valid labeling is reached (names the remaining defects)
//! \throw NotCertified (a core::GeometryError) when the map cannot be certified (with the
//!        certificate's reason and the best attempt)
ConstructResult construct_polycube(const core::TriMesh& surface, const ConstructOptions& options = {});

//! Same from a tet mesh (checked and oriented by prepare_tet_mesh, then refine_boundary).
ConstructResult construct_polycube(core::TetMesh mesh, const ConstructOptions& options = {});

//! Label, repair, deform and certify a prepared tet mesh (boundary refined, positively
//! oriented): the first attempt of plan_attempts(), then, when it fails, the others, labeled and
//! deformed most promising first until one leaves a valid map (or the time limit or
//! max_attempts is reached); the attempt with the fewest failures is kept and certified.
//! \throw as construct_polycube
ConstructResult construct_from_prepared(const core::TetMesh& mesh, const ConstructOptions& options = {});

}  // namespace polycube::construct
