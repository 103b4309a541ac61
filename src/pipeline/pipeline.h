#pragma once
//! \file pipeline.h
//! \brief The whole chain as one call (`polycube run`, issue "end to end"): construct a
//! certified polycube map, simplify it (corner alignment), grid it into a hex mesh and a quad
//! surface mesh, optimize the hex mesh, measure. Every intermediate result is written to the
//! output folder as soon as its stage ends, so a failure keeps what earlier stages produced.
//!
//! Output folder:
//!   construct/model.mesh, construct/polycube.mesh   the certified map (construct convention)
//!   simplify/model.mesh, simplify/polycube.mesh     the simplified map (unless disabled)
//!   hex.mesh                                        the gridded hex mesh (model space)
//!   hex_optimized.mesh                              after optimization (unless disabled); when
//!                                                   the optimize stage fell back to padding, the
//!                                                   padded mesh
//!   hex_padded.mesh, hex_padded.vtk                 the padded mesh (padding requested, or the
//!                                                   optimize stage's fallback); the VTK has the
//!                                                   cell fields padding_layer and source_hex
//!   hex_quality.vtk                                 the final hex mesh, cell data
//!                                                   scaled_jacobian and block_id (ParaView)
//!   quad.vtk                                        the surface quad mesh, cell data
//!                                                   scaled_jacobian and patch_id
//!   parts/                                          the solid cut into parts along the map
//!                                                   (on request: pipeline/parts_output.h)
//! (report.json and the summary table are the caller's: see RunResult.)

#include "construct/construct.h"
#include "fabricate/decompose.h"
#include "fabricate/printing.h"
#include "mesh/grid.h"
#include "optimize/hex_optimize.h"
#include "padding/padding.h"
#include "repair/repair.h"
#include "simplify/simplify.h"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace polycube::pipeline {

//! Options of run_pipeline().
struct RunOptions {
  repair::RepairOptions repair;  //!< the repairs asked for beyond the default ones (repair/repair.h)
  construct::ConstructOptions construct;
  //! When no construction attempt on a surface can be certified, construct its alpha wrap
  //! (pipeline/input.h: construct_with_wrap_fallback); the mesh then fits the wrap, and the
  //! final report also gives its distance to the surface as read.
  bool wrap_fallback = true;
  bool simplify = true;                    //!< run the simplification (corner alignment)
  simplify::SimplifyOptions simplify_options;
  int target_hexes = 20000;                //!< about this many hexes (> 0)
  mesh::GridSizing grid_sizing = mesh::GridSizing::Uniform;  //!< cells per chart interval (mesh/grid.h)
  bool optimize = true;                    //!< optimize the gridded hex mesh
  optimize::OptimizeOptions optimize_options;
  //! When the optimized mesh fails the fold-over check: when only its boundary crosses itself,
  //! optimize the grid again with a stiffer boundary barrier; then pad the first result
  //! selectively, then globally, and optimize again;
  //! then grid the map again with its own sizing, then twice as fine, and optimize each
  //! (hex.mesh and quad.vtk are replaced). A valid mesh of the first grid farther from the input
  //! than optimize_options.hausdorff_bound: grid twice as fine, keep it when valid and closer.
  //! The steps and why: pipeline/optimize_stage.h.
  bool optimize_fallbacks = true;
  //! Before twice as fine, the distance fallback grids the map with twice the cells in the unit
  //! slabs of the polycube that hold the points where the mesh misses the input (`run
  //! --refine-far`). Off by default: on fandisk it reaches the bound with a fifth fewer hexes
  //! than twice as fine but a lower mSJ (0.027 against 0.048), and cheburashka's refined grid does
  //! not untangle (bench/RESULTS.md, stop 51).
  bool refine_far = false;
  //! Padding after the optimization (stage "pad"): none, a layer under the whole boundary, or
  //! selective (where the map distorts the shape).
  padding::PaddingMode padding = padding::PaddingMode::Selective;
  //! The padded mesh replaces the optimized one only when its mSJ stays at or above the
  //! unpadded mesh's or at or above this (padding is for the boundary hexes; it must not cost
  //! the quality a mesh is used for); otherwise it is still written (hex_padded.*) but not used.
  double padding_usable_min_sj = 0.5;
  padding::PadOptions padding_options;
  padding::AnalysisOptions padding_analysis;    //!< selective padding's mapping analysis
  padding::SelectionOptions padding_selection;  //!< selective padding's binary problem
  //! Selective padding: where the plan at padding_selection.lambda pads every boundary facet,
  //! also plan at λ = 0 and keep the padded mesh with the higher mSJ (stage_steps.h,
  //! pad_with_fewest_hexes; `--padding-lambda auto`)
  bool padding_fewest_too = true;
  //! When the chain ends without a valid mesh (optimize), or its final mesh is farther from the
  //! input than optimize_options.hausdorff_bound, or its mSJ is nearly 0, run the chain again
  //! with a more faithful labeling and keep the better valid mesh (pipeline/labeling_fallback.h;
  //! `--no-labeling-fallback` turns it off)
  bool labeling_fallback = true;
  //! Mesh the map (stages hexmesh, optimize, pad, quality); false: the map only (and its parts).
  bool hexmesh = true;
  //! Cut the input solid into parts along the (simplified) map: stage "fabricate", right after
  //! the simplification, writing the folder parts/.
  bool fabricate = false;
  fabricate::DecomposeOptions fabricate_options;
  fabricate::PrintOptions fabricate_print;  //!< the printing check of the parts
  int fabricate_mill_directions = 40;        //!< the 4-axis milling check's tool directions
  //! Called when a stage starts: (1-based index, number of stages, name).
  std::function<void(int, int, const std::string&)> on_stage;
  //! Fault injection, for tests of the failure handling only (the hidden `--inject-failure`
  //! option of `polycube run`): the stage of this name fails as soon as it starts, with a
  //! core::GeometryError "injected failure", exactly as a stage that could not reach a result;
  //! "simplify-step-N": the first N steps of the simplification count as failed (its
  //! fallbacks, simplify.h); "optimize-step-N" (N in 1..5): the first N optimized meshes count
  //! as failing the fold-over check (optimize_fallbacks); "optimize-crossing-N": the first N
  //! count as meshes whose boundary crosses itself (the stiffer barrier's retry first);
  //! "construct-unwrapped": the construction of the surface as read counts as not certified (the
  //! wrap fallback); "construct-attempt-1": its first deformed attempt counts as failed (the next
  //! planned attempt, or on a surface with gaps the wrap closes, the wrap); "optimize-distance-N": the first N valid meshes count as too far from the input (1: the
  //! first finer grid of step 5 is kept; 2: it is not closer, so the next one is tried (with
  //! refine_far; without it the first mesh stays); 3 with refine_far: the first mesh stays);
  //! "final-distance" / "final-quality": the completed chain's mesh counts as beyond the
  //! distance bound / poor in mSJ (the labeling fallback). Empty (the default): never.
  std::string inject_failure;
};

