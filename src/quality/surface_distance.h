#pragma once
//! \file surface_distance.h
//! \brief Symmetric Hausdorff distance between two triangle surfaces (ARCHITECTURE §6.1),
//! absolute and relative to the bounding-box diagonal of the reference surface, with a
//! guaranteed error bound.
//!
//! Method (directed distance from A to B; B in a CGAL AABB tree giving exact point-to-surface
//! distances d): d is evaluated at every vertex and every triangle's centroid of A, then each
//! triangle T of A is refined adaptively. With d_c the distance at T's centroid c and d_i at its
//! corners v_i, every point p of T satisfies
//! d(p) <= U(T) = min(d_c + max_i |v_i - c|, min_i (d_i + max_j |v_j - v_i|)), because d is
//! 1-Lipschitz. T is accepted when U(T) <= L + tolerance, L the largest distance found so far
//! (the maximum over A's vertices and centroids, or over T's own samples); otherwise it is split
//! in four at its edge midpoints and the children are examined. The result is a lower bound
//! (a distance actually attained at a sample) and an upper bound (the largest U of the accepted
//! triangles), at most `tolerance` apart unless the refinement depth cap was reached.
//!
//! Degenerate triangles (zero area) are left out of the AABB trees (their points lie on their
//! neighbours' edges); they are still measured. The computation is deterministic (fixed work
//! blocks, in parallel with TBB when available).

#include "core/types.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace polycube::quality {

//! Options of the surface distance.
struct SurfaceDistanceOptions {
  //! Guaranteed accuracy: upper_bound - max <= tolerance * the reference's bounding-box
  //! diagonal (unless max_queries forced a shallower refinement). Must be > 0.
  double tolerance = 1e-3;
  //! Cap on distance queries per direction, enforced as a refinement depth limit per triangle
  //! (depth <= log4(max_queries / #triangles)); the bounds stay valid, only wider.
  std::size_t max_queries = 4'000'000;
};

//! Distance from the points of one surface to the other surface.
struct DirectedDistance {
  double max = 0.0;          //!< largest distance found (attained at worst_point): a lower bound
  double upper_bound = 0.0;  //!< guaranteed upper bound of the directed Hausdorff distance
  double mean = 0.0;  //!< area-weighted mean distance (centroid rule on the refined triangles)
  core::Vec3 worst_point = core::Vec3::Zero();  //!< the point achieving max
  std::size_t queries = 0;                      //!< distance queries made
};

//! Symmetric Hausdorff distance between a surface and a reference surface.
struct SurfaceDistance {
  DirectedDistance surface_to_reference;  //!< from the surface to the reference
  DirectedDistance reference_to_surface;  //!< from the reference to the surface
  double hausdorff = 0.0;                 //!< max of the two directed lower bounds (attained)
  double hausdorff_upper = 0.0;           //!< max of the two directed upper bounds
  double reference_diagonal = 0.0;        //!< bounding-box diagonal of the reference
  double relative = 0.0;  //!< hausdorff / reference_diagonal (0 if the diagonal is 0)
};

//! Symmetric Hausdorff distance between two triangle surfaces.
//! \param surface the measured surface (e.g. a mesh's boundary)
//! \param reference the reference (target) surface; tolerances and relative distances use its
//!        bounding-box diagonal
//! \throw core::InputError when a surface has no triangle, out-of-range indices, a non-finite
//!        coordinate used by a triangle, or when the tolerance is not > 0
//! \throw core::GeometryError when every triangle of a surface is degenerate
SurfaceDistance hausdorff_distance(const core::TriMesh& surface, const core::TriMesh& reference,
                                   const SurfaceDistanceOptions& options = {});

//! A quad surface as triangles (each quad split 0-1-2, 0-2-3; labels duplicated).
core::TriMesh triangulate(const core::QuadMesh& quads);

//! Symmetric Hausdorff distance between the boundary of a hex mesh (its boundary quads split in
//! two triangles) and a reference surface. \throw as hausdorff_distance and core::boundary
SurfaceDistance hausdorff_distance(const core::HexMesh& hexes, const core::TriMesh& reference,
                                   const SurfaceDistanceOptions& options = {});

//! A vertex and its distance to the other surface.
struct FarVertex {
  core::Vec3 point = core::Vec3::Zero();
  double distance = 0.0;
};

//! The vertices of `surface` (those its triangles use) farther than `distance` from `reference`:
//! where a mesh misses a surface, the farthest first (equal distances in vertex order).
//! \throw as hausdorff_distance
std::vector<FarVertex> vertices_farther_than(const core::TriMesh& surface, const core::TriMesh& reference,
                                             double distance);

//! The distance (default options) of one hex mesh's boundary to one reference surface, kept with
//! the points and hexes it was measured for. A chain measures the same mesh several times (the
//! optimizer's last retry, the pipeline's distance check, the final report), and each
//! measurement of a 20,000-hex mesh refines hundreds of thousands of points: the same mesh gets
//! the same figures without the work. The caller keeps the reference the same.
class RememberedDistance {
 public:
  //! The distance remembered for exactly these points and hexes, or nullptr.
  [[nodiscard]] const SurfaceDistance* find(const core::HexMesh& hex) const;
  //! Remember `d` as the distance of `hex` (forgetting the one before).
  void remember(const core::HexMesh& hex, const SurfaceDistance& d);
  //! The remembered distance of `hex`, else hausdorff_distance(hex, reference), remembered.
  const SurfaceDistance& measure(const core::HexMesh& hex, const core::TriMesh& reference);

 private:
  std::vector<core::Vec3> points_;
  std::vector<core::HexMesh::Cell> cells_;
  std::optional<SurfaceDistance> distance_;
};

}  // namespace polycube::quality
