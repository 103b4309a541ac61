//! `polycube pad HEX --target SURFACE -o OUT [--global | --facets F]`: insert a padding layer
//! along a facet set (thesis ch. 4), optimize it against the target, check it, report the
//! figures of thesis Table 4.1 before and after.
#include "cli/app.h"
#include "core/errors.h"
#include "io/mesh_io.h"
#include "padding/padding.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace polycube::cli {

namespace {

struct PadCliOptions {
  std::string input;
  TargetOption target;
  std::string output;
  std::string vtk;     //!< optional VTK copy with the padding_layer / source_hex / block fields
  std::string plan_vtk;  //!< selective: the analysis and the selection as boundary quads (VTK)
  std::string analysis_mesh;  //!< selective: analyse this mesh (same hexes) instead of the input
  std::string report;  //!< optional JSON report
  std::string facets;  //!< facet file; empty: global padding
  bool global = false;
  bool selective = false;
  bool no_optimize = false;
  padding::AnalysisOptions analysis;
  padding::SelectionOptions selection;
  bool keep_failed = false;
  padding::PadOptions pad;
};

//! Facets from a text file: one facet per line as its 4 vertex ids (0-based, the order of the
//! mesh file's points); blank lines and lines starting with '#' are skipped.
std::vector<core::Quad> read_facet_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot open the facet file");
  std::vector<core::Quad> quads;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream words(line);
    core::Quad q{};
    std::string extra;
    if (!(words >> q[0] >> q[1] >> q[2] >> q[3]) || (words >> extra))
      throw core::InputError(fmt::format("{}:{}: expected 4 vertex ids, got \"{}\"", path, number, line));
    quads.push_back(q);
  }
  if (quads.empty()) throw core::InputError(path + ": no facet in the facet file");
  return quads;
}

nlohmann::json figures_json(const padding::MeshFigures& f) {
  return {{"hexes", f.hexes},
          {"singular_vertices", f.singular_vertices},
          {"singular_edges", f.singular_edges},
          {"multi_boundary_hexes", f.multi_boundary_hexes},
          {"scaled_jacobian", scaled_jacobian_json(f.scaled_jacobian)}};
}

std::string figures_table(const padding::PadResult& r) {
  std::string t = fmt::format("  {:<10}{:>10}{:>10}\n", "", "before", "after");
  t += fmt::format("  {:<10}{:>10}{:>10}\n", "#H", r.before.hexes, r.after.hexes);
  t += fmt::format("  {:<10}{:>10}{:>10}\n", "#Sv", r.before.singular_vertices, r.after.singular_vertices);
  t += fmt::format("  {:<10}{:>10}{:>10}\n", "#Se", r.before.singular_edges, r.after.singular_edges);
  t += fmt::format("  {:<10}{:>10}{:>10}  (hexes with 2+ boundary faces)\n", "#H2+", r.before.multi_boundary_hexes,
                   r.after.multi_boundary_hexes);
  t += fmt::format("  {:<10}{:>10.4f}{:>10.4f}\n", "mSJ", r.before.scaled_jacobian.min, r.after.scaled_jacobian.min);
  t += fmt::format("  {:<10}{:>10.4f}{:>10.4f}\n", "aSJ", r.before.scaled_jacobian.average,
                   r.after.scaled_jacobian.average);
  t += fmt::format("  {:<10}{:>10}{:>10}\n", "inverted", r.before.scaled_jacobian.inverted + r.before.scaled_jacobian.invalid,
                   r.after.scaled_jacobian.inverted + r.after.scaled_jacobian.invalid);
  return t;
}

//! The facets to pad and how they were chosen (global, a facet file, or selective padding with
//! its report in j and text).
struct Choice {
  std::vector<std::uint8_t> facets;
  std::string how = "global";
  std::string text;
};

//! The mesh the mapping analysis looks at: the input, or --analysis-mesh (e.g. the gridded mesh
//! before optimization, where the map's distortion is still visible), which must have its hexes.
core::HexMesh analysed_mesh(const core::HexMesh& mesh, const PadCliOptions& o) {
  if (o.analysis_mesh.empty()) return mesh;
  core::HexMesh other = core::hexes_of(io::read_mesh(o.analysis_mesh));
  if (other.cells != mesh.cells)
    throw core::InputError(o.analysis_mesh + ": --analysis-mesh must have the same hexes as " + o.input +
                           " (e.g. the gridded hex.mesh of an optimized hex_optimized.mesh)");
  return other;
}

