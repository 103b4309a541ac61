#pragma once
//! \file hex_optimize.h
//! \brief Hex-mesh optimization (ARCHITECTURE §6.5): untangling and quality improvement of a hex
//! mesh whose boundary stays on a target surface and its sharp features.
//!
//! Every hex contributes its 8 corner tetrahedra (corner + its three neighbours,
//! core::kHexCornerNeighbors), whose determinants are the corner Jacobians, to the elliptic
//! energy of solve/untangle.h (Garanzha et al. 2021), each with a right-angled (ideal cube)
//! corner of the input corner's edge lengths as reference, and its centre tet (centre_frames.h,
//! lighter), so that the barrier guards all 9 points of Verdict's scaled Jacobian. Boundary
//! vertices are attracted to the target:
//! - corner vertices (junctions of the hex boundary's sharp-edge graph near a target corner)
//!   are fixed at that corner;
//! - feature vertices (on sharp hex boundary edges near a target feature line) are attracted to
//!   the closest point of the feature lines, so they slide along them;
//! - other boundary vertices are attracted to the closest point of the target surface.
//! Attraction targets are re-projected after every outer iteration (CGAL AABB trees).
//!
//! Phases: (1) untangling, when a corner is inverted, until none is; (2) quality rounds: the
//! same energy with the barrier kept (no step may invert a corner) and, from round to round,
//! larger weights on the hexes of lowest scaled Jacobian, to raise the minimum. A round is kept
//! only when it raises the minimum scaled Jacobian without lowering the average below the one
//! at the start of the phase (less OptimizeOptions::average_slack after untangling) (or, while tangled, when it leaves fewer inverted hexes).
//! (3) on a valid result, the polish of the worst hexes' interior vertices (polish.h).
//! Deterministic: same input and options, same output bit for bit.

#include "core/types.h"
#include "optimize/polish.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include <optional>

