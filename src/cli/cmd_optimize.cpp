//! `polycube optimize HEX --target SURFACE -o OUT`: untangle a hex mesh and raise its minimum
//! scaled Jacobian with the boundary kept on the target and its sharp features (ARCHITECTURE
//! §6.5), then check globally for fold-overs before writing.
#include "cli/app.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "quality/surface_distance.h"

#include <fmt/format.h>

#include <chrono>
#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct OptimizeCliOptions {
  std::string input;
  TargetOption target;
  std::string output;
  std::string report;  //!< optional JSON report file
  bool keep_failed = false;
  bool no_features = false;
  bool no_polish = false;
  optimize::OptimizeOptions opt;
};

nlohmann::json phase_json(const optimize::PhaseReport& p) {
  return {{"iterations", p.iterations}, {"newton_steps", p.newton_steps}, {"seconds", p.seconds}};
}

void run_optimize(const OptimizeCliOptions& o) {
  if (!io::is_volume_format(io::format_from_path(o.output)))
    throw core::InputError("-o expects a volume mesh file (.mesh .vtk .msh), got " + o.output);
  const core::MeshData d = io::read_mesh(o.input);
  if (d.hexes.empty()) throw core::InputError(o.input + ": no hexahedra to optimize");
  core::HexMesh mesh = core::hexes_of(d);
  const core::TriMesh target = read_fitting_target(o.target, mesh, o.input);
  optimize::OptimizeOptions opt = o.opt;
  opt.features = !o.no_features;
  opt.polish = !o.no_polish;

  const optimize::OptimizeResult r = optimize::optimize_hex_mesh(mesh, target, opt);
  const auto tc = std::chrono::steady_clock::now();
  const optimize::FoldoverReport check = optimize::check_foldover(mesh);
  const double check_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - tc).count();
  const quality::SurfaceDistance dist = r.distance ? *r.distance : quality::hausdorff_distance(mesh, target);

  nlohmann::json j;
  j["input"] = o.input;
  j["target"] = o.target.path;
  j["hexes"] = mesh.num_cells();
  j["before"] = scaled_jacobian_json(r.before);
  j["after"] = scaled_jacobian_json(r.after);
  j["hausdorff"] = {{"absolute", dist.hausdorff}, {"relative", dist.relative},
                    {"upper_bound", dist.hausdorff_upper}, {"target_diagonal", dist.reference_diagonal}};
  j["vertices"] = {{"surface", r.boundary_vertices - r.feature_vertices}, {"feature", r.feature_vertices},
                   {"corner", r.corner_vertices}};
  j["target_features"] = {{"sharp_edges", r.target_feature_edges}, {"corners", r.target_corners}};
  j["untangle"] = phase_json(r.untangle);
  j["quality"] = phase_json(r.quality);
  j["quality"]["rounds_kept"] = r.rounds_accepted;
  j["quality"]["rounds_run"] = r.rounds_run;
  j["quality"]["drift_retries_kept"] = r.drift_retries;
  j["quality"]["fit_retry_kept"] = r.fit_retry;
  j["polish"] = {{"sweeps", r.polish.sweeps},
                 {"moved", r.polish.moved},
                 {"msj_before", r.polish.min_before},
                 {"msj_after", r.polish.min_after},
                 {"seconds", r.polish.seconds}};
  j["setup_seconds"] = r.setup.seconds;
  j["check"] = foldover_json(check);
  j["check"]["seconds"] = check_seconds;
  j["seconds"] = r.seconds + check_seconds;
  std::string text = fmt::format("{}: {} hexes, target {}\n", o.input, mesh.num_cells(), o.target.path);
  text += fmt::format("  {:<10}{:>10}{:>10}\n", "", "before", "after");
  text += fmt::format("  {:<10}{:>10.4f}{:>10.4f}\n", "mSJ", r.before.min, r.after.min);
  text += fmt::format("  {:<10}{:>10.4f}{:>10.4f}\n", "aSJ", r.before.average, r.after.average);
  text += fmt::format("  {:<10}{:>10}{:>10}\n", "inverted", r.before.inverted + r.before.invalid,
                      r.after.inverted + r.after.invalid);
  text += fmt::format("  Hausdorff to the target {:.6g} ({:.4f}% of its bounding-box diagonal)\n", dist.hausdorff,
                      100.0 * dist.relative);
  text += fmt::format("  vertices: {} on the surface, {} on feature lines, {} at corners\n",
                      r.boundary_vertices - r.feature_vertices, r.feature_vertices, r.corner_vertices);
  text += fmt::format("  time: setup {:.2f} s, untangle {:.2f} s ({} it.), quality {:.2f} s ({} it.), check {:.2f} s\n",
                      r.setup.seconds, r.untangle.seconds, r.untangle.iterations, r.quality.seconds,
                      r.quality.iterations, check_seconds);
  text += fmt::format("  fold-over check: {}\n", check.reason());

  const bool write = check.ok() || o.keep_failed;
  if (write) {
    core::MeshData out = core::to_mesh_data(mesh);
    io::write_mesh(o.output, out);
    j["output"] = o.output;
    text += fmt::format("wrote {}{}\n", o.output, check.ok() ? "" : " (failed the fold-over check: --keep-failed)");
  }
  if (!o.report.empty()) io::write_text_atomic(o.report, j.dump(2) + "\n");
  print_result(j, text);
  if (!check.ok()) throw core::GeometryError("optimized mesh fails the fold-over check: " + check.reason());
}

}  // namespace

