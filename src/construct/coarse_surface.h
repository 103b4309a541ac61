#pragma once
//! \file coarse_surface.h
//! \brief A surface too coarse for the labeling, refined without moving it (issue 24).
//!
//! A chart of a polycube labeling needs at least four neighbouring charts, and a face of the
//! input can only be split into charts along its triangles' edges. A tetrahedron (4 triangles),
//! a wedge (8) or a pyramid (6) therefore has no valid labeling at all. Splitting every triangle
//! into four at its edges' midpoints keeps every point of the surface where it was (the new
//! vertices lie on the old edges, the new triangles in the old planes) and gives the labeling
//! room; construct does it only when the labeling fails and the surface has long edges.

#include "core/types.h"

namespace polycube::construct {

//! What the refinement did.
struct SurfaceRefinement {
  int levels = 0;  //!< times every triangle was split into four (0: not refined)
  int triangles_before = 0;
  int triangles_after = 0;
  double longest_edge_before = 0.0;  //!< model units
  double longest_edge_after = 0.0;
};

//! The longest edge of a triangle surface (0 when empty).
double longest_edge(const core::TriMesh& surface);

//! Split every triangle into four at its edges' midpoints (shared midpoints are one vertex, so a
//! closed manifold stays closed and manifold), as many times as it takes for no edge to be
//! longer than `max_edge`, but not past `max_triangles` triangles.
core::TriMesh subdivide_to(const core::TriMesh& surface, double max_edge, int max_triangles,
                           SurfaceRefinement& done);

}  // namespace polycube::construct
