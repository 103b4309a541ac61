//! Feature-preserving isotropic remeshing of the samples' CSG results (CGAL PMP).
#include "samples/cgal_mesh.h"

#include "core/errors.h"

#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/helpers.h>

#include <string>

namespace polycube::samples::detail {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw core::InternalError("sample remeshing produced an invalid surface: " + what);
}

}  // namespace

core::TriMesh remesh(const Solid& s, const RemeshParams& params) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  using Edge = SurfaceMesh::Edge_index;
  using Face = SurfaceMesh::Face_index;
  using Vertex = SurfaceMesh::Vertex_index;
  PC_REQUIRE(params.target_edge_length > 0.0, "remesh: target edge length must be positive");

  SurfaceMesh m = s.impl().mesh;

  // CAD edges: dihedral angle above the threshold. They split the surface into patches, each
  // remeshed and projected on its own, so vertices never hop across a sharp edge.
  auto is_feature = m.add_property_map<Edge, bool>("e:is_feature", false).first;
  auto patch = m.add_property_map<Face, std::size_t>("f:patch", 0).first;
  PMP::sharp_edges_segmentation(m, params.feature_angle_deg, is_feature, patch);

  // Corners (a feature degree other than 0 or 2) never move; feature edges may be split and
  // collapsed only along their own polyline, and their vertices are not relaxed, so every
  // feature vertex stays on the input's feature polylines: the CAD edges stay crisp.
  auto is_corner = m.add_property_map<Vertex, bool>("v:is_corner", false).first;
  for (Vertex v : m.vertices()) {
    int degree = 0;
    for (auto h : CGAL::halfedges_around_target(v, m))
      if (is_feature[m.edge(h)]) ++degree;
    is_corner[v] = degree != 0 && degree != 2;
  }

  PMP::isotropic_remeshing(
      faces(m), params.target_edge_length, m,
      CGAL::parameters::number_of_iterations(static_cast<unsigned int>(params.iterations))
          .number_of_relaxation_steps(static_cast<unsigned int>(params.relaxation_steps))
          .edge_is_constrained_map(is_feature)
          .vertex_is_constrained_map(is_corner)
          .face_patch_map(patch)
          .protect_constraints(false)
          .relax_constraints(false));
  m.collect_garbage();

  // Re-validate before handing the surface out (ARCHITECTURE §9).
  if (!m.is_valid(false)) fail("invalid halfedge structure");
  if (!CGAL::is_closed(m)) fail("not closed");
  if (!CGAL::is_triangle_mesh(m)) fail("not a triangle mesh");
  if (PMP::does_self_intersect(m)) fail("self-intersecting");
  if (!PMP::is_outward_oriented(m)) fail("not outward oriented");

  return to_tri_mesh(make_solid(std::move(m)));
}

}  // namespace polycube::samples::detail
