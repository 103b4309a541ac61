#include "quality/report.h"

#include "core/topology.h"
#include "quality/structure_topology.h"

namespace polycube::quality {

std::vector<core::Field> HexReport::fields() const {
  std::vector<core::Field> f;
  if (static_cast<int>(sj.values.size()) == hexes) f.push_back(sj.field("scaled_jacobian"));
  if (domains && static_cast<int>(domains->block_id.size()) == hexes)
    f.push_back(domains->field("block_id"));
  return f;
}

std::vector<core::Field> TetReport::fields() const {
  std::vector<core::Field> f;
  if (static_cast<int>(sj.values.size()) == tets) f.push_back(sj.field("scaled_jacobian"));
  return f;
}

std::vector<core::Field> QuadReport::fields() const {
  std::vector<core::Field> f;
  if (static_cast<int>(sj.values.size()) == quads) f.push_back(sj.field("scaled_jacobian"));
  if (domains && static_cast<int>(domains->patch_id.size()) == quads)
    f.push_back(domains->field("patch_id"));
  return f;
}

HexReport hex_report(const core::HexMesh& mesh, const ReportOptions& options) {
  HexReport r;
  r.hexes = mesh.num_cells();
  r.vertices = mesh.num_points();
  r.sj = scaled_jacobian(mesh, ScaledJacobianOptions{options.keep_per_element});
  if (options.structure) {
    const HexTopology t = hex_topology(mesh);
    r.singularities = hex_singularities(mesh, t);
    r.domains = hex_domains(mesh, t, *r.singularities, DomainOptions{options.keep_per_element});
    if (!options.keep_per_element) {
      r.singularities->edge_singular.clear();
      r.singularities->vertex_singular.clear();
    }
  }
  if (options.surface_layout || options.target) {
    const core::HexBoundary b = core::boundary(mesh);
    if (options.surface_layout && !b.surface.cells.empty()) {
      const QuadTopology qt = quad_topology(b.surface);
      const QuadSingularities qs = quad_singularities(b.surface, qt);
      r.surface_singular_vertices = qs.singular_vertices;
      r.surface_domains = quad_domains(b.surface, qt, qs, DomainOptions{false}).domains;
    }
    if (options.target)
      r.distance = hausdorff_distance(triangulate(b.surface), *options.target, options.distance);
  }
  return r;
}

TetReport tet_report(const core::TetMesh& mesh, const ReportOptions& options) {
  TetReport r;
  r.tets = mesh.num_cells();
  r.vertices = mesh.num_points();
  r.sj = scaled_jacobian(mesh, ScaledJacobianOptions{options.keep_per_element});
  return r;
}

QuadReport quad_report(const core::QuadMesh& mesh, const ReportOptions& options) {
  QuadReport r;
  r.quads = mesh.num_cells();
  r.vertices = mesh.num_points();
  r.sj = scaled_jacobian(mesh, ScaledJacobianOptions{options.keep_per_element});
  if (options.structure) {
    const QuadTopology t = quad_topology(mesh);
    r.singularities = quad_singularities(mesh, t);
    r.domains = quad_domains(mesh, t, *r.singularities, DomainOptions{options.keep_per_element});
    if (!options.keep_per_element) r.singularities->vertex_singular.clear();
  }
  if (options.target)
    r.distance = hausdorff_distance(triangulate(mesh), *options.target, options.distance);
  return r;
}

}  // namespace polycube::quality
