//! `polycube label INPUT -o DIR`: tetrahedralize (or take the input tet mesh), label the
//! boundary by graph cut, repair the labeling to validity, write the tet mesh, the labeling and
//! a report (ARCHITECTURE §6.2 steps 1–3).
#include "cli/app.h"
#include "construct/labeling.h"
#include "construct/labeling_check.h"
#include "construct/labeling_repair.h"
#include "construct/polycube_estimate.h"
#include "construct/predeform.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"

#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <memory>

namespace polycube::cli {

namespace {

struct LabelOptions {
  std::string input;
  std::string output_dir;
  construct::TetrahedralizeOptions tet;
  construct::LabelingOptions labeling;
  construct::PredeformOptions predeform;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void run_label(const LabelOptions& o) {
  namespace fs = std::filesystem;
  auto& log = core::logger();
  const auto t0 = std::chrono::steady_clock::now();

  // 1. Tet mesh: read it, or tetrahedralize the surface.
  core::TetMesh mesh;
  std::string source;
  construct::RefineStats refine;
  int tetgen_tets = 0;
  const io::Format format = io::format_from_path(o.input);
  core::MeshData data;
  bool is_volume = false;
  if (io::is_volume_format(format)) {
    data = io::read_mesh(o.input);
    is_volume = !data.tets.empty();
    if (!is_volume && !data.hexes.empty())
      throw core::InputError(o.input, 0, "hexahedral meshes are not accepted; give a surface or a tet mesh");
  }
  if (is_volume) {
    mesh = core::tets_of(data);
    mesh.labels.clear();
    try {
      construct::prepare_tet_mesh(mesh);
    } catch (const core::InputError& e) {
      throw core::InputError(o.input, 0, e.what());
    }
    refine = construct::refine_boundary(mesh);
    source = "tet mesh";
  } else {
    core::TriMesh surface;
    if (io::is_volume_format(format)) {
      surface = core::triangles_of(data);
      surface.labels.clear();
      if (surface.cells.empty()) throw core::InputError(o.input, 0, "the file holds no triangle and no tet");
    } else {
      surface = io::read_surface(o.input);
    }
    try {
      auto r = construct::tetrahedralize(surface, o.tet);
      mesh = std::move(r.mesh);
      refine = r.refine;
      tetgen_tets = r.tetgen_tets;
    } catch (const core::InputError& e) {
      throw core::InputError(o.input, 0, e.what());
    }
    source = "surface";
  }
  const double t_tet = seconds_since(t0);

  // 2. Boundary, pre-deformation (optional), labeling, repair. With a pre-deformation the
  //    fidelity term reads the normals of the pre-deformed surface, as construct does.
  const core::TetBoundary bnd = core::boundary(mesh);
  construct::LabelingOptions labeling = o.labeling;
  const auto t1 = std::chrono::steady_clock::now();
  construct::PredeformResult pre;
  if (o.predeform.iterations > 0) {
    std::vector<core::Tri> tris;
    tris.reserve(bnd.surface.cells.size());
    for (const auto& t : bnd.surface.cells)
      tris.push_back({bnd.vertex_map[t[0]], bnd.vertex_map[t[1]], bnd.vertex_map[t[2]]});
    pre = construct::predeform(mesh, tris, o.predeform);
    labeling.data_normals = construct::triangle_normals(pre.points, tris);
  }
  const construct::LabelingResult lab = construct::graph_cut_labeling(bnd.surface, labeling);
  construct::RepairOptions ropt;
  ropt.energy = labeling;
  const construct::RepairResult rep = construct::repair_labeling(bnd.surface, lab.labels, ropt);
  const double t_label = seconds_since(t1);
  const double fidelity = construct::labeling_fidelity(bnd.surface, rep.labels);
  const construct::PolycubeEstimate est = construct::estimate_polycube(bnd.surface, rep.labels);
  const auto& layout = rep.check.layout;

  // 3. Outputs: tets.mesh (Triangles = boundary, refs = labels), labeling.txt, report.json.
  const fs::path dir(o.output_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw core::InputError(fmt::format("cannot create the output folder {}: {}", dir.string(), ec.message()));
  core::MeshData out;
  out.points = mesh.points;
  out.tets = mesh.cells;
  out.triangles.reserve(bnd.surface.cells.size());
  for (const auto& t : bnd.surface.cells)
    out.triangles.push_back({bnd.vertex_map[t[0]], bnd.vertex_map[t[1]], bnd.vertex_map[t[2]]});
  out.triangle_labels = rep.labels;
  io::write_mesh(dir / "tets.mesh", out);
  if (o.predeform.iterations > 0) {
    out.points = pre.points;
    io::write_mesh(dir / "predeformed.mesh", out);
  }
  std::string text_labels;
  text_labels.reserve(rep.labels.size() * 2);
  for (const int l : rep.labels) {
    text_labels += static_cast<char>('0' + l);
    text_labels += '\n';
  }
  io::write_text_atomic(dir / "labeling.txt", text_labels);

  nlohmann::json defects = nlohmann::json::array();
  for (const auto& d : rep.check.defects)
    defects.push_back({{"kind", construct::defect_kind_name(d.kind)}, {"charts", d.charts},
                       {"vertex", d.vertex}, {"reason", d.reason}});
  nlohmann::json j = {{"input", o.input},
                      {"source", source},
                      {"vertices", mesh.num_points()},
                      {"tets", mesh.num_cells()},
                      {"tetgen_tets", tetgen_tets},
                      {"refine", {{"split_edges", refine.split_edges}, {"split_tets", refine.split_tets}}},
                      {"boundary_triangles", bnd.surface.num_cells()},
                      {"charts", layout.num_charts()},
                      {"corners", layout.corners.size()},
                      {"boundaries", layout.num_boundaries},
                      {"fidelity", fidelity},
                      {"fidelity_before_repair", construct::labeling_fidelity(bnd.surface, lab.labels)},
                      {"defects_before_repair", rep.initial_defects},
                      {"repair_moves", rep.moves},
                      {"valid", rep.valid()},
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
                      {"seconds", {{"tetrahedralize", t_tet}, {"label_and_repair", t_label}}},
                      {"outputs", {{"mesh", (dir / "tets.mesh").string()},
                                   {"labeling", (dir / "labeling.txt").string()},
                                   {"report", (dir / "report.json").string()}}}};
  io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");

  std::string text = fmt::format(
      "{}: {} tets ({}), {} boundary triangles\n"
      "charts {}, corners {}, boundaries {}, fidelity {:.4f}\n",
      o.input, mesh.num_cells(), source, bnd.surface.num_cells(), layout.num_charts(),
      layout.corners.size(), layout.num_boundaries, fidelity);
  if (rep.valid()) {
    text += "labeling: valid\n";
  } else {
    text += fmt::format("labeling: INVALID, {} defect(s) remain:\n", rep.check.defects.size());
    for (const auto& d : rep.check.defects) text += "  " + d.reason + "\n";
  }
  text += fmt::format("polycube estimate: {} folded triangles ({:.3g}% of the area), edge distortion {:.3f}\n",
                      est.flipped.size(), 100.0 * est.flipped_area, est.edge_distortion);
  text += fmt::format("wrote {}", dir.string());
  print_result(j, text);
  log.info("label: tetrahedralize {:.2f} s, label and repair {:.2f} s", t_tet, t_label);
  if (!rep.valid())
    throw core::SolverError(fmt::format("no valid labeling reached: {} defect(s) remain (see {})",
                                        rep.check.defects.size(), (dir / "report.json").string()));
}

}  // namespace

void register_label(CLI::App& app) {
  auto opts = std::make_shared<LabelOptions>();
  CLI::App* sub = app.add_subcommand(
      "label", "Tetrahedralize a closed surface (or take a tet mesh) and compute a valid polycube labeling");
  sub->add_option("input", opts->input, "Surface (.obj .off .stl .ply .mesh) or tet mesh (.mesh .vtk .msh)")
      ->required();
  sub->add_option("-o,--output", opts->output_dir,
                  "Output folder (tets.mesh, labeling.txt, report.json; predeformed.mesh with --predeform)")
      ->required();
  sub->add_option("--quality", opts->tet.quality, "TetGen radius-edge ratio bound (0: none)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--max-volume", opts->tet.max_volume,
                  "Largest tet volume as a fraction of the bounding-box volume (0: no bound)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--compactness", opts->labeling.compactness,
                  "Compactness vs fidelity trade-off of the labeling (larger: fewer, smoother charts)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--predeform", opts->predeform.iterations,
                  "Iterations of the normal-driven pre-deformation; the labeling then reads the pre-deformed "
                  "normals (0: the model's own)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--smooth", opts->labeling.smoothing_rounds,
                  "Sweeps of chart-boundary smoothing after the graph cut (teeth and zigzags removed)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  sub->add_option("--predeform-weight", opts->predeform.surface_weight,
                  "Weight of the normal alignment against rigidity in the pre-deformation")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  sub->callback([opts] { run_label(*opts); });
}

}  // namespace polycube::cli
