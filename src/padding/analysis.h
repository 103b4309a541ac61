#pragma once
//! \file analysis.h
//! \brief Mapping analysis of selective padding (thesis §4.4): which boundary facets of a
//! polycube hex mesh must be padded (the hard-constrained set HF).
//!
//! 1. Only the boundary hexes whose scaled Jacobian is below a threshold T are looked at.
//! 2. A distortion D(e) per boundary edge of such a hex, from the dihedral angle the polycube
//!    gave it: at a convex edge (one hex, E1H) the two boundary facets should meet at 90°, so
//!    θ = n_i·n_j (outward normals) near 1 means a flat or folded stretch: D = θ when θ ≥ 0.5;
//!    at a concave edge (three hexes, E3H) the two inner facets of the middle hex should meet at
//!    90° too: D = |θ| when θ ≤ −0.5 (their normals, outward of the middle hex, turn opposite
//!    where the surface is flat). Edges of two hexes (E2H) get 0: padding them leaves an E2H edge.
//! 3. D(f) = the largest D of a boundary facet's four edges.
//! 4. Soft propagation, equation 4.8: for n = 0 .. k−1, every facet still at 0 takes the
//!    largest D of its neighbours (boundary facets sharing an edge) times e^(−n/2), so isolated
//!    holes in a distorted patch fill in.
//! 5. HF by a minimum cut (equations 4.9–4.11, Boykov–Kolmogorov): a facet costs 1 − D in HF and
//!    D outside it; two neighbours with different labels cost (1 − |D_p − D_q|)(D_p + D_q),
//!    so HF comes in patches without holes or isolated facets (thesis figure 4.9).

#include "core/types.h"

#include <cstdint>
#include <vector>

namespace polycube::padding {

//! Options of analyze_mapping().
struct AnalysisOptions {
  double threshold = 0.6;  //!< T: boundary hexes with a scaled Jacobian at least this are ignored
  int propagation = 3;     //!< k: steps of the soft propagation (equation 4.8)
};

//! Result of analyze_mapping(): one value per facet of core::unique_faces(mesh) (interior facets
//! 0 throughout).
struct Analysis {
  std::vector<double> distortion;             //!< D(f) before the propagation
  std::vector<double> propagated;             //!< D(f) after it
  std::vector<std::uint8_t> hard;             //!< HF: 1 for the facets that must be padded
  int analysed_hexes = 0;                     //!< boundary hexes below the threshold
  int distorted_edges = 0;                    //!< boundary edges with D(e) > 0
  int hard_facets = 0;                        //!< |HF|
  double seconds = 0;                         //!< wall time
};

//! Analyse a hex mesh (model space, positively oriented hexes expected: an inverted hex's
//! normals mean nothing, but it counts as below the threshold).
//! \throw core::InputError on bad options or an empty mesh; as quality::hex_topology
Analysis analyze_mapping(const core::HexMesh& mesh, const AnalysisOptions& options = {});

}  // namespace polycube::padding
