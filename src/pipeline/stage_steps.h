#pragma once
//! \file stage_steps.h
//! \brief Steps that more than one stage of run_pipeline() takes (internal to src/pipeline):
//! gridding the map and writing the grid, padding and recording it, and the hidden fault
//! injection of the tests (RunOptions::inject_failure).

#include "core/types.h"
#include "core/polycube_map.h"
#include "mesh/grid.h"
#include "optimize/foldover_check.h"
#include "padding/padding.h"
#include "pipeline/input.h"
#include "pipeline/pipeline.h"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace polycube::pipeline {

//! Called with each file the chain writes (RunResult::files).
using FileWritten = std::function<void(const std::filesystem::path&)>;

//! Testing only: N for an injected failure "<prefix>N" with N in 1..9 (RunOptions::inject_failure), else 0.
int injected_steps(const std::string& inject, const std::string& prefix);

//! Write a mesh with cell fields as VTK (or whatever the extension says).
void write_vtk(const std::filesystem::path& path, core::MeshData data, std::vector<core::Field> fields);

//! Grid the map at about `target` hexes with `sizing`; write hex.mesh and quad.vtk and record
//! the gridded mesh's figures in r. Returns the hex mesh.
core::HexMesh grid_and_write(const core::PolycubeMap& map, int target, mesh::GridSizing sizing,
                             const std::filesystem::path& out_dir, RunResult& r,
                             const FileWritten& wrote, const std::vector<core::Vec3>& refine_near = {});

//! One line for a fold-over check's failures.
std::string fold_summary(const optimize::FoldoverReport& fold);

//! Pad the mesh (`mode`), optimize and check it (padding/padding.h); record the figures in r
//! (r.padding = how) and write hex_padded.mesh and hex_padded.vtk when the result passes the
//! check. Nothing when there is nothing to pad. A facet set the insertion refuses comes back as
//! an error, like a failed check. `planned`, when given, is told how many facets the plan pads
//! as soon as it is known (before the padding and its optimization).
std::optional<padding::PadResult> pad_and_record(const core::HexMesh& hex, const ConstructInput& in,
                                                 const RunOptions& o, padding::PaddingMode mode, const std::string& how,
                                                 const std::filesystem::path& out_dir, RunResult& r,
                                                 const FileWritten& wrote, const std::function<void(int)>& planned = {});

//! A selective plan's figures in r (|HF|, |PF|, turns, solver, gap, seconds).
void record_plan(const padding::SelectivePlan& plan, RunResult& r);

//! A padded mesh's figures in r (r.padding = how).
void record_padding(const padding::PadResult& p, const std::string& how, RunResult& r);

//! Write a padded mesh that passed its check: hex_padded.mesh and hex_padded.vtk.
void write_padded(const padding::PadResult& p, const std::filesystem::path& out_dir, const FileWritten& wrote);

//! Forget a padded mesh that is not kept (only an injected failure can reject a mesh that
//! passed the check, the only one pad_and_record writes).
void discard_padded(const std::filesystem::path& out_dir, RunResult& r);

}  // namespace polycube::pipeline
