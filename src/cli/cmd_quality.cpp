//! `polycube quality FILE [--vtk OUT.vtk] [--target SURFACE]`: the quality and structure numbers of
//! the thesis's tables for a hex, tet or quad mesh (scaled Jacobian, singularities, base-complex
//! domains, distance to a target surface).
#include "cli/app.h"
#include "core/errors.h"
#include "core/log.h"
#include "io/mesh_io.h"
#include "quality/report.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

namespace polycube::cli {

namespace {

struct QualityOptions {
  std::string input;
  std::string vtk;     //!< optional output with per-element cell data
  std::string target;  //!< optional reference surface for the Hausdorff distance
  double tolerance = quality::SurfaceDistanceOptions{}.tolerance;
};

std::string sj_text(const quality::ScaledJacobianSummary& s) {
  return fmt::format("  {:<10}{:.4f}\n  {:<10}{:.4f}\n  {:<10}{}\n  {:<10}{}\n", "mSJ", s.min,
                     "aSJ", s.average, "inverted", s.inverted, "invalid", s.invalid);
}

std::string histogram_text(const quality::ScaledJacobianSummary& s) {
  std::string t = "  SJ histogram\n";
  for (int i = 0; i < quality::kHistogramBins; ++i) {
    const double pct = s.count > 0 ? 100.0 * s.histogram[i] / s.count : 0.0;
    t += fmt::format("    {}{:4.1f}, {:3.1f}]  {:>9}  {:5.1f}%\n", i == 0 ? '[' : '(',
                     quality::histogram_bin_lower(i), quality::histogram_bin_upper(i),
                     s.histogram[i], pct);
  }
  return t;
}

nlohmann::json point_json(const core::Vec3& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::json distance_json(const quality::SurfaceDistance& d) {
  return {{"hausdorff", d.hausdorff},
          {"hausdorff_upper_bound", d.hausdorff_upper},
          {"relative", d.relative},
          {"reference_diagonal", d.reference_diagonal},
          {"mesh_to_target", d.surface_to_reference.max},
          {"target_to_mesh", d.reference_to_surface.max},
          {"mean_mesh_to_target", d.surface_to_reference.mean},
          {"mean_target_to_mesh", d.reference_to_surface.mean},
          {"mesh_to_target_worst_point", point_json(d.surface_to_reference.worst_point)},
          {"target_to_mesh_worst_point", point_json(d.reference_to_surface.worst_point)}};
}

std::string distance_text(const quality::SurfaceDistance& d) {
  return fmt::format(
      "  Hausdorff distance to the target {:.6g} ({:.4f}% of its bounding-box diagonal), "
      "at most {:.6g}\n"
      "    mesh -> target {:.6g} (mean {:.3g}, worst at ({:.4g}, {:.4g}, {:.4g})), target -> mesh {:.6g} "
      "(mean {:.3g}, worst at ({:.4g}, {:.4g}, {:.4g}))\n",
      d.hausdorff, 100.0 * d.relative, d.hausdorff_upper, d.surface_to_reference.max, d.surface_to_reference.mean,
      d.surface_to_reference.worst_point.x(), d.surface_to_reference.worst_point.y(),
      d.surface_to_reference.worst_point.z(), d.reference_to_surface.max, d.reference_to_surface.mean,
      d.reference_to_surface.worst_point.x(), d.reference_to_surface.worst_point.y(),
      d.reference_to_surface.worst_point.z());
}

void write_vtk(const std::string& path, core::MeshData data, std::vector<core::Field> fields) {
  data.cell_data = std::move(fields);
  io::write_mesh(path, data);
}

void run_quality(const QualityOptions& o) {
  if (!o.vtk.empty()) {
    std::string ext = std::filesystem::path(o.vtk).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (ext != ".vtk")
      throw core::InputError("--vtk expects a file name ending in .vtk, got " + o.vtk);
  }
  const core::MeshData d = io::read_mesh(o.input);
  std::optional<core::TriMesh> target;
  quality::ReportOptions ro;
  ro.keep_per_element = !o.vtk.empty();
  ro.distance.tolerance = o.tolerance;
  if (!o.target.empty()) {
    target = io::read_surface(o.target);
    ro.target = &*target;
  }

  nlohmann::json j;
  j["file"] = o.input;
  std::string text;
  if (!d.hexes.empty()) {
    const core::HexMesh m = core::hexes_of(d);
    core::logger().info("quality: analysing {} hexahedra", m.num_cells());
    const quality::HexReport r = quality::hex_report(m, ro);
    j["cell_type"] = "hex";
    j["cells"] = r.hexes;
    j["vertices"] = r.vertices;
    j["scaled_jacobian"] = scaled_jacobian_json(r.sj);
    j["singular_vertices"] = r.singularities->singular_vertices;
    j["singular_edges"] = r.singularities->singular_edges;
    j["boundary_singular_edges"] = r.singularities->boundary_singular_edges;
    j["interior_singular_edges"] = r.singularities->interior_singular_edges;
    j["domains"] = r.domains->domains;
    j["surface"] = {{"singular_vertices", r.surface_singular_vertices},
                    {"domains", r.surface_domains}};
    text =
        fmt::format("{}: hex mesh, {} vertices\n  {:<10}{}\n", o.input, r.vertices, "#H", r.hexes);
    text += sj_text(r.sj);
    text += fmt::format("  {:<10}{}\n  {:<10}{}  ({} on the boundary, {} interior)\n  {:<10}{}\n",
                        "#Sv", r.singularities->singular_vertices, "#Se",
                        r.singularities->singular_edges, r.singularities->boundary_singular_edges,
                        r.singularities->interior_singular_edges, "#D", r.domains->domains);
    text += fmt::format("  boundary quad layout: #sv {}, #dom {}\n", r.surface_singular_vertices,
                        r.surface_domains);
    if (r.distance) {
      j["distance"] = distance_json(*r.distance);
      text += distance_text(*r.distance);
    }
    text += histogram_text(r.sj);
    if (!o.vtk.empty()) write_vtk(o.vtk, core::to_mesh_data(m), r.fields());
  } else if (!d.tets.empty()) {
    const core::TetMesh m = core::tets_of(d);
    const quality::TetReport r = quality::tet_report(m, ro);
    if (target) core::logger().warn("quality: --target is only used for hex and quad meshes");
    j["cell_type"] = "tet";
    j["cells"] = r.tets;
    j["vertices"] = r.vertices;
    j["scaled_jacobian"] = scaled_jacobian_json(r.sj);
    text =
        fmt::format("{}: tet mesh, {} vertices\n  {:<10}{}\n", o.input, r.vertices, "#T", r.tets);
    text += sj_text(r.sj) + histogram_text(r.sj);
    if (!o.vtk.empty()) write_vtk(o.vtk, core::to_mesh_data(m), r.fields());
  } else if (!d.quads.empty()) {
    const core::QuadMesh m = core::quads_of(d);
    const quality::QuadReport r = quality::quad_report(m, ro);
    j["cell_type"] = "quad";
    j["cells"] = r.quads;
    j["vertices"] = r.vertices;
    j["scaled_jacobian"] = scaled_jacobian_json(r.sj);
    j["singular_vertices"] = r.singularities->singular_vertices;
    j["domains"] = r.domains->domains;
    text =
        fmt::format("{}: quad mesh, {} vertices\n  {:<10}{}\n", o.input, r.vertices, "#Q", r.quads);
    text += sj_text(r.sj);
    text += fmt::format("  {:<10}{}\n  {:<10}{}\n", "#sv", r.singularities->singular_vertices,
                        "#dom", r.domains->domains);
    if (r.distance) {
      j["distance"] = distance_json(*r.distance);
      text += distance_text(*r.distance);
    }
    text += histogram_text(r.sj);
    if (!o.vtk.empty()) write_vtk(o.vtk, core::to_mesh_data(m), r.fields());
  } else {
    throw core::InputError(o.input + ": no hexahedra, tetrahedra or quads to analyse");
  }
  if (!o.vtk.empty()) j["vtk"] = o.vtk;
  print_result(j, text);
}

}  // namespace

void register_quality(CLI::App& app) {
  auto opts = std::make_shared<QualityOptions>();
  CLI::App* sub = app.add_subcommand("quality",
                                     "Scaled Jacobian (Verdict), singularities (#Sv, #Se), "
                                     "base-complex domains (#D) of a hex, tet or quad "
                                     "mesh, and its distance to a target surface");
  sub->add_option("file", opts->input, "Mesh file (.mesh .vtk .msh, or a quad surface)")
      ->required();
  sub->add_option("--vtk", opts->vtk,
                  "Write the mesh with per-element scaled_jacobian and block_id cell data");
  sub->add_option("--target", opts->target,
                  "Reference surface: report the Hausdorff distance of the mesh's boundary to it");
  sub->add_option(
         "--tolerance", opts->tolerance,
         "Accuracy of the Hausdorff distance, relative to the target's bounding-box diagonal")
      ->check(cli::positive())
      ->capture_default_str();
  sub->callback([opts] { run_quality(*opts); });
}

}  // namespace polycube::cli
