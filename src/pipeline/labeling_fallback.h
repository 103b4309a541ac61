#pragma once
//! \file labeling_fallback.h
//! \brief The chain once more with a more faithful labeling, when its mesh is invalid or misses
//! the input.
//!
//! Where a labeling's compactness merges the sides of a thin part (a flipper, an ear, a fluke)
//! into the charts around it, the polycube has no protrusion there: the map squeezes the part
//! into a plate of the polycube a fraction of a hex thick, and a grid of the polycube follows it
//! only once its hexes are thinner than the plate (the optimize stage's grid with twice the
//! hexes may stay beyond the bound). The labeling's compactness is then what decides: 0.3 times
//! it gives such parts their own charts (bench/RESULTS.md, stop 62: synthetic organic shapes).
//! So when the final mesh of a chain that completed is farther from the input than
//! optimize_options.hausdorff_bound, the chain runs again with compactness × kFaithfulFactor,
//! one construction attempt (the others of the plan are less faithful) and no wrap fallback,
//! in a folder of its own; its result replaces the first when it completes with a valid mesh
//! closer to the input. A squeezed part
//! within the bound shows as hexes nearly flat: a first mesh of an mSJ below kPoorMinSJ gets
//! the same retry, kept when valid, within the bound and higher in mSJ. Squeezed thinner, the
//! plate keeps hexes flat or inverted whatever the optimizer's fallbacks do (padding, a finer
//! grid): a chain that ends at optimize without a valid mesh gets the retry too, kept when
//! valid. The report says what was tried and what was kept (RunResult::labeling_fallback).

#include "pipeline/pipeline.h"

#include <filesystem>
#include <functional>

namespace polycube::pipeline {

//! The compactness of the retry, as a share of the first chain's.
inline constexpr double kFaithfulFactor = 0.3;
//! A first mesh of an mSJ below this (hexes nearly flat) gets the retry too; the shared shapes'
//! meshes are all above it (bench/RESULTS.md), the squeezed legs of a synthetic dog below.
inline constexpr double kPoorMinSJ = 0.1;
//! The retry's folder, inside the output folder (removed once the retry is decided, and by the
//! next run into the same folder when the retry was interrupted).
inline constexpr const char* kRetryFolder = "faithful-labeling";

//! The chain of run_pipeline() without this fallback: (input, output folder, options).
using Chain = std::function<RunResult(const std::filesystem::path&, const std::filesystem::path&, const RunOptions&)>;

//! Whether `first` (the chain's result with options `o`) gets the retry: it failed at optimize
//! (or at the final check of the mesh), or it completed and its mesh is beyond the bound or
//! poor in mSJ (or the hidden injection "final-distance" or "final-quality" says so), its map is
//! the
//! input's own (not the alpha wrap of the construct fallback: the retry would compare
//! distances to different surfaces), and the fallback is on.
bool wants_faithful_labeling(const RunResult& first, const RunOptions& o);

//! The retry (see the file comment) into out_dir/faithful-labeling, then that folder's files
//! moved into out_dir when its result is kept (the first chain's files removed first), or the
//! folder removed when not. Returns the kept result, with RunResult::labeling_fallback filled in
//! and the seconds of both chains.
RunResult with_faithful_labeling(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                                 const RunOptions& o, RunResult first, const Chain& chain);

}  // namespace polycube::pipeline
