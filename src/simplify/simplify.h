#pragma once
//! \file simplify.h
//! \brief Polycube simplification, the whole pipeline (thesis Algorithm 1): structure, corner
//! alignment with finalization, domain counts before/after, fitting and certification.

#include "core/polycube_map.h"
#include "simplify/corner_alignment.h"
#include "simplify/domain_count.h"
#include "simplify/fit.h"

namespace polycube::simplify {

//! Options of simplify_map().
struct SimplifyOptions {
  AlignOptions align;
  FitOptions fit;
  bool count_domains = true;  //!< compute #D and #dom before and after (domain_count.h)
  bool fit_map = true;        //!< fit and certify the tet mesh (false: structure only)
};

//! Result of simplify_map().
struct SimplifyResult {
  int corners = 0, edges = 0, charts = 0;
  AlignResult alignment;
  DomainCount before;  //!< input planes (naive snapping that merges no distinct coordinates)
  DomainCount after;   //!< aligned integer planes (gridding the output at scale 1)
  FitResult fit;       //!< empty map when fit_map is false
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
