#pragma once
//! \file solid.h
//! \brief Internal to polycube_samples: a tiny CSG toolkit over CGAL, kept behind a pimpl so
//! that only the solid_*.cpp files include CGAL (its headers are slow to compile).
//!
//! A Solid is a closed, outward-oriented triangle surface in double precision whose triangles
//! remember the planar facet of the primitive they lie on. Booleans are exact corefinements
//! (CGAL, exact predicates, intersection points computed exactly and then rounded), followed by
//! a canonical re-triangulation of the facets so results never depend on the process state;
//! the final remeshing protects sharp feature edges so CAD edges stay crisp.

#include "core/types.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace polycube::samples::detail {

//! A simple polygon in the plane, counter-clockwise, without repeated vertices.
using Polygon2 = std::vector<Eigen::Vector2d>;

//! A right-handed or left-handed frame: world point = origin + u*e_u + v*e_v + w*e_w.
struct Frame {
  core::Vec3 origin = core::Vec3::Zero();
  core::Vec3 e_u = core::Vec3::UnitX();
  core::Vec3 e_v = core::Vec3::UnitY();
  core::Vec3 e_w = core::Vec3::UnitZ();
};

//! A closed, outward-oriented triangle surface (an immutable value: copies share the mesh).
class Solid {
 public:
  struct Impl;
  explicit Solid(std::shared_ptr<const Impl> impl);
  [[nodiscard]] const Impl& impl() const { return *impl_; }

 private:
  std::shared_ptr<const Impl> impl_;
};

//! Right prism: the polygon (in the frame's u,v plane) swept along e_w from w0 to w1 (w0 < w1).
//! Caps are ear-clipped; the result is outward-oriented whatever the frame's handedness.
Solid prism(const Polygon2& polygon, const Frame& frame, double w0, double w1);

//! Regular n-gon of circumradius r centred at c, counter-clockwise, first vertex at angle 0.
Polygon2 regular_polygon(const Eigen::Vector2d& c, double r, int n);

//! Axis-aligned rectangle [x0,x1] x [y0,y1], counter-clockwise.
Polygon2 rectangle(double x0, double y0, double x1, double y1);

//! Exact boolean union / difference (CGAL corefinement).
//! \throw core::InternalError if CGAL cannot produce a manifold result.
Solid unite(const Solid& a, const Solid& b);
Solid subtract(const Solid& a, const Solid& b);

//! Surface area of a solid.
double area(const Solid& s);

//! Parameters of the final remeshing.
struct RemeshParams {
  double target_edge_length = 1.0;  //!< mm
  double feature_angle_deg = 45.0;  //!< dihedral angle above which an edge is a CAD edge
  int iterations = 5;               //!< isotropic remeshing iterations
  int relaxation_steps = 3;         //!< tangential relaxation steps per iteration
};

//! Isotropic remeshing to an even triangle size with the sharp edges of `s` kept as
//! constraints (split and collapsed only along themselves, corners fixed), then checks the
//! result (closed, valid, no self-intersection) and copies it out with compact indices.
//! \throw core::InternalError if the result is not a valid closed surface.
core::TriMesh remesh(const Solid& s, const RemeshParams& params);

//! The solid as a TriMesh without remeshing (for inspection and tests of the toolkit).
core::TriMesh to_tri_mesh(const Solid& s);

}  // namespace polycube::samples::detail
