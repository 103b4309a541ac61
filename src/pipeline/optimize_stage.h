#pragma once
//! \file optimize_stage.h
//! \brief The optimize stage of run_pipeline() and its fallbacks (issue 27). In order:
//!  1. the gridded mesh is optimized, and the result goes through the global fold-over check;
//!  2. a result that fails only by its boundary crossing itself: the same grid once more, the
//!     boundary barrier kBarrierRetry times stiffer (keeps the hexes the user asked for);
//!     steps 1–2 run with the optimizer's fast ε schedule (OptimizeOptions::untangle_min_sigma)
//!     and, when neither passes, once more with the paper's slower one ("slower untangling
//!     schedule"), which step 4 also uses; with the fast schedule, step 2 runs only for a
//!     crossing found right after the untangling;
//!  3. the first result padded selectively, then globally, and optimized again (the new layer
//!     frees the boundary hexes the gridding squashed; thesis ch. 4);
//!  4. the map gridded again with its own sizing, then twice as fine, and optimized;
//!  5. a valid mesh of the first grid (steps 1–2) farther from the input than the optimizer's
//!     Hausdorff bound (OptimizeOptions::hausdorff_bound): with RunOptions::refine_far, the map
//!     gridded with twice the cells in the unit slabs of the polycube that hold the points where
//!     the mesh misses the input (mesh::GridOptions::refine_near; not when that makes more than
//!     twice the hexes); then, while still beyond the bound, twice as fine everywhere (each with
//!     steps 1–2 and their schedules); a finer mesh is kept when it is valid and closer
//!     than the one before.
//! Each step runs only when the ones before it left no valid mesh (step 5: a mesh too far).
//! RunResult::optimize_fallback names the step that gave the mesh ("none": step 1) and
//! optimize_tried says why each earlier one was not kept.

#include "core/polycube_map.h"
#include "core/types.h"
#include "mesh/grid.h"
#include "pipeline/input.h"
#include "pipeline/pipeline.h"
#include "pipeline/stage_steps.h"

#include <filesystem>

namespace polycube::pipeline {

//! The optimize stage: returns the mesh that passed and writes it as hex_optimized.mesh (with
//! hex.mesh and quad.vtk of the gridding it came from; hex_padded.* when padding gave it).
//! \throw core::GeometryError when no step gave a mesh that passes the fold-over check
core::HexMesh optimize_with_fallbacks(const core::HexMesh& gridded, const core::PolycubeMap& map,
                                      mesh::GridSizing sizing, const ConstructInput& in, const RunOptions& o,
                                      const std::filesystem::path& out_dir, RunResult& r, const FileWritten& wrote);

}  // namespace polycube::pipeline
