//! `polycube label INPUT -o DIR`: tetrahedralize (or take the input tet mesh), label the
//! boundary by graph cut, repair the labeling to validity (construct::label_surface), write the
//! tet mesh, the labeling and a report (ARCHITECTURE §6.2 steps 1–3).
#include "cli/app.h"
#include "construct/label_surface.h"
#include "core/errors.h"
#include "core/log.h"
#include "io/mesh_io.h"
#include "pipeline/input.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <utility>

namespace polycube::cli {

namespace {

struct LabelOptions {
  std::string input;
  std::string output_dir;
  construct::LabelSurfaceOptions label;
};

construct::LabelSurfaceResult label_input(pipeline::ConstructInput& in, const LabelOptions& o) {
  try {
    if (in.tets) return construct::label_surface(std::move(*in.tets), o.label);
    return construct::label_surface(*in.surface, o.label);
  } catch (const core::InputError& e) {
    throw core::InputError(o.input, 0, e.what());
  }
}

//! tets.mesh (Triangles = boundary, refs = labels), labeling.txt, labeling_cut.txt (the graph
//! cut before the repair: what a repair that moved many labels started from, for diagnosis),
//! and predeformed.mesh when there is a pre-deformation.
void write_outputs(const LabelOptions& o, const construct::LabelSurfaceResult& r) {
  const std::filesystem::path dir(o.output_dir);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw core::InputError(fmt::format("cannot create the output folder {}: {}", dir.string(), ec.message()));
  core::MeshData out;
  out.points = r.mesh.points;
  out.tets = r.mesh.cells;
  out.triangles = r.boundary_triangles;
  out.triangle_labels = r.labels;
  io::write_mesh(dir / "tets.mesh", out);
  if (o.label.predeform.iterations > 0) {
    out.points = r.predeform.points;
    io::write_mesh(dir / "predeformed.mesh", out);
  }
  io::write_labeling(dir / "labeling.txt", r.labels);
  io::write_labeling(dir / "labeling_cut.txt", r.initial_labels);
}

nlohmann::json report_json(const LabelOptions& o, const std::string& source, const construct::LabelSurfaceResult& r) {
  const std::filesystem::path dir(o.output_dir);
  const auto& layout = r.check.layout;
  const auto& est = r.estimate;
  const auto& pre = r.predeform;
  nlohmann::json defects = nlohmann::json::array();
  for (const auto& d : r.check.defects)
    defects.push_back({{"kind", construct::defect_kind_name(d.kind)}, {"charts", d.charts},
                       {"vertex", d.vertex}, {"reason", d.reason}});
  return {{"input", o.input},
          {"source", source},
          {"vertices", r.mesh.num_points()},
          {"tets", r.mesh.num_cells()},
          {"tetgen_tets", r.tetgen_tets},
          {"refine", {{"split_edges", r.refine.split_edges}, {"split_tets", r.refine.split_tets}}},
          {"boundary_triangles", r.boundary.surface.num_cells()},
          {"charts", layout.num_charts()},
          {"corners", layout.corners.size()},
          {"boundaries", layout.num_boundaries},
          {"fidelity", r.fidelity},
          {"fidelity_before_repair", r.fidelity_before_repair},
          {"defects_before_repair", r.initial_defects},
          {"repair_moves", r.repair_moves},
          {"valid", r.valid()},
          {"estimate",
           {{"folded_triangles", est.flipped.size()},
            {"folded_area_fraction", est.flipped_area},
            {"edge_distortion", est.edge_distortion}}},
          {"defects", defects},
          {"predeform",
           {{"iterations", pre.iterations},
            {"misalignment_before", pre.misalignment_before},
            {"misalignment_after", pre.misalignment_after},
            {"inverted_tets", pre.inverted},
            {"seconds", pre.seconds}}},
          {"seconds", {{"tetrahedralize", r.seconds.tetrahedralize}, {"label_and_repair", r.seconds.label_and_repair}}},
          {"outputs", {{"mesh", (dir / "tets.mesh").string()},
                       {"labeling", (dir / "labeling.txt").string()},
                       {"labeling_cut", (dir / "labeling_cut.txt").string()},
                       {"report", (dir / "report.json").string()}}}};
}

std::string report_text(const LabelOptions& o, const std::string& source, const construct::LabelSurfaceResult& r) {
  const auto& layout = r.check.layout;
  std::string text = fmt::format(
      "{}: {} tets ({}), {} boundary triangles\n"
      "charts {}, corners {}, boundaries {}, fidelity {:.4f}\n",
      o.input, r.mesh.num_cells(), source, r.boundary.surface.num_cells(), layout.num_charts(),
      layout.corners.size(), layout.num_boundaries, r.fidelity);
  if (r.valid()) {
    text += "labeling: valid\n";
  } else {
    text += fmt::format("labeling: INVALID, {} defect(s) remain:\n", r.check.defects.size());
    for (const auto& d : r.check.defects) text += "  " + d.reason + "\n";
  }
  text += fmt::format("polycube estimate: {} folded triangles ({:.3g}% of the area), edge distortion {:.3f}\n",
                      r.estimate.flipped.size(), 100.0 * r.estimate.flipped_area, r.estimate.edge_distortion);
  text += fmt::format("wrote {}", std::filesystem::path(o.output_dir).string());
  return text;
}

void run_label(const LabelOptions& o) {
  pipeline::ConstructInput in = pipeline::read_construct_input(o.input);
  const std::string source = in.tets ? "tet mesh" : "surface";
  const construct::LabelSurfaceResult r = label_input(in, o);
  write_outputs(o, r);
  const std::filesystem::path dir(o.output_dir);
  const nlohmann::json j = report_json(o, source, r);
  io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");
  print_result(j, report_text(o, source, r));
  core::logger().info("label: tetrahedralize {:.2f} s, label and repair {:.2f} s", r.seconds.tetrahedralize,
                      r.seconds.label_and_repair);
  if (!r.valid())
    throw core::SolverError(fmt::format("no valid labeling reached: {} defect(s) remain (see {})",
                                        r.check.defects.size(), (dir / "report.json").string()));
}

}  // namespace

void register_label(CLI::App& app) {
  auto opts = std::make_shared<LabelOptions>();
  CLI::App* sub = app.add_subcommand(
      "label", "Tetrahedralize a closed surface (or take a tet mesh) and compute a valid polycube labeling");
  sub->add_option("input", opts->input, "Surface (.obj .off .stl .ply .mesh) or tet mesh (.mesh .vtk .msh)")
      ->required();
  sub->add_option("-o,--output", opts->output_dir,
                  "Output folder (tets.mesh, labeling.txt, labeling_cut.txt: the graph cut before its repair, report.json; "
                  "predeformed.mesh with --predeform)")
      ->required();
  sub->add_option("--quality", opts->label.tetrahedralize.quality, "TetGen radius-edge ratio bound (0: none)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--max-volume", opts->label.tetrahedralize.max_volume,
                  "Largest tet volume as a fraction of the bounding-box volume (0: no bound)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--compactness", opts->label.labeling.compactness,
                  "Compactness vs fidelity trade-off of the labeling (larger: fewer, smoother charts)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--predeform", opts->label.predeform.iterations,
                  "Iterations of the normal-driven pre-deformation; the labeling then reads the pre-deformed "
                  "normals (0: the model's own)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--smooth", opts->label.labeling.smoothing_rounds,
                  "Sweeps of chart-boundary smoothing after the graph cut (teeth and zigzags removed)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--predeform-weight", opts->label.predeform.surface_weight,
                  "Weight of the normal alignment against rigidity in the pre-deformation")
      ->capture_default_str()
      ->check(cli::positive());
  sub->callback([opts] { run_label(*opts); });
}

}  // namespace polycube::cli