Choice choose_selectively(const core::HexMesh& mesh, const PadCliOptions& o, nlohmann::json& j) {
  const padding::SelectivePlan plan = padding::plan_selective_padding(analysed_mesh(mesh, o), o.analysis, o.selection);
  if (!o.plan_vtk.empty()) {
    io::write_mesh(o.plan_vtk, padding::plan_mesh_data(mesh, plan));
    j["plan_vtk"] = o.plan_vtk;
  }
  const padding::Analysis& a = plan.analysis;
  const padding::Selection& sel = plan.selection;
  j["analysis"] = {{"threshold", o.analysis.threshold}, {"propagation", o.analysis.propagation},
                   {"analysed_hexes", a.analysed_hexes}, {"distorted_edges", a.distorted_edges},
                   {"hard_facets", a.hard_facets},       {"seconds", a.seconds}};
  j["selection"] = {{"lambda", o.selection.lambda}, {"selected_facets", sel.selected},
                    {"edge_turns", sel.edge_turns},   {"vertex_turns", sel.vertex_turns},
                    {"objective", sel.objective},     {"optimal", sel.optimal},
                    {"gap", sel.gap},                 {"variables", sel.variables},
                    {"rows", sel.rows},               {"solver", sel.solver},
                    {"seconds", sel.seconds}};
  Choice c{sel.facets, "selective", ""};
  c.text = fmt::format(
      "  analysis: {} boundary hexes below SJ {}, {} distorted edges, |HF| = {} ({:.2f} s)\n"
      "  binary problem: |PF| = {}, {} edge and {} vertex turns, {} ({} variables, {} rows, {}, {:.2f} s)\n",
      a.analysed_hexes, o.analysis.threshold, a.distorted_edges, a.hard_facets, a.seconds, sel.selected,
      sel.edge_turns, sel.vertex_turns,
      sel.optimal ? std::string("optimal") : fmt::format("not proven optimal, gap {:.1f}%", 100.0 * sel.gap),
      sel.variables, sel.rows, sel.solver, sel.seconds);
  return c;
}

Choice choose_facets(const core::HexMesh& mesh, const PadCliOptions& o, nlohmann::json& j) {
  if (o.selective) return choose_selectively(mesh, o, j);
  if (!o.facets.empty()) return {padding::select_facets(mesh, read_facet_file(o.facets)), o.facets, ""};
  return {padding::boundary_selection(mesh), "global", ""};
}

void add_result_json(nlohmann::json& j, const padding::PadResult& r) {
  j["selected_facets"] = r.selected_facets;
  j["added_hexes"] = r.added_hexes;
  j["crossing_hexes"] = r.crossing_hexes;
  j["before"] = figures_json(r.before);
  j["after"] = figures_json(r.after);
  j["hausdorff"] = {{"absolute", r.distance.hausdorff}, {"relative", r.distance.relative}};
  j["check"] = foldover_json(r.check);
  j["seconds"] = {{"insertion", r.insert_seconds}, {"optimization", r.optimization.seconds}, {"total", r.seconds}};
}

std::string result_text(const PadCliOptions& o, const Choice& c, const padding::PadResult& r) {
  std::string text = fmt::format("{}: {} facets padded ({}), {} hexes added\n", o.input, r.selected_facets, c.how,
                                 r.added_hexes);
  text += c.text;
  text += figures_table(r);
  text += fmt::format("  Hausdorff to the target {:.6g} ({:.4f}% of its bounding-box diagonal)\n", r.distance.hausdorff,
                      100.0 * r.distance.relative);
  text += fmt::format("  time: insertion {:.3f} s, optimization {:.2f} s\n", r.insert_seconds, r.optimization.seconds);
  text += fmt::format("  fold-over check: {}\n", r.check.reason());
  return text;
}

//! Write the padded mesh (and its VTK copy): cell fields go where they can be held (VTK); a
//! .mesh file holds the block labels only.
void write_outputs(const PadCliOptions& o, const padding::PadResult& r, nlohmann::json& j, std::string& text) {
  const core::MeshData out = padding::padded_mesh_data(r);
  io::write_mesh(o.output, io::format_from_path(o.output) == io::Format::Vtk ? out : core::to_mesh_data(r.mesh));
  j["output"] = o.output;
  text += fmt::format("wrote {}{}\n", o.output, r.check.ok() ? "" : " (failed the fold-over check: --keep-failed)");
  if (o.vtk.empty()) return;
  io::write_mesh(o.vtk, out);
  j["vtk"] = o.vtk;
  text += fmt::format("wrote {}\n", o.vtk);
}

void run_pad(const PadCliOptions& o) {
  for (const std::string& out : {o.output, o.vtk})
    if (!out.empty() && !io::is_volume_format(io::format_from_path(out)))
      throw core::InputError("expected a volume mesh file (.mesh .vtk .msh), got " + out);
  const core::MeshData d = io::read_mesh(o.input);
  if (d.hexes.empty()) throw core::InputError(o.input + ": no hexahedra to pad");
  const core::HexMesh mesh = core::hexes_of(d);
  const core::TriMesh target = read_fitting_target(o.target, mesh, o.input);
  nlohmann::json j = {{"input", o.input}, {"target", o.target.path}};
  const Choice choice = choose_facets(mesh, o, j);
  j["padding"] = choice.how;
  if (std::none_of(choice.facets.begin(), choice.facets.end(), [](std::uint8_t f) { return f != 0; }) && o.selective) {
    // Nothing is distorted enough to pad: the mesh stays as it is, and nothing is written.
    j["added_hexes"] = 0;
    if (!o.report.empty()) io::write_text_atomic(o.report, j.dump(2) + "\n");
    print_result(j, fmt::format("{}: nothing to pad (no boundary hex below the threshold needs it)\n", o.input) +
                        choice.text);
    return;
  }
  padding::PadOptions opt = o.pad;
  opt.run_optimizer = !o.no_optimize;
  const padding::PadResult r = padding::pad_hex_mesh(mesh, target, choice.facets, opt);
  add_result_json(j, r);
  std::string text = result_text(o, choice, r);
  if (r.check.ok() || o.keep_failed) write_outputs(o, r, j, text);
  if (!o.report.empty()) io::write_text_atomic(o.report, j.dump(2) + "\n");
  print_result(j, text);
  if (!r.check.ok()) throw core::GeometryError("padded mesh fails the fold-over check: " + r.check.reason());
}

}  // namespace

