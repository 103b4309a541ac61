//! `polycube construct INPUT -o DIR`: tetrahedralize (or take the input tet mesh), label and
//! repair, deform, untangle and certify; write the certified map (model.mesh, polycube.mesh),
//! labeling.txt and report.json (ARCHITECTURE §6.2). Exit code 2 when the input is at fault, 3
//! when no certified map is reached (the reason; with --keep-failed the best attempt, when one got
//! as far as the deformation, as uncertified_*.mesh). The hidden `--inject-failure certify` treats
//! the certified result as not certified, for the tests of --keep-failed (no small input makes the
//! certification fail reliably).
#include "cli/app.h"
#include "construct/construct.h"
#include "core/errors.h"
#include "core/log.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "pipeline/input.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

namespace polycube::cli {

namespace {

struct ConstructCliOptions {
  std::string input;
  std::string output_dir;
  std::string keep_failed;  // folder for the best uncertified attempt, for diagnosis
  std::string inject_failure;  // testing only: "certify" = report the result as not certified; "attempt-N"
  repair::RepairOptions repair;
  construct::ConstructOptions construct;
};

construct::ConstructResult run_from_file(const ConstructCliOptions& o) {
  const pipeline::ConstructInput in = pipeline::read_construct_input(o.input, o.repair);
  return pipeline::construct_from_input(in, o.input, o.construct);
}

//! The best uncertified attempt, written for diagnosis under names that say so.
void write_failed_attempt(const std::filesystem::path& dir, const construct::NotCertified& e) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw core::InputError(fmt::format("cannot create the folder {}: {}", dir.string(), ec.message()));
  core::MeshData model, cube;
  model.points = e.map().model;
  cube.points = e.map().polycube;
  model.tets = cube.tets = e.map().tets;
  model.triangles = cube.triangles = e.boundary();
  model.triangle_labels = cube.triangle_labels = e.labels();
  io::write_mesh(dir / "uncertified_model.mesh", model);
  io::write_mesh(dir / "uncertified_polycube.mesh", cube);
  core::logger().warn("construct: wrote the best uncertified attempt to {} (uncertified_*.mesh, for diagnosis only)",
                      dir.string());
}

void run_construct(const ConstructCliOptions& o) {
  namespace fs = std::filesystem;
  construct::ConstructResult r;
  try {
    r = run_from_file(o);  // throws unless certified
    if (o.inject_failure == "certify")
      throw construct::NotCertified("polycube map not certified: injected failure (--inject-failure certify)", r.map,
                                    r.boundary, r.labels);
  } catch (const construct::NotCertified& e) {
    if (!o.keep_failed.empty()) write_failed_attempt(o.keep_failed, e);
    throw;
  }

  const fs::path dir(o.output_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw core::InputError(fmt::format("cannot create the output folder {}: {}", dir.string(), ec.message()));
  io::write_polycube_map(dir / "model.mesh", dir / "polycube.mesh", r.map);
  io::write_labeling(dir / "labeling.txt", r.labels);

  const auto& s = r.seconds;
  nlohmann::json j = {
      {"input", o.input},
      {"certified", r.certificate.certified()},
      {"vertices", r.map.num_vertices()},
      {"tets", r.map.num_tets()},
      {"tetgen_tets", r.tetgen_tets},
      {"coarse_surface_refined",
       r.coarse_refinement.levels > 0
           ? nlohmann::json({{"levels", r.coarse_refinement.levels},
                             {"triangles_before", r.coarse_refinement.triangles_before},
                             {"triangles_after", r.coarse_refinement.triangles_after},
                             {"tip_corners", r.tip_corners}})
           : nlohmann::json(nullptr)},
      {"surface_decimated",
       r.decimation.done() ? nlohmann::json({{"triangles_before", r.decimation.triangles_before},
                                             {"triangles_after", r.decimation.triangles_after},
                                             {"tolerance", r.decimation.tolerance}})
                           : nlohmann::json(nullptr)},
      {"refine", {{"split_edges", r.refine.split_edges}, {"split_tets", r.refine.split_tets}}},
      {"split_boundary_triangles", r.split_triangles},
      {"split_boundary_edges", r.split_edges},
      {"split_interior_faces", r.split_faces},
      {"refined_edges", r.refined_edges},
      {"boundary_first", r.boundary_first},
      {"boundary_triangles", r.boundary.size()},
      {"charts", r.charts},
      {"corners", r.corners},
      {"boundaries", r.boundaries},
      {"fidelity", r.fidelity},
      {"repair_moves", r.repair_moves},
      {"cut_compactness", r.cut_compactness},
      {"attempt", r.attempt.name()},
      {"attempts", r.attempts},
      {"tried", r.tried},
      {"axis_rotation",
       {{"rotated", !r.axis_rotation.rotation.isIdentity()},
        {"l1_energy_before", r.axis_rotation.energy_before},
        {"l1_energy_after", r.axis_rotation.energy_after}}},
      {"predeform",
       {{"iterations", r.predeform.iterations},
        {"misalignment_before", r.predeform.misalignment_before},
        {"misalignment_after", r.predeform.misalignment_after}}},
      {"inverted_after_linear_step", r.inverted_after_linear},
      {"untangle",
       {{"iterations", r.untangle.iterations},
        {"newton_steps", r.untangle.newton_steps},
        {"inverted_before", r.untangle.inverted_before},
        {"min_det", r.untangle.min_det},
        {"energy", r.untangle.energy}}},
      {"distortion",
       {{"isometric_average", r.isometric_average},
        {"isometric_max", r.isometric_max},
        {"conformal_average", r.conformal_average},
        {"conformal_max", r.conformal_max},
        {"volume_normalized", true}}},
      {"seconds",
       {{"decimate", s.decimate},
        {"tetrahedralize", s.tetrahedralize},
        {"predeform", s.predeform},
        {"label", s.label},
        {"repair", s.repair},
        {"deform", s.deform},
        {"untangle", s.untangle},
        {"certify", s.certify},
        {"total", s.total}}},
      {"outputs",
       {{"model", (dir / "model.mesh").string()},
        {"polycube", (dir / "polycube.mesh").string()},
        {"labeling", (dir / "labeling.txt").string()},
        {"report", (dir / "report.json").string()}}}};
  io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");

  const std::string decimated =
      r.decimation.done() ? fmt::format(" (of the surface decimated from {} to {} triangles)",
                                        r.decimation.triangles_before, r.decimation.triangles_after)
                          : "";
  const std::string decimate_time = r.decimation.done() ? fmt::format("decimate {:.2f} s, ", s.decimate) : "";
  const std::string text = fmt::format(
      "{}: certified polycube map, {} tets, {} charts, {} corners, fidelity {:.4f}{}\n"
      "isometric distortion avg {:.3f} max {:.3f}\n"
      "time: {}tetrahedralize {:.2f} s, predeform {:.2f} s, label {:.2f} s, repair {:.2f} s, deform {:.2f} s, "
      "untangle {:.2f} s, certify {:.2f} s, total {:.2f} s\n"
      "wrote {}",
      o.input, r.map.num_tets(), r.charts, r.corners, r.fidelity, decimated, r.isometric_average, r.isometric_max,
      decimate_time, s.tetrahedralize, s.predeform, s.label, s.repair, s.deform, s.untangle, s.certify, s.total,
      dir.string());
  print_result(j, text);
}

}  // namespace

void register_construct(CLI::App& app) {
  auto opts = std::make_shared<ConstructCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "construct",
      "Build a certified polycube map: tetrahedralize, label, repair, deform, untangle, certify");
  sub->add_option("input", opts->input, "Surface (.obj .off .stl .ply .mesh) or tet mesh (.mesh .vtk .msh)")
      ->required();
  sub->add_option("-o,--output", opts->output_dir,
                  "Output folder (model.mesh, polycube.mesh, labeling.txt, report.json)")
      ->required();
  auto& c = opts->construct;
  CLI::Option* tet_quality =
      sub->add_option("--quality", c.tetrahedralize.quality, "TetGen radius-edge ratio bound (0: none)")
          ->capture_default_str()
          ->check(cli::non_negative());
  sub->add_option("--max-volume", c.tetrahedralize.max_volume,
                  "Resolution: largest tet volume as a fraction of the bounding-box volume (0: no bound)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--compactness", c.labeling.compactness,
                  "Compactness vs fidelity trade-off of the labeling (larger: fewer, smoother charts)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--predeform", c.predeform.iterations,
                  "Iterations of the normal-driven pre-deformation before the labeling (0: label the model's own "
                  "normals)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_flag_callback("--no-align", [&c] { c.align_axes = false; },
                "Keep the model's orientation (default: rotate it so its normals cluster on the axes before the "
                "labeling; the written model keeps the input's positions)");
  sub->add_option("--time-limit", c.time_limit,
                  "Construction budget in seconds: an attempt with others still planned stops at half of what is left, "
                  "the last one at the budget; then the best attempt is certified, or the failure lists what was "
                  "tried (0: no limit, and the result does not depend on the machine's speed)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--keep-failed", opts->keep_failed,
                  "When certification fails, write the best attempt to this folder as uncertified_model.mesh and "
                  "uncertified_polycube.mesh (boundary labels as triangle references), for diagnosis");
  const std::vector<CLI::Option*> repair_expert = add_repair_options(*sub, opts->repair);
  const std::vector<CLI::Option*> decimation = add_decimation_options(*sub, c);
  std::vector<CLI::Option*> expert = {
      tet_quality,
      decimation[0],
      decimation[1],
      add_coarse_edge_option(*sub, c),
      sub->add_option("--predeform-retry", c.predeform_retry,
                      "When --predeform is 0, also plan the attempts on the model pre-deformed by this many "
                      "iterations, with estimate-driven unfolding (0: never); the attempts run most promising first")
          ->capture_default_str()
          ->check(cli::non_negative()),
      sub->add_option("--smooth", c.labeling.smoothing_rounds,
                      "Sweeps of chart-boundary smoothing after the graph cut (teeth and zigzags removed)")
          ->capture_default_str()
          ->check(cli::non_negative()),
      sub->add_option("--predeform-weight", c.predeform.surface_weight,
                      "Weight of the normal alignment against rigidity in the pre-deformation")
          ->capture_default_str()
          ->check(cli::positive()),
      sub->add_option("--iterations", c.deform.untangle.max_iterations,
                      "Outer iterations of the untangling/optimization")
          ->capture_default_str()
          ->check(cli::positive()),
      sub->add_option("--volume-weight", c.deform.untangle.volume_weight,
                      "Weight of the volume term of the elliptic energy")
          ->capture_default_str()
          ->check(cli::positive()),
      sub->add_option("--refine-rounds", c.deform.refine_rounds,
                      "When tets stay inverted, split their edges and untangle again, at most this many times")
          ->capture_default_str()
          ->check(cli::non_negative()),
      sub->add_flag_callback("--no-boundary-first", [&c] { c.deform.boundary_first = construct::BoundaryFirst::Off; },
                             "Never place the boundary first (polycube edges straight between their corners, charts "
                             "untangled in 2D inside them, then the volume with the boundary fixed); only the "
                             "free-boundary untangling and the local repairs"),
      sub->add_flag_callback("--untangle-first",
                             [&c] { c.deform.boundary_first = construct::BoundaryFirst::AfterRepairs; },
                             "Untangle with the boundary free (then the local repairs) before trying the "
                             "boundary-first placement; by default the boundary is placed first and the free "
                             "untangling is the fallback"),
      sub->add_flag_callback("--flow",
                             [&c] { c.deform.first.method = mapping::FirstPolycubeMethod::PlanarityFlow; },
                             "First polycube by the foldover-free planarity flow (the model flows towards its chart "
                             "planes without folding) instead of the as-rigid-as-possible least squares"),
      sub->add_option("--flow-iterations", c.deform.first.flow.iterations,
                      "Outer iterations of the planarity flow at most")
          ->capture_default_str()
          ->check(cli::positive()),
      sub->add_option("--flow-growth", c.deform.first.flow.growth,
                      "Growth factor of the planarity flow's attraction weight per iteration")
          ->capture_default_str()
          ->check(cli::in_range(1.0001, 100.0)),
      sub->add_option("--straighten", c.straighten_moves,
                      "After the repair, at most this many local relabellings removing turning points of the chart "
                      "boundaries (chains running backwards along their polycube edge's axis; 0: none)")
          ->capture_default_str()
          ->check(cli::non_negative()),
      sub->add_option("--unfold-moves", c.unfold_moves,
                      "After the repair, at most this many local relabellings against the folds of the fast "
                      "polycube estimate (0: none)")
          ->capture_default_str()
          ->check(cli::non_negative()),
  };
  expert.insert(expert.end(), repair_expert.begin(), repair_expert.end());
  add_expert_options(*sub, expert);
  // Fault injection for the tests of --keep-failed and of the fallback attempts: hidden from --help.
  sub->add_option(
         "--inject-failure", opts->inject_failure,
         "Testing only: 'certify' treats the result as not certified, 'attempt-N' the first N "
         "attempts as failed, 'uncertified-attempt-N' the first N attempts that certify as not "
         "certified")
      ->check(CLI::IsMember({"certify", "attempt-1", "attempt-2", "uncertified-attempt-1"}))
      ->group("");
  sub->callback([opts] {
    opts->construct.on_attempt = attempt_progress();
    if (opts->inject_failure.rfind("attempt-", 0) == 0)
      opts->construct.inject_failed_attempts = std::stoi(opts->inject_failure.substr(8));
    if (opts->inject_failure.rfind("uncertified-attempt-", 0) == 0)
      opts->construct.inject_uncertified_attempts = std::stoi(opts->inject_failure.substr(20));
    run_construct(*opts);
  });
}

}  // namespace polycube::cli
