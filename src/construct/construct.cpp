//! The whole construction chain (see construct.h).
#include "construct/construct.h"

#include "construct/labeling_check.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "quality/distortion.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

namespace polycube::construct {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string defects_text(const LabelingCheck& check, std::size_t max_listed = 5) {
  std::string s;
  for (std::size_t i = 0; i < check.defects.size() && i < max_listed; ++i)
    s += (i ? "; " : "") + check.defects[i].reason;
  if (check.defects.size() > max_listed) s += fmt::format("; and {} more", check.defects.size() - max_listed);
  return s;
}

}  // namespace

ConstructResult construct_from_prepared(const core::TetMesh& mesh, const ConstructOptions& o) {
  auto& log = core::logger();
  const auto t0 = Clock::now();
  ConstructResult res;

  // Labeling, repair, deformation; when the map cannot be untangled, revisit the labeling with
  // other compactness weights (each attempt is a different valid labeling).
  const core::TetBoundary bnd = core::boundary(mesh);
  std::vector<core::Tri> tris(bnd.surface.cells.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto& s = bnd.surface.cells[f];
    tris[f] = {bnd.vertex_map[s[0]], bnd.vertex_map[s[1]], bnd.vertex_map[s[2]]};
  }
  std::vector<double> factors{1.0};
  for (double f : o.retry_compactness_factors) factors.push_back(f);
  DeformResult def;
  std::string failures;
  bool done = false;
  for (std::size_t attempt = 0; attempt < factors.size() && !done; ++attempt) {
    LabelingOptions lopt = o.labeling;
    lopt.compactness *= factors[attempt];
    auto t = Clock::now();
    const LabelingResult lab = graph_cut_labeling(bnd.surface, lopt);
    res.seconds.label += since(t);
    t = Clock::now();
    RepairOptions ropt = o.repair;
    ropt.energy = lopt;
    const RepairResult rep = repair_labeling(bnd.surface, lab.labels, ropt);
    res.seconds.repair += since(t);
    res.repair_moves = rep.moves;
    if (!rep.valid()) {
      failures += fmt::format("{}compactness {:.3g}: no valid labeling ({} defect(s): {})", failures.empty() ? "" : "; ",
                              lopt.compactness, rep.check.defects.size(), defects_text(rep.check, 2));
      continue;
    }
    log.info("construct: labeling valid ({} charts, compactness {:.3g}) in {:.2f} s + repair {:.2f} s",
             rep.check.layout.num_charts(), lopt.compactness, res.seconds.label, res.seconds.repair);
    def = deform_to_polycube(mesh, tris, rep.labels, o.deform);
    res.seconds.deform += def.seconds_linear;
    res.seconds.untangle += def.seconds_untangle;
    log.info("construct: deformation {:.2f} s ({} inverted after the linear step), untangling {:.2f} s "
             "({} iterations, {} Newton steps, min det {:.3g}, {} inverted)",
             def.seconds_linear, def.inverted_after_linear, def.seconds_untangle, def.untangle.iterations,
             def.untangle.newton_steps, def.untangle.min_det, def.untangle.inverted_after);
    done = def.untangle.untangled;
    if (!done)
      failures += fmt::format("{}compactness {:.3g}: {} tets stay inverted", failures.empty() ? "" : "; ",
                              lopt.compactness, def.untangle.inverted_after);
  }
  if (def.polycube.empty())
    throw core::SolverError("no valid polycube labeling reached: " + failures);
  if (!done) log.warn("construct: every attempt left inverted tets ({})", failures);
  res.split_triangles = def.split_triangles;
  res.split_edges = def.split_edges;
  res.refined_edges = def.refined_edges;
  res.inverted_after_linear = def.inverted_after_linear;
  res.untangle = def.untangle;

  // Certification.
  const auto t = Clock::now();
  res.map.tets = def.mesh.cells;
  res.map.model = def.mesh.points;
  res.map.polycube = def.polycube;
  res.certificate = certify_polycube_map(res.map, def.boundary, def.labels, o.certify);
  if (!res.certificate.certified())
    throw core::GeometryError("polycube map not certified: " + res.certificate.reason() +
                              (failures.empty() ? std::string() : " (attempts: " + failures + ")"));

  // Boundary in core::boundary() order (the order of the written Triangles blocks).
  const core::TetBoundary fb = core::boundary(def.mesh);
  std::vector<std::pair<std::array<int, 3>, int>> keys(def.boundary.size());
  for (std::size_t i = 0; i < def.boundary.size(); ++i) {
    std::array<int, 3> k{def.boundary[i][0], def.boundary[i][1], def.boundary[i][2]};
    std::sort(k.begin(), k.end());
    keys[i] = {k, def.labels[i]};
  }
  std::sort(keys.begin(), keys.end());
  core::TriMesh surface;
  surface.points = def.mesh.points;
  for (const auto& s : fb.surface.cells) {
    const core::Tri tri{fb.vertex_map[s[0]], fb.vertex_map[s[1]], fb.vertex_map[s[2]]};
    std::array<int, 3> k{tri[0], tri[1], tri[2]};
    std::sort(k.begin(), k.end());
    const auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    PC_REQUIRE(it != keys.end() && it->first == k, "construct: certified boundary lost a triangle");
    res.boundary.push_back(tri);
    res.labels.push_back(it->second);
    surface.cells.push_back(tri);
  }
  const LabelingCheck check = check_labeling(surface, res.labels);
  res.charts = check.layout.num_charts();
  res.corners = static_cast<int>(check.layout.corners.size());
  res.boundaries = check.layout.num_boundaries;
  res.fidelity = labeling_fidelity(surface, res.labels);
  quality::DistortionOptions dopt;
  dopt.normalize_volume = true;
  dopt.keep_per_tet = false;
  const quality::MapDistortion dist = quality::map_distortion(def.mesh, def.polycube, dopt);
  res.isometric_average = dist.isometric.average;
  res.isometric_max = dist.isometric.max;
  res.conformal_average = dist.conformal.average;
  res.conformal_max = dist.conformal.max;
  res.seconds.certify = since(t);
  res.seconds.total = since(t0);
  return res;
}

ConstructResult construct_polycube(const core::TriMesh& surface, const ConstructOptions& o) {
  const auto t0 = Clock::now();
  TetrahedralizeResult tr = tetrahedralize(surface, o.tetrahedralize);
  const double t_tet = since(t0);
  ConstructResult res = construct_from_prepared(tr.mesh, o);
  res.tetgen_tets = tr.tetgen_tets;
  res.refine = tr.refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

ConstructResult construct_polycube(core::TetMesh mesh, const ConstructOptions& o) {
  const auto t0 = Clock::now();
  prepare_tet_mesh(mesh);
  const RefineStats refine = refine_boundary(mesh);
  const double t_tet = since(t0);
  ConstructResult res = construct_from_prepared(mesh, o);
  res.refine = refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

}  // namespace polycube::construct