namespace polycube::optimize {

//! Options of optimize_hex_mesh().
struct OptimizeOptions {
  //! Strength of the attraction of boundary vertices to the target (dimensionless): a vertex at
  //! distance d from its target costs surface_weight · (d/h)² times its hexes' reference
  //! volume, h the local edge length. Larger keeps the boundary closer, smaller frees the shape.
  double surface_weight = 100.0;
  int untangle_iterations = 200;  //!< outer iterations of the untangling phase at most
  //! Floor of σ in the untangling's ε update (solve::UntangleOptions::min_sigma): ε falls up to
  //! twice as fast per outer iteration as with the paper's 0.1. A gridded or padded mesh's
  //! tangle is mostly a few folded hexes in a valid grid, which unfold on the way; where the
  //! faster fall stiffens the barrier before a squashed boundary has unfolded, `run` optimizes
  //! that gridding again with 0.1 (pipeline/optimize_stage.h). bench/RESULTS.md, stops 55–56.
  double untangle_min_sigma = 0.2;
  //! When > 0, the untangling first frees only the vertices of the hexes within this many rings
  //! of the hexes with an inverted corner or centre, the rest of the mesh fixed as it is, and
  //! runs on the whole mesh only when that leaves any inverted. For a mesh that was optimized
  //! before a local change (a padding layer just inserted): the global untangling would first
  //! relax the whole mesh under a soft barrier, at the cost of a whole optimization, only to
  //! have the quality rounds optimize it again. 0: the whole mesh at once.
  int local_untangle_rings = 0;
  int quality_rounds = 6;         //!< quality rounds (each reweights the worst hexes)
  int quality_iterations = 15;    //!< outer iterations per quality round at most
  //! The quality rounds stop once this many in a row after round 0 were neither kept nor higher
  //! in mSJ than the round before them (0: all quality_rounds run). Each round weighs the same worst hexes
  //! heavier: rounds that are not kept but climb may lead to one that is; after a round that
  //! falls, the next (heavier still) fell too on every shared shape, so one is enough
  //! (bench/RESULTS.md, stop 56: the same files on all 17, the optimizer's time 0.82).
  int quality_patience = 1;
  //! After an untangling phase, quality rounds may lower the average scaled Jacobian by this
  //! much (a valid input's average is never lowered).
  double average_slack = 0.01;
  double volume_weight = 1.0;     //!< λ of the elliptic energy (solve::UntangleOptions)
  bool features = true;           //!< preserve the target's sharp edges and corners
  //! A target edge is sharp when its faces' normals make an angle above this (degrees); the
  //! same threshold classifies the hex mesh's boundary edges.
  double feature_angle = 40.0;
  //! A hex boundary vertex is matched with a target feature line or corner only within this
  //! many local edge lengths.
  double feature_distance = 0.5;
  //! Newton systems with at most this many unknowns are solved by sparse Cholesky, larger ones
  //! by truncated conjugate gradients (a factorization grows too costly on large meshes).
  int cholesky_max_variables = 30000;
  int cg_iterations = 100;  //!< CG iterations per Newton step (large meshes)
  //! Weight of the boundary orientation barrier (optimize/boundary_lift.h) relative to a hex
  //! corner: boundary quad corners lifted along the target normal must stay positive, so the
  //! boundary cannot fold over itself between positive hexes. 0 turns it off.
  double boundary_barrier = 1.0;
  //! After the quality rounds and the final snap, when the boundary's Hausdorff distance to the
  //! target exceeds hausdorff_bound (relative to the target's bounding-box diagonal; the thesis's
  //! 0.9 %, §4.5), the boundary vertices farther from the target than drift_diagonal (same units)
  //! get a 16 times stiffer attraction and the quality optimization runs again from before the
  //! rounds (at most drift_retries times, stopping once within the bound; a retry is kept only
  //! when it lowers the Hausdorff distance): there the surface is a constraint, not something to
  //! trade for the minimum scaled Jacobian. Only for meshes valid on input. The heavier weights
  //! of the worst hexes can pull their boundary vertices off the target where the snap cannot
  //! put them back; one stiffening is not always enough on a coarse curved boundary, whose
  //! drifted set shrinks from one retry to the next. Meshes within the bound never retry, since a
  //! retry costs mSJ. The vertex threshold is half the bound: chords add to a vertex's drift.
  double hausdorff_bound = 0.009;
  double drift_diagonal = 0.0045;
  int drift_retries = 3;
  //! How far the reference size of each hex moves from its input size towards one size for the
  //! whole mesh (0: keep the input's grading, 1: ask every hex for the same volume). Each
  //! corner's three reference edge lengths are scaled by (L / h)^size_uniformity, h the hex's
  //! mean edge length and L chosen so the total reference volume is the input's. Gridded
  //! polycube meshes inherit the map's distortion: where the map compresses the model, hexes are
  //! long and their boundary faces cut chords off the surface; a uniform reference lets the
  //! boundary vertices slide along the surface towards those regions.
  double size_uniformity = 0.0;
  //! Weight of the attraction of every boundary quad's centre to the target, relative to a
  //! vertex's (optimize/face_attraction.h); 0 turns it off. With it, the boundary fits the
  //! surface (vertices may leave it by a fraction of the chord) instead of interpolating it,
  //! and the final snap of the vertices onto the target is skipped.
  double face_attraction = 0.0;
  //! When the result (valid) is still beyond hausdorff_bound after the drift retries, the
  //! quality rounds run again from their start with the quad centres attracted with this
  //! weight (face_attraction), kept when that lowers the Hausdorff distance; 0: no fit retry.
  //! Curved and creased surfaces gain most (figures in bench/RESULTS.md).
  double fit_retry = 1.0;
  //! When the valid start of the rounds, with every boundary vertex put on the target, is beyond
  //! fit_first_margin times hausdorff_bound, the fit retry would run anyway and the plain rounds
  //! before it be thrown away: the rounds then attract the quad centres from the start (the same
  //! result as the fit retry's when that is kept). 0: always the plain rounds first.
  double fit_first_margin = 1.0;
  //! Weight of each hex's centre tet (optimize/centre_frames.h) relative to one of its corner
  //! tets; 0 turns it off (then a hex may keep positive corners around a negative centre).
  double centre_weight = 0.1;
  //! Stop before the quality rounds when the untangled mesh's boundary crosses itself
  //! (OptimizeResult::stopped_crossing): the rounds keep the crossings (they only move the
  //! boundary along the target), so a caller that tries again with a stiffer boundary barrier
  //! when the result crosses itself (pipeline/optimize_stage.h) does not wait for them.
  bool stop_when_untangled_crosses = false;
  //! Last, on a valid result: the vertices of the worst hexes moved one at a time to raise the
  //! minimum scaled Jacobian around them (optimize/polish.h), the interior ones first, then the
  //! boundary ones along the target (kept within the Hausdorff bound, without crossings).
  bool polish = true;
};

//! Work of one phase.
struct PhaseReport {
  int iterations = 0;    //!< outer iterations
  int newton_steps = 0;  //!< Newton steps
  double seconds = 0;    //!< wall time
};

//! Result of optimize_hex_mesh().
struct OptimizeResult {
  quality::ScaledJacobianSummary before;  //!< scaled Jacobian of the input (no per-hex values)
  quality::ScaledJacobianSummary after;   //!< ... of the result
  int inverted_before = 0;  //!< corner and centre Jacobians <= 0 at the start (9 per hex)
  int inverted_after = 0;   //!< ... at the end
  bool untangled = false;   //!< no corner or centre Jacobian <= 0 at the end
  int boundary_vertices = 0;              //!< attracted to the surface (features included)
  int feature_vertices = 0;               //!< sliding on target feature lines
  int corner_vertices = 0;                //!< fixed at target corners
  int target_feature_edges = 0;           //!< sharp edges found on the target
  int target_corners = 0;                 //!< corners found on the target
  int rounds_accepted = 0;                //!< quality rounds kept
  int rounds_run = 0;  //!< quality rounds run, the fit retry's included (quality_patience may stop them early)
  int drift_retries = 0;                  //!< optimizations run again for drifted boundary vertices
  bool fit_retry = false;                 //!< the fit retry (quad centres attracted) was kept
  //! With stop_when_untangled_crosses: the untangled boundary crossed itself, and the mesh is
  //! the untangled one (no quality rounds ran).
  bool stopped_crossing = false;
  //! The result's boundary distance to the target, when the optimizer measured it for the
  //! points it returns (the drift and fit retries do): a caller need not measure it again.
  std::optional<quality::SurfaceDistance> distance;
  PhaseReport setup, untangle, quality;
  PolishResult polish;  //!< the polish of the worst hexes (sweeps 0: not run)
  double seconds = 0;  //!< total wall time
};

//! Untangle and optimize a hex mesh in place, its boundary kept on the target surface.
//! \param mesh   #H hexes (orientation of core/elements.h); points are updated
//! \param target closed triangle surface the boundary must follow
//! \throw core::InputError on an empty mesh, out-of-range indices, a target without
//!        non-degenerate triangles, or bad options
//! \throw core::SolverError when the sparse factorization fails beyond repair
OptimizeResult optimize_hex_mesh(core::HexMesh& mesh, const core::TriMesh& target, const OptimizeOptions& options = {});

}  // namespace polycube::optimize