void register_optimize(CLI::App& app) {
  auto opts = std::make_shared<OptimizeCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "optimize", "Untangle a hex mesh and raise its minimum scaled Jacobian, boundary kept on a target surface "
                  "and its sharp features; refuses results that fold over");
  sub->add_option("file", opts->input, "Hex mesh (.mesh .vtk .msh)")->required();
  add_target_option(*sub, opts->target);
  sub->add_option("-o,--output", opts->output, "Optimized hex mesh (.mesh .vtk .msh)")->required();
  sub->add_option("--report", opts->report, "Also write the report as JSON to this file");
  auto& oo = opts->opt;
  sub->add_option("--surface-weight", oo.surface_weight, "Strength of the attraction of the boundary to the target")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--max-hausdorff", oo.hausdorff_bound,
                  "When the result's Hausdorff distance to the target exceeds this fraction of the target's "
                  "bounding-box diagonal (thesis bound: 0.009), the optimization runs again with a stiffer attraction "
                  "on the boundary vertices beyond --max-drift")
      ->capture_default_str()
      ->check(cli::positive());
  sub->add_option("--max-drift", oo.drift_diagonal,
                  "Boundary vertices farther than this fraction of the target's bounding-box diagonal get the stiffer "
                  "attraction of a retry: larger keeps more of the mSJ, smaller keeps the surface")
      ->capture_default_str()
      ->check(cli::positive());
  sub->add_option("--drift-retries", oo.drift_retries,
                  "Optimizations run again, each with a 16x stiffer attraction on the boundary vertices beyond "
                  "--max-drift, while the Hausdorff distance exceeds --max-hausdorff (0: off; inputs with inverted "
                  "hexes never retry)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--untangle-iterations", oo.untangle_iterations, "Outer iterations of the untangling at most")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--untangle-sigma", oo.untangle_min_sigma,
                  "Floor of the untangling's sigma: epsilon falls by about this fraction per outer iteration at "
                  "least. Higher reaches a valid mesh sooner; the paper's 0.1 unfolds hard tangles more surely "
                  "(`run` falls back to it where the default fails)")
      ->check(cli::in_range(0.01, 0.9))
      ->capture_default_str();
  sub->add_option("--untangle-rings", oo.local_untangle_rings,
                  "Untangle first only the hexes within this many rings of the inverted ones, the rest of the mesh "
                  "kept as it is, and the whole mesh only when that is not enough: for a mesh that was optimized "
                  "before a local change (0: the whole mesh at once)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--quality-rounds", oo.quality_rounds, "Quality rounds (each reweights the worst hexes)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--quality-patience", oo.quality_patience,
                  "The quality rounds stop once this many in a row after the first were neither kept nor higher "
                  "in mSJ than the round before them (0: all --quality-rounds run)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--quality-iterations", oo.quality_iterations, "Outer iterations per quality round at most")
      ->check(cli::positive())
      ->capture_default_str();
  sub->add_option("--volume-weight", oo.volume_weight, "Weight of the volume term of the elliptic energy")
      ->check(cli::positive())
      ->capture_default_str();
  sub->add_option("--feature-angle", oo.feature_angle, "Dihedral angle (degrees) above which an edge is sharp")
      ->check(cli::in_range(0.0, 180.0))
      ->capture_default_str();
  sub->add_option("--feature-distance", oo.feature_distance,
                  "Match hex boundary vertices with target features within this many edge lengths")
      ->check(cli::positive())
      ->capture_default_str();
  sub->add_option("--cholesky-max-variables", oo.cholesky_max_variables,
                  "Newton systems up to this size use sparse Cholesky, larger ones truncated CG")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--cg-iterations", oo.cg_iterations, "CG iterations per Newton step (large meshes)")
      ->check(cli::positive())
      ->capture_default_str();
  sub->add_option("--boundary-barrier", oo.boundary_barrier,
                  "Weight of the barrier that keeps boundary quads facing the target's side, so the boundary cannot "
                  "fold over itself (0: off)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--size-uniformity", oo.size_uniformity,
                  "How far each hex's reference size moves from its input size towards one size for the whole "
                  "mesh (0: keep the input's grading, 1: the same volume everywhere); evens out the long hexes of "
                  "regions the polycube map compresses")
      ->check(cli::in_range(0.0, 1.0))
      ->capture_default_str();
  sub->add_option("--face-attraction", oo.face_attraction,
                  "Weight of the attraction of each boundary quad's centre to the target, relative to a vertex's: the "
                  "boundary fits the surface instead of interpolating it (0: off)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--fit-retry", oo.fit_retry,
                  "When the result is still beyond --max-hausdorff, run the quality rounds again with the quad centres "
                  "attracted with this weight (--face-attraction) and keep that if closer (0: no fit retry)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--fit-first-margin", oo.fit_first_margin,
                  "Attract the quad centres from the first quality round when the untangled mesh, its boundary put on "
                  "the target, is already beyond this many times --max-hausdorff (the fit retry would run anyway; "
                  "0: plain rounds first)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_option("--centre-weight", oo.centre_weight,
                  "Weight of each hex's centre Jacobian (Verdict's ninth point) in the energy, relative to a corner's; "
                  "its barrier keeps hexes from twisting around a negative centre (0: corners only)")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->add_flag("--no-features", opts->no_features, "Do not preserve sharp features (surface attraction only)");
  sub->add_flag("--no-polish", opts->no_polish,
                "Skip the last step, which moves the vertices of the worst hexes one at a time to raise the lowest "
                "scaled Jacobian around them (never lowering the mesh's minimum or average; boundary vertices along "
                "the target, kept within --max-hausdorff and without boundary crossings)");
  sub->add_flag("--keep-failed", opts->keep_failed,
                "Write the result even when it fails the fold-over check (the exit code is still 3)");
  sub->callback([opts] { run_optimize(*opts); });
}

}  // namespace polycube::cli
