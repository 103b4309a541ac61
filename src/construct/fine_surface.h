#pragma once
//! \file fine_surface.h
//! \brief A surface finer than the construction needs, decimated within a tolerance (issue 23).
//!
//! The tet mesh of the construction follows the surface's triangles (TetGen adds no point on
//! the surface and grades the interior from it), so every step of the construction (labeling,
//! deformation, untangling, certification) grows with the input's triangle count, while the
//! hex mesh made from the map has far fewer boundary faces (about 6 H^(2/3) for H hexes: 4,400
//! at 20,000 hexes). A scanned surface of 54,000 triangles gives some 117,000 tets.
//!
//! Construct therefore collapses edges of a surface with more triangles than it needs
//! (Lindstrom–Turk cost and placement) before the tetrahedralization. No vertex of the result
//! is farther from the input than a tolerance, no triangle turns over (bounded normal change),
//! and a result that intersects itself is not used. The map is then of the decimated solid;
//! `run` still fits the hex mesh to the input surface and measures its distance to the input.

#include <optional>

#include "core/types.h"

namespace polycube::construct {

//! What the decimation did.
struct SurfaceDecimation {
  int triangles_before = 0;
  int triangles_after = 0;  //!< 0: not decimated
  double tolerance = 0.0;   //!< model units: no vertex of the result is farther from the input
  double seconds = 0.0;
  [[nodiscard]] bool done() const { return triangles_after > 0; }
};

//! `surface` (closed, manifold) decimated to at most `max_triangles` triangles, no vertex of the
//! result farther than `tolerance` (model units) from it; nullopt when it has no more triangles
//! than that (nothing to do), the tolerance allows no collapse, or the result would intersect
//! itself (then the input is used as it is). Where the tolerance forbids more collapses the
//! result keeps more triangles. Deterministic.
std::optional<core::TriMesh> decimate_surface(const core::TriMesh& surface, int max_triangles, double tolerance,
                                              SurfaceDecimation& done);

}  // namespace polycube::construct