void register_pad(CLI::App& app) {
  auto opts = std::make_shared<PadCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "pad", "Insert a layer of hexes under the boundary (global padding) or along given facets, then optimize it "
             "with the boundary kept on the target; refuses results that fold over");
  sub->add_option("file", opts->input, "Hex mesh (.mesh .vtk .msh)")->required();
  add_target_option(*sub, opts->target);
  sub->add_option("-o,--output", opts->output, "Padded hex mesh (.mesh .vtk .msh)")->required();
  auto* global = sub->add_flag("--global", opts->global, "Pad every boundary facet (the default)");
  sub->add_option("--facets", opts->facets,
                  "Pad these facets instead: a text file, one facet per line as its 4 vertex ids (0-based, in the "
                  "order of the mesh file's points); interior facets make sheets through the volume. The set must "
                  "keep an even number of padded facets around interior and concave edges")
      ->excludes(global);
  auto* selective = sub->add_flag("--selective", opts->selective,
                                  "Pad only where the polycube map distorts the shape (thesis ch. 4): mapping analysis, "
                                  "then a binary problem for a valid facet set with few hexes and few turns")
                        ->excludes(global);
  sub->get_option("--facets")->excludes(selective);
  sub->add_option("--plan-vtk", opts->plan_vtk,
                  "Selective: write the boundary facets (and the padded interior ones) as a VTK quad mesh with the "
                  "cell fields distortion, propagated, hard (HF) and padded (PF)");
  sub->add_option("--analysis-mesh", opts->analysis_mesh,
                  "Selective: run the mapping analysis on this mesh instead (same hexes, e.g. the gridded hex.mesh of "
                  "an optimized mesh: the map's distortion before the optimizer hid part of it)");
  sub->add_option("--lambda", opts->selection.lambda,
                  "Selective: weight of the layer's turns (new singularities) against its hexes (thesis eq. 4.7): 0 "
                  "pads the fewest hexes, the layer turning wherever that saves some; larger values pad more hexes "
                  "with fewer turns, up to the whole boundary")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--threshold", opts->analysis.threshold,
                  "Selective: boundary hexes with a scaled Jacobian at least this are left alone")
      ->check(cli::in_range(-1.0, 1.0))
      ->capture_default_str();
  sub->add_option("--propagation", opts->analysis.propagation,
                  "Selective: steps of the soft propagation of the distortion over the boundary")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--time-limit", opts->selection.time_limit,
                  "Selective: seconds for the binary problem; past them the best facet set found is used and the "
                  "report says it is not proven optimal, with the gap. Under a limit, meshes of more than about "
                  "2,000 hexes get no branch and cut where the LP relaxation is fractional (it cannot progress within "
                  "minutes there): the best of the start and the rounded relaxation is used, the same on any machine "
                  "(0: no limit, branch and cut at any size)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--offset", opts->pad.sheet.offset,
                  "Where the new layer starts: this fraction of the local edge length inside the padded facets' hexes")
      ->check(cli::in_range(0.01, 0.9))
      ->capture_default_str();
  sub->add_option("--untangle-sigma", opts->pad.optimize.untangle_min_sigma,
                  "Floor of the untangling's sigma: epsilon falls by about this fraction per outer iteration at "
                  "least. Higher reaches a valid mesh sooner; the paper's 0.1 unfolds hard tangles more surely")
      ->check(cli::in_range(0.01, 0.9))
      ->capture_default_str();
  sub->add_option("--untangle-rings", opts->pad.optimize.local_untangle_rings,
                  "The optimization first untangles only the hexes within this many rings of those the new layer "
                  "inverted, the rest of the mesh kept as it is, and the whole mesh only when that is not enough "
                  "(0: the whole mesh at once, which also relaxes the optimized part). Faster where the layer's "
                  "untangling is long; the quality rounds then take another path, to a higher or lower mSJ")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--vtk", opts->vtk, "Also write the padded mesh as VTK with the cell fields padding_layer, "
                                      "source_hex and block (for ParaView)");
  sub->add_option("--report", opts->report, "Also write the report as JSON to this file");
  sub->add_flag("--no-optimize", opts->no_optimize, "Insert the layer only, without optimizing it");
  sub->add_flag("--keep-failed", opts->keep_failed,
                "Write the result even when it fails the fold-over check (the exit code is still 3)");
  sub->callback([opts] { run_pad(*opts); });
}

}  // namespace polycube::cli
