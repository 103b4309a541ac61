#pragma once
//! \file padding.h
//! \brief Padding as a stage (thesis ch. 4; ARCHITECTURE §6.6): a facet set is inflated into a
//! new layer of hexes (sheet.h), then the optimizer of optimize/ untangles the layer with the
//! boundary kept on the target surface and its features, and the global fold-over check runs.
//! Global padding selects every boundary facet; selective padding (a later issue) chooses the
//! facets where the polycube map distorts the shape.

#include "core/types.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "padding/analysis.h"
#include "padding/selection.h"
#include "padding/sheet.h"
#include "quality/scaled_jacobian.h"
#include "quality/surface_distance.h"

#include <cstdint>
#include <string>
#include <vector>

namespace polycube::padding {

//! Which facets are padded.
enum class PaddingMode {
  None,    //!< no padding
  Global,     //!< every boundary facet
  Selective,  //!< where the map distorts the shape: mapping analysis, then the binary problem
};

//! "none", "global" or "selective".
const char* mode_name(PaddingMode mode);

//! Options of pad_hex_mesh().
struct PadOptions {
  SheetOptions sheet;                  //!< where the new layer's vertices start
  //! The optimization after insertion. Its untangling may free only the region around the hexes
  //! the insertion inverted first (OptimizeOptions::local_untangle_rings; off by default: after
  //! it the quality rounds ended lower in mSJ on more of the shared shapes than higher,
  //! bench/RESULTS.md).
  optimize::OptimizeOptions optimize;
  bool run_optimizer = true;           //!< false: insertion only (the layer as placed)
};

//! The figures of thesis Table 4.1 for one mesh.
struct MeshFigures {
  int hexes = 0;              //!< #H
  int singular_vertices = 0;  //!< #Sv
  int singular_edges = 0;     //!< #Se
  //! Hexes with two or more faces on the boundary: what padding is for (they keep the angle of
  //! a polycube edge where the surface is flat or curved; global padding leaves none).
  int multi_boundary_hexes = 0;
  quality::ScaledJacobianSummary scaled_jacobian;  //!< mSJ, aSJ (no per-hex values)
};

//! The figures of a hex mesh. \throw as quality::hex_singularities
MeshFigures mesh_figures(const core::HexMesh& mesh);

//! Result of pad_hex_mesh().
struct PadResult {
  core::HexMesh mesh;                       //!< the padded (and optimized) mesh
  std::vector<std::uint8_t> padding_layer;  //!< #H': 1 for the new layer's hexes
  std::vector<int> source_hex;              //!< #H': the input hex each hex comes from
  MeshFigures before;                       //!< the input
  MeshFigures after;                        //!< the result
  int added_hexes = 0;                      //!< hexes of the new layer
  int crossing_hexes = 0;                   //!< of which at edges where two sheets cross
  int selected_facets = 0;                  //!< |PF|
  double insert_seconds = 0;                //!< the insertion
  optimize::OptimizeResult optimization;    //!< when PadOptions::run_optimizer
  optimize::FoldoverReport check;           //!< the global fold-over check of the result
  quality::SurfaceDistance distance;        //!< the result's boundary to the target
  double seconds = 0;                       //!< wall time, everything included
};

//! Pad a hex mesh along the selected facets (core::unique_faces order; sheet.h), optimize it
//! against the target, check it. The result is returned even when the check fails (the caller
//! decides; PadResult::check says why).
//! \throw as insert_sheet and optimize::optimize_hex_mesh
PadResult pad_hex_mesh(const core::HexMesh& mesh, const core::TriMesh& target, const std::vector<std::uint8_t>& selected,
                       const PadOptions& options = {});

//! The facets selective padding pads: the mapping analysis's hard set HF (analysis.h), completed
//! by the binary problem (selection.h).
struct SelectivePlan {
  Analysis analysis;
  Selection selection;
};

//! Why a padded mesh should not replace the unpadded one (empty: it should). Its mSJ must not be
//! lower than the unpadded one's, unless it is at least `usable_min_sj` anyway; its boundary must
//! stay within `hausdorff_bound` (relative to the target's bounding-box diagonal) where the
//! unpadded one, `unpadded_distance` from it, was (and no farther where it was not): the surface
//! is a constraint of the optimization, which padding may not trade for the mSJ.
std::string why_not_kept(const PadResult& padded, double unpadded_distance, double hausdorff_bound,
                         double usable_min_sj);

//! Plan selective padding on a hex mesh. \throw as analyze_mapping and select_facets_to_pad
SelectivePlan plan_selective_padding(const core::HexMesh& mesh, const AnalysisOptions& analysis = {},
                                     const SelectionOptions& selection = {});

//! What selective padding saw and chose, for ParaView (thesis figures 4.9 and 4.10): the
//! boundary facets and the selected interior facets as quads, with the cell fields
//! `distortion` (D(f)), `propagated` (after equation 4.8), `hard` (HF) and `padded` (PF).
core::MeshData plan_mesh_data(const core::HexMesh& mesh, const SelectivePlan& plan);

//! The padded mesh as mesh data with the cell fields `padding_layer`, `source_hex` and, when the
//! input had labels, `block` (the label of the hex each hex comes from), for ParaView.
core::MeshData padded_mesh_data(const PadResult& result);

}  // namespace polycube::padding
