#pragma once
//! \file certify.h
//! \brief Certification of a polycube map with exact predicates (ARCHITECTURE §6.2 step 5).
//!
//! A map is certified when
//! 1. no tet is inverted or flat in model space nor in polycube space (CGAL::orientation,
//!    Exact_predicates_inexact_constructions_kernel);
//! 2. the labeled triangles are exactly the boundary faces of the tet mesh, and the boundary is
//!    a closed 2-manifold surface;
//! 3. every polycube boundary triangle lies exactly on its chart's plane: its three vertex
//!    coordinates along its label's axis are equal bit for bit, and it faces its label's
//!    direction (exact 2D orientation of its projection);
//! 4. the polycube boundary surface does not intersect itself
//!    (CGAL::Polygon_mesh_processing::does_self_intersect).
//! A map that fails is never written as a result: the caller throws core::GeometryError with
//! the certificate's reason (require_certified).

#include "core/polycube_map.h"
#include "core/types.h"

#include <string>
#include <vector>

namespace polycube::construct {

//! Options of certify_polycube_map().
struct CertifyOptions {
  bool check_self_intersection = true;  //!< run check 4 (the most expensive one)
  int max_listed = 5;                   //!< offending elements named per failure
};

//! What certify_polycube_map() found; every count is 0 for a certified map.
struct Certificate {
  int tets = 0;
  int boundary_triangles = 0;
  int inverted_model = 0;
  int flat_model = 0;
  int inverted_polycube = 0;
  int flat_polycube = 0;
  int unmatched_triangles = 0;  //!< labeled triangles that are not boundary faces (or missing)
  int off_plane = 0;            //!< boundary triangles not exactly on an axis plane of their label
  int wrong_facing = 0;         //!< boundary triangles facing away from (or flat along) their label
  bool closed_manifold = false; //!< boundary closed and 2-manifold
  bool self_intersecting = false;
  bool self_intersection_checked = false;
  std::vector<std::string> failures;  //!< one sentence per failed check

  [[nodiscard]] bool certified() const { return failures.empty(); }
  //! "; "-joined failures ("certified" when none).
  [[nodiscard]] std::string reason() const;
};

//! Certify a polycube map against its boundary labeling.
//! \param map       tets with model and polycube positions
//! \param boundary  #B labeled triangles (volume indices, any orientation)
//! \param labels    #B labels in {0..5}
//! \throw core::InputError when sizes or indices are inconsistent
Certificate certify_polycube_map(const core::PolycubeMap& map, const std::vector<core::Tri>& boundary,
                                 const std::vector<int>& labels, const CertifyOptions& options = {});

//! Throw core::GeometryError("polycube map not certified: <reason>") unless certified.
void require_certified(const Certificate& certificate);

}  // namespace polycube::construct
