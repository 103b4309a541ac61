//! Steps more than one stage of the chain takes (see stage_steps.h).
#include "pipeline/stage_steps.h"

#include "core/progress.h"
#include "io/mesh_io.h"
#include "quality/report.h"
#include "quality/scaled_jacobian.h"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

namespace polycube::pipeline {

int injected_steps(const std::string& inject, const std::string& prefix) {
  if (inject.size() != prefix.size() + 1 || inject.rfind(prefix, 0) != 0) return 0;
  const char n = inject.back();
  return n >= '1' && n <= '9' ? n - '0' : 0;
}

void write_vtk(const std::filesystem::path& path, core::MeshData data, std::vector<core::Field> fields) {
  data.cell_data = std::move(fields);
  io::write_mesh(path, data);
}

core::HexMesh grid_and_write(const core::PolycubeMap& map, int target, mesh::GridSizing sizing,
                             const std::filesystem::path& out_dir, RunResult& r,
                             const FileWritten& wrote, const std::vector<core::Vec3>& refine_near) {
  mesh::GridOptions go;
  go.target_hexes = target;
  go.sizing = sizing;
  go.refine_near = refine_near;
  mesh::GridResult g = mesh::grid_polycube(map, go);
  if (!g.snapping.ok())
    throw core::GeometryError("snapping the polycube to the lattice broke it: " + g.snapping.summary());
  r.grid_scale = g.scale;
  r.hexes = static_cast<int>(g.hex_model.cells.size());
  r.quads = static_cast<int>(g.quad_model.cells.size());
  const quality::ScaledJacobianSummary sj = quality::scaled_jacobian(g.hex_model);
  r.inverted_gridded = sj.inverted + sj.invalid;
  r.msj_gridded = sj.min;
  r.asj_gridded = sj.average;
  io::write_mesh(out_dir / "hex.mesh", core::to_mesh_data(g.hex_model));
  wrote(out_dir / "hex.mesh");
  quality::ReportOptions qo;
  qo.structure = true;
  const quality::QuadReport qr = quality::quad_report(g.quad_model, qo);
  write_vtk(out_dir / "quad.vtk", core::to_mesh_data(g.quad_model), qr.fields());
  wrote(out_dir / "quad.vtk");
  return std::move(g.hex_model);
}

std::string fold_summary(const optimize::FoldoverReport& fold) {
  return fmt::format("{} inverted hexes, {} with a non-positive scaled Jacobian, {} boundary self-intersections",
                     fold.inverted_hexes, fold.nonpositive_scaled_jacobian, fold.boundary_self_intersections);
}

void record_plan(const padding::SelectivePlan& plan, RunResult& r) {
  r.padding_hard_facets = plan.analysis.hard_facets;
  r.padding_plan_optimal = plan.selection.optimal;
  r.padding_plan_gap = plan.selection.gap;
  r.padding_plan_solver = plan.selection.solver;
  r.padding_analysis_seconds = plan.analysis.seconds;
  r.padding_solve_seconds = plan.selection.seconds;
  r.padding_selected_facets = plan.selection.selected;
  r.padding_edge_turns = plan.selection.edge_turns;
  r.padding_vertex_turns = plan.selection.vertex_turns;
}

void record_padding(const padding::PadResult& p, const std::string& how, RunResult& r) {
  r.padding = how;
  r.padding_added = p.added_hexes;
  r.singular_vertices_before = p.before.singular_vertices;
  r.singular_edges_before = p.before.singular_edges;
  r.singular_vertices_after = p.after.singular_vertices;
  r.singular_edges_after = p.after.singular_edges;
  r.padding_insert_seconds = p.insert_seconds;
  r.padding_optimize_seconds = p.optimization.seconds;
  r.iterations_optimize = p.optimization.untangle.iterations + p.optimization.quality.iterations;
}

namespace {

//! The facets `mode` pads on this mesh; empty when selective padding finds nothing to pad.
std::vector<std::uint8_t> padding_facets(const core::HexMesh& hex, padding::PaddingMode mode, const RunOptions& o,
                                         RunResult& r) {
  if (mode == padding::PaddingMode::Global) return padding::boundary_selection(hex);
  padding::SelectivePlan plan = padding::plan_selective_padding(hex, o.padding_analysis, o.padding_selection);
  record_plan(plan, r);
  if (plan.selection.selected == 0) return {};
  return std::move(plan.selection.facets);
}

}  // namespace

std::optional<padding::PadResult> pad_and_record(const core::HexMesh& hex, const ConstructInput& in,
                                                 const RunOptions& o, padding::PaddingMode mode, const std::string& how,
                                                 const std::filesystem::path& out_dir, RunResult& r,
                                                 const FileWritten& wrote, const std::function<void(int)>& planned) {
  // Two steps for the progress bar: which facets (the selective plan solves a MILP), then the
  // sheet and its optimization.
  core::ProgressTask progress("pad", 2);
  const std::vector<std::uint8_t> facets = padding_facets(hex, mode, o, r);
  if (planned) planned(static_cast<int>(std::count(facets.begin(), facets.end(), 1)));
  progress.step();
  if (facets.empty()) return std::nullopt;
  padding::PadResult p = padding::pad_hex_mesh(hex, in.target, facets, o.padding_options);
  in.distances.remember(p.mesh, p.distance);
  progress.step();
  progress.finish();
  record_padding(p, how, r);
  if (p.check.ok()) write_padded(p, out_dir, wrote);
  return p;
}

void write_padded(const padding::PadResult& p, const std::filesystem::path& out_dir, const FileWritten& wrote) {
  io::write_mesh(out_dir / "hex_padded.mesh", core::to_mesh_data(p.mesh));
  wrote(out_dir / "hex_padded.mesh");
  io::write_mesh(out_dir / "hex_padded.vtk", padding::padded_mesh_data(p));
  wrote(out_dir / "hex_padded.vtk");
}

void discard_padded(const std::filesystem::path& out_dir, RunResult& r) {
  for (const char* name : {"hex_padded.mesh", "hex_padded.vtk"}) {
    std::error_code ec;
    std::filesystem::remove(out_dir / name, ec);
    std::erase(r.files, (out_dir / name).string());
  }
}

}  // namespace polycube::pipeline
