#pragma once
//! \file labeling.h
//! \brief Polycube labeling of boundary triangles by multi-label graph cut (α-expansion)
//! (ARCHITECTURE §6.2 step 2).
//!
//! A labeling is one value per boundary triangle in {0..5} = {+X, −X, +Y, −Y, +Z, −Z}
//! (ARCHITECTURE §4): label l has axis l / 2 and sign + when l is even.

#include "core/polycube_map.h"
#include "core/types.h"

#include <array>
#include <vector>

namespace polycube::construct {

inline constexpr int kNumLabels = 6;

// The label conventions live in core (core/polycube_map.h); construct code names them here.
using core::faces_label;
using core::label_axis;
using core::label_direction;
using core::label_name;
using core::opposite_label;

//! Options of graph_cut_labeling().
struct LabelingOptions {
  //! Weight of the compactness (smoothness) term relative to the fidelity term: larger values
  //! give fewer, more compact charts with straighter boundaries; 0 = the best axis per triangle.
  double compactness = 1.0;
  //! Width of the normal-similarity weight: a label change across an edge whose normals differ
  //! by `1 - n1·n2 = sigma` costs e^-0.5 of a change across a flat edge (sharp edges are cheap).
  double sigma = 0.25;
  //! At most this many α-expansion cycles (one cycle = one expansion move per label).
  int max_cycles = 8;
  //! Empty, or #T extra data costs per (triangle, label), in units of the fidelity term of a
  //! triangle of mean area (so 1 = as bad as a label 90° off the normal). Used to steer the
  //! labeling away from labels that could not be realized (construct_polycube's relabelling).
  std::vector<std::array<double, 6>> penalty;
  //! Empty, or #T unit normals read by the fidelity (data) term instead of the surface's own,
  //! e.g. those of a pre-deformed surface (predeform.h); the compactness weights keep reading
  //! the surface's normals, so chart boundaries stay as smooth as the model allows.
  std::vector<core::Vec3> data_normals;
  //! Sweeps of smooth_chart_boundaries() after the graph cut (0: none).
  int smoothing_rounds = 0;
};

//! Result of graph_cut_labeling().
struct LabelingResult {
  std::vector<int> labels;  //!< #T labels in {0..5}
  double energy = 0.0;      //!< final energy (fidelity + compactness terms, area-normalized)
  int cycles = 0;           //!< α-expansion cycles run
  int moves = 0;            //!< expansion moves that lowered the energy
  double compactness = 0.0; //!< the compactness of the cut (LabelingOptions::compactness)
};

//! Label the triangles of a closed, edge-manifold surface by α-expansion graph cut: data term
//! `A_t/Ā · (1 − n_t·axis_l)`, Potts smoothness `compactness · |e|/ē · exp(−(1 − n_s·n_t)²/2σ²)`.
//! Each move is a max-flow (solve::max_flow). Deterministic.
//! \param surface  #V points, #T triangles with outward orientation
//! \throw core::InputError when the surface is not a closed edge-manifold surface
LabelingResult graph_cut_labeling(const core::TriMesh& surface, const LabelingOptions& options = {});

//! Smooth the chart boundaries of a labeling: a triangle with two or three edge neighbours of
//! one other label (a "tooth" of its chart, a zigzag of the boundary) takes that label, until
//! no triangle changes or after max_rounds sweeps. Zigzags at the scale of the triangles become
//! polycube edges that fold back on themselves, which the deformation cannot untangle.
//! Deterministic (triangles visited in index order). Returns the number of changes.
//! \pre labels.size() == surface.cells.size(), each in {0..5}
int smooth_chart_boundaries(const core::TriMesh& surface, std::vector<int>& labels, int max_rounds = 10);

//! Fidelity of a labeling: area-weighted mean of `1 − n·axis` (0 = every triangle exactly
//! facing its axis; at most 2).
//! \pre labels.size() == surface.cells.size(), each in {0..5}
double labeling_fidelity(const core::TriMesh& surface, const std::vector<int>& labels);

}  // namespace polycube::construct