//! One stage's record.
struct StageRecord {
  std::string name;
  double seconds = 0.0;
  bool ok = false;
};

//! The chain's retry with a more faithful labeling (pipeline/labeling_fallback.h).
struct LabelingFallback {
  bool tried = false;
  //! "optimize" (no valid mesh), "distance" (beyond the bound) or "quality" (mSJ below kPoorMinSJ)
  std::string reason;
  std::string failure_first;   //!< the first chain's failed stage and reason ("optimize" only)
  bool kept = false;           //!< the retry's result is the run's
  double compactness = -1;     //!< the retry's labeling compactness
  int charts_first = -1, charts_retry = -1;          //!< charts of each labeling (-1: not constructed)
  double distance_first = -1, distance_retry = -1;  //!< final meshes to the input / its diagonal (-1: none)
  double msj_first = -2, msj_retry = -2;            //!< final meshes' mSJ (-2: none)
  std::string why_not;         //!< why the retry was not kept (empty when kept)
};

//! What the chain did. When a stage failed, `failed_stage` names it, `failure` gives the
//! reason, and the figures of the later stages keep their "not computed" values (-1).
struct RunResult {
  std::vector<StageRecord> stages;
  std::string failed_stage;  //!< empty when every stage succeeded
  std::string failure;       //!< the reason, one line
  std::vector<std::string> repairs;  //!< what the default repairs changed in the input surface
  //! The failure is the input file's fault (exit code 2): an InputError of the stages that read
  //! and process the file ("input", "construct"). A later stage's InputError (the chain's own
  //! intermediate result, or a request such as a target hex count whose lattice is too large for
  //! this polycube) is a stage that could not reach a result (exit code 3). A file that cannot
  //! be written (core::OutputError) is exit code 2 in any stage.
  bool bad_input = false;
  std::vector<std::string> files;  //!< files written, in order

