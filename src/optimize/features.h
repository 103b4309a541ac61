#pragma once
//! \file features.h
//! \brief Sharp features of a target triangle surface (edges whose dihedral angle exceeds a
//! threshold, and the corners of the feature graph) and closest-point queries on the surface,
//! on its feature lines and at its corners, for hex-mesh optimization (ARCHITECTURE §6.5).

#include "core/types.h"

#include <array>
#include <memory>
#include <utility>
#include <vector>

namespace polycube::optimize {

//! Feature graph of a triangle surface.
struct SurfaceFeatures {
  //! #FE feature edges as target vertex pairs (a < b), sorted: edges whose two faces' normals
  //! make an angle above the threshold, plus boundary and non-manifold edges.
  std::vector<std::array<int, 2>> edges;
  //! #FE feature line of each edge: lines are the chains of feature edges between corners
  //! (closed loops included), numbered by their lowest edge.
  std::vector<int> edge_line;
  int num_lines = 0;
  //! Target vertices of feature valence != 2 (endpoints, junctions), sorted.
  std::vector<int> corners;
};

//! Feature edges and corners of a triangle surface.
//! \param surface the target surface (degenerate faces are skipped when measuring angles)
//! \param angle_degrees an edge is sharp when the angle between its faces' normals exceeds
//!        this (0 < angle < 180)
//! \throw core::InputError on out-of-range indices
SurfaceFeatures detect_features(const core::TriMesh& surface, double angle_degrees);

//! A target surface with its features, answering closest-point queries (CGAL AABB trees).
//! Queries are const and thread-safe.
class TargetSurface {
 public:
  //! \param surface the target (kept by copy) \param features its features (may be empty)
  //! \throw core::InputError when the surface has no non-degenerate triangle
  TargetSurface(const core::TriMesh& surface, SurfaceFeatures features);
  ~TargetSurface();
  TargetSurface(TargetSurface&&) noexcept;
  TargetSurface& operator=(TargetSurface&&) noexcept;

  //! Closest point of the surface to p.
  [[nodiscard]] core::Vec3 closest_point(const core::Vec3& p) const;
  //! Outward unit normal of the surface's triangle closest to p (outward: the surface's
  //! orientation is flipped when its signed volume is negative).
  [[nodiscard]] core::Vec3 normal(const core::Vec3& p) const;
  //! Closest point to p of the triangles whose outward normal makes a positive dot product with
  //! n, and that triangle's normal, when it is at most `reach` farther than the closest point of
  //! all triangles: where the surface is thinner than the distance from p, the closest point may
  //! lie on the side facing away (the far side of an ear or a fin), and a boundary pulled there
  //! crosses the rest of the surface. Otherwise (or when n is zero) the closest point of all
  //! triangles and its normal: a boundary folded farther than `reach` is not sent across the
  //! model to a side that faces its way.
  [[nodiscard]] std::pair<core::Vec3, core::Vec3> closest_point_facing(const core::Vec3& p, const core::Vec3& n,
                                                                       double reach) const;
  //! Closest point of the feature lines to p (p itself when there is no feature edge).
  [[nodiscard]] core::Vec3 closest_feature_point(const core::Vec3& p) const;
  //! Index into features().corners of the corner nearest to p (-1 when there is none).
  [[nodiscard]] int nearest_corner(const core::Vec3& p) const;
  //! Position of corner k of features().corners.
  [[nodiscard]] core::Vec3 corner_position(int k) const;

  [[nodiscard]] const SurfaceFeatures& features() const;
  [[nodiscard]] bool has_features() const { return !features().edges.empty(); }
  [[nodiscard]] const core::TriMesh& surface() const;
  [[nodiscard]] double diagonal() const;  //!< bounding-box diagonal of the surface

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace polycube::optimize
