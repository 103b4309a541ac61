#pragma once
//! \file labeling_repair.h
//! \brief Repair of a polycube labeling to validity by local operators (ARCHITECTURE §6.2 step 3).
//!
//! Each step takes one defect found by check_labeling() and tries local operators around it:
//! re-labelling a small chart (merging it into a neighbour), re-labelling a strip along a
//! boundary between opposite charts with a third axis, re-labelling the k-ring of a bad corner
//! or the sectors of its charts, for growing rings. A move is kept only when it lowers the
//! number of defects; among those that remove the most, the one whose fast polycube estimate
//! (polycube_estimate.h) folds the least surface area wins, then the one with the lowest
//! labeling energy (fidelity + compactness, the terms of graph_cut_labeling()). The repair never gives up silently:
//! the result lists every remaining defect with its reason.

#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "core/types.h"

#include <vector>

namespace polycube::construct {

//! cut_and_repair(): the compactness factor of the looser cut.
inline constexpr double kLooserCut = 0.8;

//! Options of repair_labeling().
struct RepairOptions {
  //! Energy used to rank the moves that lower the number of defects (same meaning as in
  //! graph_cut_labeling()).
  LabelingOptions energy;
  //! Largest ring radius (in vertex rings) tried around a defect.
  int max_ring = 6;
  //! At most this many accepted moves.
  int max_moves = 5000;
  //! Rank the moves that remove the most defects by the fast polycube estimate
  //! (polycube_estimate.h: least area folded), then by labeling energy; false: energy only.
  bool score_by_estimate = true;
  //! Empty, or #T labels the moves leave alone (-1: free): a move's triangles held to another
  //! label are dropped from it.
  std::vector<int> held;
};

//! Result of repair_labeling().
struct RepairResult {
  std::vector<int> labels;  //!< #T repaired labels
  LabelingCheck check;      //!< check of the repaired labels (defects with reasons)
  int initial_defects = 0;  //!< defects before the repair
  int moves = 0;            //!< accepted moves
  [[nodiscard]] bool valid() const { return check.valid(); }
};


//! Repair a labeling towards validity.
//! \param surface  closed, edge-manifold surface (#V, #T), outward orientation
//! \param labels   #T initial labels in {0..5}
//! \throw core::InputError on a wrong number of labels, a label out of range or a surface that
//!        is not a closed edge-manifold surface
RepairResult repair_labeling(const core::TriMesh& surface, const std::vector<int>& labels,
                             const RepairOptions& options = {});

//! Charts that face away from their label: the area-weighted sum of their triangles' normals
//! has no positive component along the label's direction (sorted ids of layout's charts). In a
//! polycube whose corners sit where the model's are, such a chart is a face whose boundary winds
//! the wrong way round, and no map can place it: the compactness term can pull a small chart on
//! a strongly curved part to a label its triangles do not face.
//! \param normals  #T unit normals the labeling read (LabelingOptions::data_normals), or empty:
//!                 the surface's own
std::vector<int> backward_charts(const core::TriMesh& surface, const ChartLayout& layout,
                                 const std::vector<core::Vec3>& normals = {});

//! Give every backward chart the label of the neighbouring chart it faces most, then repair to
//! validity again (repair_labeling with `options`, whose energy's data normals are the ones
//! read); repeated while the number of backward charts falls. `rep` comes back unchanged when
//! it has no backward chart or the relabelled labeling cannot be repaired to validity.
RepairResult relabel_backward_charts(const core::TriMesh& surface, RepairResult rep, const RepairOptions& options);

//! A graph cut and its repair (cut_and_repair()).
struct CutAndRepair {
  LabelingResult cut;   //!< the graph cut repaired; cut.compactness says at which compactness
  RepairResult repair;  //!< its repair, backward charts relabelled (options.energy: the cut's options)
};

//! graph_cut_labeling() at `labeling`, then repair_labeling() and relabel_backward_charts()
//! (what `construct` and `label` both run). When the repair had to move
//! labels to make the cut valid and the cut at kLooserCut times the compactness is valid as it
//! is, that cut is kept instead. The repair's moves are ranked by the defects they remove and
//! by the polycube estimate, not by the creases: a chart with too few neighbours is relabeled
//! as a whole, and where it meets its new chart at a sharp crease, that crease ends up inside
//! one polycube face, where no hex edge follows it and the hex mesh cuts across it. A slightly
//! less compact cut keeps its chart boundaries on the creases, as the graph cut does everywhere
//! (its edge weights vanish across sharp edges). A looser cut that still needs moves is not
//! better, and a cut the repair cannot make valid stays a failure (the attempts at other
//! compactness values are the fallbacks there).
CutAndRepair cut_and_repair(const core::TriMesh& surface, const LabelingOptions& labeling, RepairOptions repair);

}  // namespace polycube::construct
