//! The labeling stage on its own (see label_surface.h).
#include "construct/label_surface.h"

#include "core/stopwatch.h"
#include "core/topology.h"

#include <utility>

namespace polycube::construct {

namespace {

//! Label the boundary of a prepared tet mesh (boundary refined, positively oriented) and
//! repair the labeling; fills everything but the tetrahedralization figures.
void label_prepared(LabelSurfaceResult& res, const LabelSurfaceOptions& o) {
  res.boundary = core::boundary(res.mesh);
  res.boundary_triangles = core::boundary_triangles(res.boundary);
  const core::TriMesh& s = res.boundary.surface;
  const core::Stopwatch clock;

  // With a pre-deformation the fidelity term reads the normals of the pre-deformed surface,
  // which cluster around the axes; the compactness weights keep reading the model's.
  LabelingOptions labeling = o.labeling;
  if (o.predeform.iterations > 0) {
    res.predeform = predeform(res.mesh, res.boundary_triangles, o.predeform);
    labeling.data_normals = triangle_normals(res.predeform.points, res.boundary_triangles);
  }
  CutAndRepair cr = cut_and_repair(s, labeling, o.repair);  // as construct does
  LabelingResult& lab = cr.cut;
  RepairResult& rep = cr.repair;
  res.seconds.label_and_repair = clock.seconds();

  res.fidelity = labeling_fidelity(s, rep.labels);
  res.estimate = estimate_polycube(s, rep.labels);
  res.fidelity_before_repair = labeling_fidelity(s, lab.labels);
  res.initial_defects = rep.initial_defects;
  res.repair_moves = rep.moves;
  res.labels = std::move(rep.labels);
  res.check = std::move(rep.check);
  res.initial_labels = std::move(lab.labels);
}

}  // namespace

LabelSurfaceResult label_surface(const core::TriMesh& surface, const LabelSurfaceOptions& o) {
  const core::Stopwatch clock;
  TetrahedralizeResult tr = tetrahedralize(surface, o.tetrahedralize);
  LabelSurfaceResult res;
  res.mesh = std::move(tr.mesh);
  res.tetgen_tets = tr.tetgen_tets;
  res.refine = tr.refine;
  res.seconds.tetrahedralize = clock.seconds();
  label_prepared(res, o);
  return res;
}

LabelSurfaceResult label_surface(core::TetMesh mesh, const LabelSurfaceOptions& o) {
  const core::Stopwatch clock;
  mesh.labels.clear();
  prepare_tet_mesh(mesh);
  LabelSurfaceResult res;
  res.refine = refine_boundary(mesh);
  res.mesh = std::move(mesh);
  res.seconds.tetrahedralize = clock.seconds();
  label_prepared(res, o);
  return res;
}

}  // namespace polycube::construct
