#pragma once
//! \file selection.h
//! \brief The binary problem of selective padding (thesis §4.3.1–4.3.2, equations 4.1–4.7):
//! the set PF of facets to pad, containing the hard set HF, valid for the insertion (sheet.h),
//! with few added hexes and few turns of the layer.
//!
//! Formulation. The thesis gives every facet a binary x_f and every edge an integer k_e with
//! sum x_f = 2 k_e (equation 4.3). Parity rows like these give CBC a useless relaxation (x = 1/2
//! everywhere), so the same problem is written as a cut, the way pillowing is defined (a shrink
//! set and its boundary): a binary y_c per cell (hexes, and the ghosts glued outside boundary
//! facets, sheet.h), y = 1 inside the shrink set, and x_f = y_a XOR y_b for the facet between
//! cells a and b; z_e = y XOR y of the two ghosts at a boundary edge (a sheet ending on the
//! surface). A cut has an even number of cut facets around every edge, so equation 4.3 holds
//! by construction; the other rules are rows:
//! - HF (equation 4.2): the facet's hex is inside (y = 1), its ghost outside (y = 0);
//! - a concave boundary edge (E3H): its ghosts on one side (z = 0), so its four facets have an
//!   even count;
//! - an edge of two hexes (E2H): not one surface facet alone, x_b1 + z − x_g − x_b2 ≤ 1 and the
//!   same for b2;
//! - sheets do not cross: at most two separations around an edge. The insertion fills a
//!   crossing along an edge, but a cut can also end a crossing at a vertex where two opposite
//!   quadrants join around it, which no hex fills; padding needs no crossings (the start below
//!   has none), so the program leaves them out.
//! Every cut with these rows is a valid PF for the insertion, and every valid PF of a solid
//! without handles is such a cut; a solid with handles also has sheets around a handle that
//! bound nothing, which this formulation leaves out (they are never needed: a cut that pads
//! every surface facet is always feasible).
//!
//! Objective (equation 4.7): |H|^(−2/3) · #(PF \ HF) + λ (|H|^(−1/3) · Σ te + Σ tv). te_e ≥
//! |x_i − x_k| for each pair of opposite facets around edge e (equation 4.5; opposite = two
//! apart in the turning order), tv_v ≥ |te_i − te_k| for each pair of opposite edges at vertex v
//! (no facet holds both; equation 4.6). Minimization makes them the indicators. Turns that HF
//! itself makes (two of its facets at right angles around an edge or a vertex) are left out:
//! they are in every solution. Edges of one hex (E1H) and vertices of one hex (V1H) carry no
//! turn, as in the thesis.
//!
//! What the solver gets: y fixed at HF; te only where a turn can happen and is not forced; the
//! XOR upper bounds (x ≤ y_a + y_b, x ≤ 2 − y_a − y_b) only for facets that appear in a rule or
//! turn row (elsewhere minimization already makes x = |y_a − y_b|, so they change nothing); and
//! the cheaper of two cuts as a start, so a time limit still returns a valid PF: padding every
//! surface facet (every hex inside, every ghost outside: always feasible, and the optimum where
//! turns cost much) and the pillow of HF's hexes (those hexes inside, a sheet one hex deep under
//! HF that turns at its rim, grown where a rule needs it: the optimum where turns cost little,
//! which a large program's relaxation does not find when it is fractional). When the relaxation is fractional, its
//! cut rounded at 1/2 and repaired in a small neighbourhood of the fractional cells (the program
//! over those cells alone, the rest fixed) is a second start, often far cheaper: the relaxation
//! is typically integral but at a few ghosts.

#include "core/types.h"

#include <cstdint>
#include <string>
#include <vector>

namespace polycube::padding {

//! Options of select_facets_to_pad().
struct SelectionOptions {
  double lambda = 1.0;       //!< λ of equation 4.7: weight of the layer's turns against its hexes
  double time_limit = 60.0;  //!< seconds for CBC (0: none); the best PF found is returned
  //! Under a time limit, branch and cut on programs small enough to search (false: the cheapest
  //! start or repaired rounding only, as on large programs; fast, and the same on any machine)
  bool search = true;
};

//! Result of select_facets_to_pad().
struct Selection {
  std::vector<std::uint8_t> facets;  //!< PF: one flag per facet of core::unique_faces(mesh)
  int selected = 0;                  //!< |PF|
  int edge_turns = 0;                //!< te = 1 in the solution
  int vertex_turns = 0;              //!< tv = 1 in the solution
  double objective = 0;              //!< E of equation 4.7
  bool optimal = false;              //!< proven optimal (else stopped at the time limit)
  double gap = 0;                    //!< relative gap to the best bound when not proven optimal
  int variables = 0, rows = 0;       //!< size of the program given to CBC
  std::string solver;                //!< what proved (or found) it: solve::MilpResult::solver
  double seconds = 0;                //!< building and solving
};

//! Solve the binary problem for the hard set `hard` (boundary facets, core::unique_faces order).
//! \throw core::InputError when `hard` has the wrong size or flags an interior facet
//! \throw core::SolverError when CBC finds no solution (it always has the start's)
Selection select_facets_to_pad(const core::HexMesh& mesh, const std::vector<std::uint8_t>& hard,
                               const SelectionOptions& options = {});

}  // namespace polycube::padding
