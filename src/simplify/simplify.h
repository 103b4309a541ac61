#pragma once
//! \file simplify.h
//! \brief Polycube simplification, the whole pipeline (thesis Algorithm 1): structure, corner
//! alignment with finalization, domain counts before/after, fitting and certification.
//!
//! When the fit cannot be certified, the simplification falls back instead of failing, each
//! step giving up some of the alignment (SimplifyStep): the fit itself already tries the
//! boundary-first placement (fit.h); then the corners near the tets the fit left inverted are
//! frozen (never paired) and the alignment runs again; then no corner is paired at all (the
//! corners only go to their nearest lattice positions). When every step fails the result is
//! uncertified and the caller keeps the unsimplified map.

#include "core/polycube_map.h"
#include "simplify/corner_alignment.h"
#include "simplify/domain_count.h"
#include "simplify/fit.h"

#include <string>
#include <vector>

namespace polycube::simplify {

//! The simplification's steps, in the order they are tried (see the file comment).
enum class SimplifyStep {
  Aligned,          //!< the alignment as asked
  FewerAlignments,  //!< corners near the inverted tets frozen (or a single alignment iteration)
  Unaligned,        //!< no pair aligned: the corners rounded to the lattice
  None              //!< every step failed: the result is not certified
};

//! "aligned", "fewer alignments", "unaligned", "none".
const char* step_name(SimplifyStep step);

//! Options of simplify_map().
struct SimplifyOptions {
  AlignOptions align;
  FitOptions fit;
  bool count_domains = true;  //!< compute #D and #dom before and after (domain_count.h)
  bool fit_map = true;        //!< fit and certify the tet mesh (false: structure only)
  bool fallbacks = true;      //!< when the fit cannot be certified, try the next steps
  //! Testing only: the first this many steps count as failed whatever their fit gave, so the
  //! tests reach every fallback on small inputs (pipeline.h, `--inject-failure`).
  int inject_failed_steps = 0;
};

//! Result of simplify_map().
struct SimplifyResult {
  int corners = 0, edges = 0, charts = 0;
  AlignResult alignment;
  DomainCount before;  //!< input planes (naive snapping that merges no distinct coordinates)
  DomainCount after;   //!< aligned integer planes (gridding the output at scale 1)
  FitResult fit;       //!< empty map when fit_map is false
  SimplifyStep step = SimplifyStep::Aligned;  //!< the step that gave `fit` (None: not certified)
  std::vector<std::string> tried;             //!< why each earlier step failed
  int frozen_corners = 0;                     //!< corners frozen by the FewerAlignments step
  double seconds_validate = 0.0;
  double seconds_structure = 0.0;
  double seconds_domains = 0.0;
};

//! Simplify a polycube map.
//! \throw core::InputError when the map is invalid (structure::validate_map)
//! \throw core::GeometryError when its structure cannot be simplified (corner_system.h)
//! \throw core::SolverError when a solver fails
//! The result may be uncertified (result.fit.certified false, with the reasons): callers must
//! not write it as a valid map.
SimplifyResult simplify_map(const core::PolycubeMap& map, const SimplifyOptions& options = {});

}  // namespace polycube::simplify
