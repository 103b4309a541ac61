#include "padding/padding.h"

#include "core/progress.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "quality/singularities.h"

#include <fmt/format.h>

#include <algorithm>

namespace polycube::padding {

const char* mode_name(PaddingMode mode) {
  switch (mode) {
    case PaddingMode::None: return "none";
    case PaddingMode::Global: return "global";
    case PaddingMode::Selective: return "selective";
  }
  return "?";
}

MeshFigures mesh_figures(const core::HexMesh& mesh) {
  MeshFigures f;
  f.hexes = mesh.num_cells();
  const quality::HexSingularities s = quality::hex_singularities(mesh);
  f.singular_vertices = s.singular_vertices;
  f.singular_edges = s.singular_edges;
  f.scaled_jacobian = quality::scaled_jacobian(mesh, {.keep_values = false});
  std::vector<int> boundary_faces(mesh.cells.size(), 0);
  for (int c : core::boundary(mesh).cell_of_face) ++boundary_faces[c];
  f.multi_boundary_hexes = static_cast<int>(std::count_if(boundary_faces.begin(), boundary_faces.end(), [](int n) { return n >= 2; }));
  return f;
}

PadResult pad_hex_mesh(const core::HexMesh& mesh, const core::TriMesh& target, const std::vector<std::uint8_t>& selected,
                       const PadOptions& options) {
  const core::Stopwatch clock;
  core::ProgressTask progress("pad", 2);  // the sheet, then its optimization
  PadResult r;
  r.before = mesh_figures(mesh);
  SheetResult sheet = insert_sheet(mesh, selected, options.sheet);
  progress.step();
  r.mesh = std::move(sheet.mesh);
  r.padding_layer = std::move(sheet.padding_layer);
  r.source_hex = std::move(sheet.source_hex);
  r.added_hexes = sheet.added_hexes;
  r.crossing_hexes = sheet.crossing_hexes;
  r.selected_facets = sheet.facet_hexes;
  r.insert_seconds = sheet.seconds;
  if (options.run_optimizer) r.optimization = optimize::optimize_hex_mesh(r.mesh, target, options.optimize);
  r.check = optimize::check_foldover(r.mesh);
  r.distance = r.optimization.distance ? *r.optimization.distance : quality::hausdorff_distance(r.mesh, target);
  r.after = mesh_figures(r.mesh);
  r.seconds = clock.seconds();
  progress.step();
  progress.finish();
  return r;
}

std::string why_not_kept(const PadResult& padded, double unpadded_distance, double hausdorff_bound,
                         double usable_min_sj) {
  const double before = padded.before.scaled_jacobian.min, after = padded.after.scaled_jacobian.min;
  if (after < before && after < usable_min_sj)
    return fmt::format("its mSJ {:.3f} is below the unpadded {:.3f} and {:g}", after, before, usable_min_sj);
  if (padded.distance.relative > std::max(hausdorff_bound, unpadded_distance))
    return fmt::format("its boundary is {:.3f} % of the diagonal from the input, beyond the unpadded mesh's {:.3f} % "
                       "and the {:.2f} % bound",
                       100 * padded.distance.relative, 100 * unpadded_distance, 100 * hausdorff_bound);
  return {};
}

SelectivePlan plan_selective_padding(const core::HexMesh& mesh, const AnalysisOptions& analysis,
                                     const SelectionOptions& selection) {
  SelectivePlan plan;
  plan.analysis = analyze_mapping(mesh, analysis);
  plan.selection = select_facets_to_pad(mesh, plan.analysis.hard, selection);
  return plan;
}

core::MeshData plan_mesh_data(const core::HexMesh& mesh, const SelectivePlan& plan) {
  const auto faces = core::unique_faces(mesh);
  core::MeshData d;
  d.points = mesh.points;
  core::Field distortion{"distortion", {}}, propagated{"propagated", {}}, hard{"hard", {}}, padded{"padded", {}};
  for (int f = 0; f < faces.num_faces(); ++f) {
    if (!faces.is_boundary(f) && !plan.selection.facets[f]) continue;
    d.quads.push_back(faces.faces[f]);
    distortion.values.push_back(plan.analysis.distortion[f]);
    propagated.values.push_back(plan.analysis.propagated[f]);
    hard.values.push_back(plan.analysis.hard[f]);
    padded.values.push_back(plan.selection.facets[f]);
  }
  d.cell_data = {std::move(distortion), std::move(propagated), std::move(hard), std::move(padded)};
  return d;
}

core::MeshData padded_mesh_data(const PadResult& result) {
  core::MeshData d = core::to_mesh_data(result.mesh);
  core::Field layer{"padding_layer", {}}, source{"source_hex", {}};
  for (std::size_t h = 0; h < result.mesh.cells.size(); ++h) {
    layer.values.push_back(result.padding_layer[h]);
    source.values.push_back(result.source_hex[h]);
  }
  d.cell_data.push_back(std::move(layer));
  d.cell_data.push_back(std::move(source));
  if (!result.mesh.labels.empty()) {
    core::Field block{"block", {}};
    for (int l : result.mesh.labels) block.values.push_back(l);
    d.cell_data.push_back(std::move(block));
  }
  return d;
}

}  // namespace polycube::padding
