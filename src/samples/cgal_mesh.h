#pragma once
//! \file cgal_mesh.h
//! \brief Internal to polycube_samples: the CGAL types behind detail::Solid. Include only from
//! the solid_*.cpp files.

#include "samples/solid.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <string>

namespace polycube::samples::detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point3>;
using FaceIndex = SurfaceMesh::Face_index;
using FacetMap = SurfaceMesh::Property_map<FaceIndex, int>;

//! Name of the face property recording which planar facet of which primitive a triangle lies
//! on. Ids are only compared for equality, never ordered, so their values do not matter.
inline const std::string kFacetProperty = "f:facet";

//! The facet-id map of a mesh (added, filled with -1, if absent).
inline FacetMap facet_map(SurfaceMesh& m) {
  return m.add_property_map<FaceIndex, int>(kFacetProperty, -1).first;
}

//! A closed triangle surface whose faces carry facet ids, in canonical form (see canonicalize).
struct Solid::Impl {
  SurfaceMesh mesh;
};

//! Wrap a mesh as a Solid (takes ownership; the mesh must already be canonical).
inline Solid make_solid(SurfaceMesh&& mesh) {
  auto impl = std::make_shared<Solid::Impl>();
  impl->mesh = std::move(mesh);
  return Solid(std::move(impl));
}

//! Rebuild a closed, facet-labelled surface in a canonical form that depends only on its
//! geometry, not on how it was triangulated.
//!
//! Why: CGAL's corefinement output varies with the heap layout of the process (some internal
//! tie-breaks compare addresses), so two runs can split the same planar facets differently.
//! The canonical form keeps only the essential vertices (where three or more facets meet, or a
//! facet outline bends), snapped to a 2^-24 mm grid, drops the vertices corefinement added
//! along straight facet outlines, and re-triangulates every facet with a constrained Delaunay
//! triangulation of its outline, inserting vertices and constraints in sorted order. Vertices
//! are numbered in lexicographic order of their coordinates and faces in facet order.
//! \throw core::InternalError if the facet outlines do not form a valid closed surface.
SurfaceMesh canonicalize(SurfaceMesh& mesh);

}  // namespace polycube::samples::detail