  // construct
  int tets = -1, charts = -1, corners = -1;
  double isometric_average = -1, isometric_max = -1;
  std::string construct_attempt;       //!< the construction attempt whose map was kept
  int construct_attempts = -1;         //!< attempts deformed
  std::string construct_fallback;      //!< "" or what construct fell back to ("alpha wrap (...)")
  std::string construct_fallback_why;  //!< why: the surface as read could not be certified
  int input_triangles = -1;            //!< triangles of the surface input (-1: a tet mesh)
  int decimated_triangles = 0;         //!< the surface decimated for the construction to this many (0: not)
  int coarse_levels = 0;               //!< times a surface too coarse to label was split into four
  int coarse_triangles = -1;           //!< its triangles after that (-1: not refined)
  int coarse_tip_corners = 0;          //!< its sharp tips made polycube corners
  // simplify (#D, #dom before/after; without simplification both are the map's own counts)
  std::string simplify_step;           //!< the step that gave the map (simplify::step_name, or "unsimplified")
  std::vector<std::string> simplify_tried;  //!< why the earlier steps failed
  int frozen_corners = -1;             //!< corners the "fewer alignments" step froze
  int hex_domains_before = -1, hex_domains_after = -1;
  int quad_domains_before = -1, quad_domains_after = -1;
  // hexmesh
  double grid_scale = -1;
  //! Empty, or why the gridding fell back to the map's own sizing ("map sizing (<why>)")
  std::string grid_sizing_fallback;
  int hexes = -1, quads = -1;
  int inverted_gridded = -1;           //!< hexes inverted in model space right after gridding
  double msj_gridded = -2, asj_gridded = -2;
  // optimize / final mesh
  int iterations_optimize = -1;
  std::string optimize_fallback = "none";   //!< the gridding whose optimized mesh passed ("none": the first)
  std::vector<std::string> optimize_tried;  //!< why the earlier griddings' results failed
  // padding (requested, or the optimize stage's fallback)
  //! "none", "global", "selective", "none (nothing to pad)", "<mode> (optimize fallback)", or
  //! "<mode> (not kept: ...)" when the padded mesh lost quality (see kPaddingUsableMinSJ)
  std::string padding = "none";
  double msj_unpadded = -2, msj_padded = -2;  //!< requested padding: mSJ before and after
  int padding_hard_facets = -1;        //!< selective: |HF|
  bool padding_plan_optimal = false;   //!< selective: the binary problem was solved to optimality
  double padding_plan_gap = -1;        //!< selective: relative gap to the best bound (0 when optimal)
  std::string padding_plan_solver;     //!< selective: what solved the binary problem (solve/milp.h)
  double padding_analysis_seconds = -1, padding_solve_seconds = -1;  //!< selective: the plan's two steps
  int padding_selected_facets = -1;    //!< selective: |PF|
  int padding_edge_turns = -1, padding_vertex_turns = -1;  //!< selective: turns of the new layer
  int padding_added = -1;              //!< hexes of the new layer
  //! selective: what the plan at λ = 0 gave where the plan at the options' λ padded every boundary
  //! facet (RunOptions::padding_fewest_too); empty when it was not planned
  std::string padding_fewest_hexes;
  int singular_vertices_before = -1, singular_edges_before = -1;  //!< #Sv, #Se before padding
  int singular_vertices_after = -1, singular_edges_after = -1;    //!< ... after
  double padding_insert_seconds = -1, padding_optimize_seconds = -1;
  // fabricate (on request)
  int part_boxes = -1;                 //!< boxes of the thesis's partition
  int parts = -1;                      //!< parts after merging and chamber splits
  int unfit_parts = -1;                //!< parts that fit the chamber on none of their flat sides
  double support_whole_percent = -1;   //!< support printing the solid in one piece (%3DPST)
  double support_parts_percent = -1;   //!< support printing the parts on their bases (%3DPPST)
  double three_axis_percent = -1;      //!< parts' surface no 3-axis tool reaches on the best side
  double four_axis_percent = -1;       //!< parts' surface no 4-axis direction reaches
  double msj = -2, asj = -2;           //!< final hex mesh
  int inverted = -1;                   //!< final hex mesh
  int final_domains = -1;              //!< #D of the final hex mesh
  double hausdorff_relative = -1;      //!< final boundary vs the input surface (the wrap after the wrap fallback), / its bbox diagonal
  double hausdorff_unwrapped_relative = -1;  //!< after the wrap fallback: final boundary vs the surface as read
  LabelingFallback labeling_fallback;  //!< not tried unless the first mesh missed the distance bound
  double total_seconds = 0.0;
  double peak_memory_mib = -1;         //!< peak resident memory of the process (getrusage)

  [[nodiscard]] bool ok() const { return failed_stage.empty(); }
  [[nodiscard]] double seconds(const std::string& stage) const;  //!< 0 when not run
};

//! Run the chain on a surface or tet-mesh file, writing into out_dir (created).
//! Never throws for a stage failure (see RunResult); throws core::InputError only when out_dir
//! cannot be created or the options are invalid (target_hexes <= 0, inject_failure not a stage
//! name).
RunResult run_pipeline(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                       const RunOptions& options);

}  // namespace polycube::pipeline
