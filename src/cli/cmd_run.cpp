//! `polycube run INPUT -o DIR`: the whole chain (construct -> simplify -> hexmesh -> optimize,
//! plus the quad surface mesh), every intermediate result in DIR, report.json and a summary
//! table. A failing stage stops the chain, names the stage (stderr and report.json's
//! `failure.stage`) and keeps what the earlier stages wrote; nothing of the failing or later
//! stages is written (except hex_quality.vtk when the quality stage fails on inverted hexes: it
//! shows them). Exit code 2 when the input file is at fault (stages input and construct:
//! unreadable, open, non-manifold, self-intersecting, ...), else 3: the stage could not reach a
//! valid result, with the reason -- also when the request cannot be met for this polycube (a
//! `--hexes` whose lattice is too large is only known after the construction; the file is fine).
//! The hidden `--inject-failure STAGE` makes that stage fail at its start, for the tests of the
//! failure handling of the stages no small input makes fail reliably (pipeline.h).
#include "cli/app.h"
#include "core/errors.h"
#include "io/mesh_io.h"
#include "pipeline/pipeline.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

namespace polycube::cli {

namespace {

struct RunCliOptions {
  const CLI::App* command = nullptr;  //!< the parsed subcommand: its options go into the report
  std::string input;
  std::string output_dir;
  bool no_simplify = false;
  bool no_optimize = false;
  bool no_wrap_fallback = false;
  bool no_labeling_fallback = false;
  std::vector<double> chamber;
  pipeline::RunOptions run;
};

std::string figure(double v, const char* fmt_spec = "{:.3f}") {
  return v < -1.5 ? std::string("-") : fmt::format(fmt::runtime(fmt_spec), v);
}
std::string count(int v) { return v < 0 ? std::string("-") : std::to_string(v); }

// What was not computed is null in the report (RunResult keeps -1, and -2 for scaled Jacobians,
// which can be -1).
nlohmann::json known(int v) { return v < 0 ? nlohmann::json(nullptr) : nlohmann::json(v); }
nlohmann::json known(double v) { return v < 0.0 ? nlohmann::json(nullptr) : nlohmann::json(v); }
nlohmann::json known_sj(double v) { return v < -1.5 ? nlohmann::json(nullptr) : nlohmann::json(v); }

//! Paths as seen from the report's folder: the report stays right when the folder moves.
std::vector<std::string> relative_to(const std::vector<std::string>& files, const std::string& dir) {
  std::vector<std::string> out;
  for (const std::string& f : files) out.push_back(std::filesystem::path(f).lexically_relative(dir).string());
  return out;
}

//! What every report starts with: the program, the command, the options and the input.
nlohmann::json report_head(const RunCliOptions& o, const char* status) {
  return {{"status", status},
          {"version", kVersion},
          {"command", global_options().command_line},
          {"options", o.command ? options_json(*o.command) : nlohmann::json::object()},
          {"input", o.input}};
}

//! Selective padding's plan: its two steps together (-1 when there was no plan).
double plan_seconds(const pipeline::RunResult& r) {
  return r.padding_analysis_seconds < 0 ? -1.0 : r.padding_analysis_seconds + r.padding_solve_seconds;
}

//! The labeling fallback in the report: null when not tried.
nlohmann::json labeling_fallback_json(const pipeline::LabelingFallback& f) {
  if (!f.tried) return nullptr;
  return {{"kept", f.kept},
          {"reason", f.reason},
          {"compactness", f.compactness},
          {"failure_first", f.failure_first.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.failure_first)},
          {"charts_first", known(f.charts_first)},
          {"charts_retry", known(f.charts_retry)},
          {"hausdorff_relative_first", known(f.distance_first)},
          {"hausdorff_relative_retry", known(f.distance_retry)},
          {"msj_first", known_sj(f.msj_first)},
          {"msj_retry", known_sj(f.msj_retry)},
          {"why_not", f.why_not.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.why_not)}};
}

//! The summary's line on the labeling fallback (empty when not tried).
std::string labeling_fallback_summary(const pipeline::LabelingFallback& f) {
  if (!f.tried) return {};
  const std::string first =
      f.failure_first.empty()
          ? fmt::format("the first labeling's mesh ({} charts) was {:.3f} % of the diagonal from the input, mSJ {:.3f}",
                        f.charts_first, 100 * f.distance_first, f.msj_first)
          : fmt::format("the first labeling ({} charts) gave no valid mesh ({})", f.charts_first, f.failure_first);
  return f.kept ? fmt::format("labeling fallback: {}; the chain ran again with compactness {:.3g} ({} charts): {:.3f} %, "
                              "mSJ {:.3f} (the stages above)\n",
                              first, f.compactness, f.charts_retry, 100 * f.distance_retry, f.msj_retry)
                : fmt::format("labeling fallback: {}; compactness {:.3g} was tried and not kept: {}\n", first,
                              f.compactness, f.why_not);
}

nlohmann::json to_json(const pipeline::RunResult& r, const RunCliOptions& o) {
  nlohmann::json stages = nlohmann::json::array();
  for (const auto& s : r.stages) stages.push_back({{"stage", s.name}, {"ok", s.ok}, {"seconds", s.seconds}});
  nlohmann::json j = report_head(o, r.ok() ? "ok" : "failed");
  j.update({
      {"repairs", r.repairs},
      {"ok", r.ok()},
      {"stages", stages},
      {"tets", known(r.tets)},
      {"charts", known(r.charts)},
      {"corners", known(r.corners)},
      {"isometric_average", known(r.isometric_average)},
      {"isometric_max", known(r.isometric_max)},
      {"construct_attempt", r.construct_attempt},
      {"construct_attempts", known(r.construct_attempts)},
      {"construct_fallback", r.construct_fallback.empty()
                                 ? nlohmann::json(nullptr)
                                 : nlohmann::json({{"taken", r.construct_fallback}, {"why", r.construct_fallback_why}})},
      {"labeling_fallback", labeling_fallback_json(r.labeling_fallback)},
      {"surface_decimated",
       r.decimated_triangles > 0
           ? nlohmann::json({{"triangles_before", r.input_triangles}, {"triangles_after", r.decimated_triangles}})
           : nlohmann::json(nullptr)},
      {"coarse_surface_refined",
       r.coarse_levels > 0 ? nlohmann::json({{"levels", r.coarse_levels},
                                           {"triangles", r.coarse_triangles},
                                           {"tip_corners", r.coarse_tip_corners}})
                           : nlohmann::json(nullptr)},
      {"simplify_step", r.simplify_step},
      {"simplify_tried", r.simplify_tried},
      {"frozen_corners", known(r.frozen_corners)},
      {"optimize_fallback", r.optimize_fallback},
      {"optimize_tried", r.optimize_tried},
      {"padding", {{"applied", r.padding},
                   {"msj_unpadded", known_sj(r.msj_unpadded)},
                   {"msj_padded", known_sj(r.msj_padded)},
                   {"added_hexes", known(r.padding_added)},
                   {"singular_vertices_before", known(r.singular_vertices_before)},
                   {"singular_edges_before", known(r.singular_edges_before)},
                   {"singular_vertices_after", known(r.singular_vertices_after)},
                   {"singular_edges_after", known(r.singular_edges_after)},
                   {"insert_seconds", known(r.padding_insert_seconds)},
                   {"hard_facets", known(r.padding_hard_facets)},
                   {"plan_seconds", known(plan_seconds(r))},
                   {"plan_optimal", r.padding_plan_optimal},
                   {"plan_gap", known(r.padding_plan_gap)},
                   {"plan_solver", r.padding_plan_solver.empty() ? nlohmann::json(nullptr)
                                                                 : nlohmann::json(r.padding_plan_solver)},
                   {"analysis_seconds", known(r.padding_analysis_seconds)},
                   {"solve_seconds", known(r.padding_solve_seconds)},
                   {"selected_facets", known(r.padding_selected_facets)},
                   {"edge_turns", known(r.padding_edge_turns)},
                   {"vertex_turns", known(r.padding_vertex_turns)},
                   {"fewest_hexes", r.padding_fewest_hexes.empty() ? nlohmann::json(nullptr)
                                                                   : nlohmann::json(r.padding_fewest_hexes)},
                   {"optimize_seconds", known(r.padding_optimize_seconds)}}},
      {"fabricate",
       {{"boxes", known(r.part_boxes)},
        {"parts", known(r.parts)},
        {"unfit_parts", known(r.unfit_parts)},
        {"support_whole_percent", known(r.support_whole_percent)},
        {"support_parts_percent", known(r.support_parts_percent)},
        {"three_axis_unreachable_percent", known(r.three_axis_percent)},
        {"four_axis_unreached_percent", known(r.four_axis_percent)}}},
      {"hex_domains_before", known(r.hex_domains_before)},
      {"hex_domains_after", known(r.hex_domains_after)},
      {"quad_domains_before", known(r.quad_domains_before)},
      {"quad_domains_after", known(r.quad_domains_after)},
      {"grid_scale", known(r.grid_scale)},
      {"grid_sizing_fallback", r.grid_sizing_fallback},
      {"hexes", known(r.hexes)},
      {"quads", known(r.quads)},
      {"gridded", {{"inverted", known(r.inverted_gridded)}, {"msj", known_sj(r.msj_gridded)}, {"asj", known_sj(r.asj_gridded)}}},
      {"final", {{"inverted", known(r.inverted)}, {"msj", known_sj(r.msj)}, {"asj", known_sj(r.asj)}, {"domains", known(r.final_domains)},
                 {"hausdorff_relative", known(r.hausdorff_relative)},
                 {"hausdorff_unwrapped_relative", known(r.hausdorff_unwrapped_relative)}}},
      {"total_seconds", r.total_seconds},
      {"peak_memory_mib", known(r.peak_memory_mib)},
      {"files", relative_to(r.files, o.output_dir)}});
  if (!r.ok()) j["failure"] = {{"stage", r.failed_stage}, {"reason", r.failure}};
  return j;
}

std::string padding_summary(const pipeline::RunResult& r) {
  return fmt::format("{} hexes added, #Sv {} -> {}, #Se {} -> {}", count(r.padding_added),
                     count(r.singular_vertices_before), count(r.singular_vertices_after),
                     count(r.singular_edges_before), count(r.singular_edges_after));
}

//! ", |HF| .., |PF| .., turns, plan time (and gap)" after the pad line; empty without a plan.
std::string plan_summary(const pipeline::RunResult& r) {
  if (plan_seconds(r) < 0) return {};
  return fmt::format(", |HF| {}, |PF| {}, {} edge and {} vertex turns, plan {:.1f} s{}", r.padding_hard_facets,
                     r.padding_selected_facets, r.padding_edge_turns, r.padding_vertex_turns, plan_seconds(r),
                     r.padding_plan_optimal
                         ? std::string()
                         : fmt::format(" (not proven optimal, gap {:.1f} %)", 100.0 * r.padding_plan_gap));
}

//! ", fell back to ..." after the optimize line: which fallback gave the mesh; empty for none.
std::string optimize_fallback_summary(const pipeline::RunResult& r) {
  if (r.optimize_fallback == "none") return {};
  if (r.optimize_fallback.ends_with("padding"))
    return ", fell back to " + r.optimize_fallback + ": " + padding_summary(r);
  if (r.optimize_fallback.starts_with("stiffer boundary barrier") ||
      r.optimize_fallback.starts_with("slower untangling schedule"))  // the same grid
    return ", optimized again with a " + r.optimize_fallback;
  return ", regridded: " + r.optimize_fallback;
}

std::string summary_table(const pipeline::RunResult& r) {
  std::string t;
  t += "| stage | time (s) | result |\n|---|---:|---|\n";
  for (const auto& s : r.stages) {
    std::string what;
    if (!s.ok) what = "FAILED";
    else if (s.name == "construct")
      what = fmt::format("{} tets, {} charts, {} corners, isometric avg {} max {}; {} ({} attempt(s) run)", r.tets,
                         r.charts, r.corners, figure(r.isometric_average), figure(r.isometric_max),
                         r.construct_attempt, r.construct_attempts) +
             (r.construct_fallback.empty() ? "" : "; of the surface's " + r.construct_fallback +
                                                      ": the surface as read could not be certified") +
             (r.decimated_triangles > 0 ? fmt::format("; the surface decimated from {} to {} triangles",
                                                      r.input_triangles, r.decimated_triangles) : "") +
             (r.coarse_levels > 0 ? fmt::format("; the coarse surface split to {} triangles, {} sharp tips made corners",
                                                 r.coarse_triangles, r.coarse_tip_corners) : "");
    else if (s.name == "simplify")
      what = fmt::format("{}: #D {} -> {}, #dom {} -> {}", r.simplify_step, r.hex_domains_before,
                         r.hex_domains_after, r.quad_domains_before, r.quad_domains_after);
    else if (s.name == "fabricate")
      what = fmt::format("{} boxes, {} parts, support {:.1f} % in one piece, {:.1f} % in parts "
                         "(parts/parts.3mf, parts/exploded.vtk)",
                         r.part_boxes, r.parts, r.support_whole_percent, r.support_parts_percent);
    else if (s.name == "hexmesh")
      what = fmt::format("scale {:.4g}: {} hexes, {} quads; mSJ {} aSJ {}, {} inverted{}", r.grid_scale, r.hexes,
                         r.quads, figure(r.msj_gridded), figure(r.asj_gridded), count(r.inverted_gridded),
                         r.grid_sizing_fallback.empty() ? "" : ", the map's own sizing (one scale did not snap)");
    else if (s.name == "optimize")
      what = fmt::format("{} iterations{}", count(r.iterations_optimize), optimize_fallback_summary(r));
    else if (s.name == "pad")
      what = r.padding_added < 0 ? r.padding
                                 : fmt::format("{}: {}{}", r.padding, padding_summary(r), plan_summary(r));
    else if (s.name == "quality")
      what = fmt::format("mSJ {} aSJ {}, {} inverted, #D {}, Hausdorff {} of the bbox diagonal{}", figure(r.msj),
                         figure(r.asj), count(r.inverted), count(r.final_domains),
                         figure(r.hausdorff_relative, "{:.5f}"),
                         r.hausdorff_unwrapped_relative < 0
                             ? ""
                             : fmt::format(" from the wrap, {} from the surface as read",
                                           figure(r.hausdorff_unwrapped_relative, "{:.5f}")));
    else
      what = "ok";
    t += fmt::format("| {} | {:.2f} | {} |\n", s.name, s.seconds, what);
  }
  t += fmt::format("| total | {:.2f} | peak memory {:.0f} MiB |\n", r.total_seconds, r.peak_memory_mib);
  return t + labeling_fallback_summary(r.labeling_fallback);
}

void run_run(RunCliOptions o) {
  namespace fs = std::filesystem;
  o.run.simplify = !o.no_simplify;
  o.run.optimize = !o.no_optimize;
  o.run.wrap_fallback = !o.no_wrap_fallback;
  o.run.labeling_fallback = !o.no_labeling_fallback;
  if (!o.chamber.empty()) {
    if (!o.run.fabricate) throw core::InputError("--chamber needs --fabricate");
    o.run.fabricate_options.chamber = {o.chamber[0], o.chamber[1], o.chamber[2]};
  }
  const bool show = !global_options().quiet && !global_options().json;
  o.run.construct.on_attempt = attempt_progress();
  const fs::path dir(o.output_dir);
  // Interrupted: a report that says so and which stage was running (the stages' files written
  // so far are whole: every file is written atomically).
  auto running = std::make_shared<std::pair<std::mutex, std::string>>();
  o.run.on_stage = [show, running](int i, int n, const std::string& name) {
    if (show) print_status(fmt::format("[{}/{}] {}", i, n, name));
    std::lock_guard lock(running->first);
    running->second = name;
  };
  on_interrupt([&o, dir, running] {
    nlohmann::json j = report_head(o, "interrupted");
    std::lock_guard lock(running->first);
    j["interrupted_stage"] = running->second.empty() ? nlohmann::json(nullptr) : nlohmann::json(running->second);
    if (fs::is_directory(dir)) io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");
  });
  const pipeline::RunResult r = pipeline::run_pipeline(o.input, o.output_dir, o.run);
  on_interrupt({});
  nlohmann::json j = to_json(r, o);
  io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");
  if (!r.ok()) {
    const std::string msg = fmt::format("stage {} failed: {} (earlier results and report.json are in {})",
                                        r.failed_stage, r.failure, dir.string());
    if (global_options().json) print_result(j, "");  // the report is the JSON answer, failure included
    if (r.bad_input) throw core::InputError(msg);
    if (!global_options().json && !global_options().quiet) std::fputs(summary_table(r).c_str(), stdout);
    throw core::GeometryError(msg);
  }
  print_result(j, summary_table(r) + fmt::format("wrote {} (open hex_quality.vtk and quad.vtk in ParaView)", dir.string()));
}

}  // namespace

void register_run(CLI::App& app) {
  auto opts = std::make_shared<RunCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "run", "The whole chain on a surface or tet mesh: construct -> simplify -> hexmesh (+ quad mesh) -> optimize "
             "(-> pad), "
             "with every intermediate result, report.json and a summary table. A stage that cannot reach a valid "
             "result tries its fallbacks first (other construction attempts, the surface's alpha wrap, fewer alignments, a stiffer boundary "
             "barrier, padding, other griddings; a mesh too far from the input is gridded twice as fine, and one "
             "still too far or nearly flat somewhere is made again with a more faithful labeling), and the "
             "summary says which one gave the result. A failing stage stops the chain: "
             "exit code 2 when the input file is at fault, 3 when the stage could not reach a valid result (the "
             "reason and the stage on stderr and in report.json; earlier results kept)");
  sub->add_option("input", opts->input, "Closed surface (.obj .off .stl .ply .mesh) or tet mesh (.mesh .vtk .msh)")
      ->required();
  sub->add_option("-o,--output", opts->output_dir,
                  "Output folder: construct/ and simplify/ maps, hex.mesh, hex_optimized.mesh, hex_padded.mesh and "
                  "hex_padded.vtk (when padded), hex_quality.vtk, quad.vtk, report.json")
      ->required();
  sub->add_option("--hexes", opts->run.target_hexes,
                  "About this many hexes in the hex mesh (when the polycube's lattice at that size would be too "
                  "large, the hexmesh stage fails: exit code 3)")
      ->capture_default_str()
      ->check(cli::positive());
  add_sizing_option(*sub, opts->run.grid_sizing,
                  "Gridding: cells per interval between chart planes, 'uniform' (one scale) or 'map' (follows the "
                  "map's stretch, for hexes of more even size in model space)");
  sub->add_flag("--no-simplify", opts->no_simplify, "Mesh the constructed map without corner alignment");
  sub->add_flag("--no-optimize", opts->no_optimize, "Keep the gridded hex mesh as it is (and do not pad it)");
  add_choice<padding::PaddingMode>(
      *sub, "--padding", opts->run.padding,
      {{"none", padding::PaddingMode::None}, {"global", padding::PaddingMode::Global}, {"selective", padding::PaddingMode::Selective}},
      "After optimizing: 'none', 'global' (a layer of hexes under the whole boundary) or 'selective' "
      "(only where the polycube map distorts the shape; thesis ch. 4); the padded mesh is optimized again "
      "and written as hex_padded.mesh and hex_padded.vtk");
  sub->add_option_function<std::string>(
         "--padding-lambda",
         [o = &opts->run](const std::string& v) {
           o->padding_fewest_too = v == "auto";
           o->padding_selection.lambda = v == "auto" ? 1.0 : std::stod(v);
         },
         "Selective padding: weight of the new layer's turns (new singular edges and vertices) against its "
         "hexes (thesis eq. 4.7): 0 pads the fewest hexes, the layer turning wherever that saves some; larger "
         "values pad more hexes with fewer turns, up to the whole boundary. 'auto': the thesis's 1, and where "
         "that pads the whole boundary, also 0 when it pads at most half of it, keeping the padded mesh with the "
         "higher mSJ (thesis 4.6: the best value depends on the shape)")
      ->check(cli::auto_or_non_negative())
      ->default_str("auto")
      ->type_name("auto|X");
  sub->add_option("--padding-min-sj", opts->run.padding_usable_min_sj,
                  "The padded mesh replaces the optimized one when its minimum scaled Jacobian is at least the "
                  "unpadded mesh's or at least this; otherwise the unpadded mesh is kept (the padded one is still "
                  "written)")
      ->check(cli::in_range(-1.0, 1.0))
      ->capture_default_str();
  CLI::Option* refine_far =
      sub->add_flag("--refine-far", opts->run.refine_far,
                    "When the optimized mesh stays farther from the input than the Hausdorff bound, first grid the map "
                    "with twice the cells in the slabs of the polycube around the points it misses (fewer hexes than "
                    "twice as fine everywhere, which follows when that is not enough; the mSJ may be lower)");
  sub->add_flag("--no-wrap-fallback", opts->no_wrap_fallback,
                "When no construction attempt can be certified, fail instead of constructing the surface's alpha "
                "wrap (which closes slits and gaps thinner than the tets; the mesh then fits the wrap, and the "
                "report also gives its distance to the surface as read)");
  sub->add_flag("--no-labeling-fallback", opts->no_labeling_fallback,
                "When the optimizer and its fallbacks leave hexes inverted, fail; when the final mesh stays farther "
                "from the input than the Hausdorff bound (0.9 % of the input's bounding-box diagonal), or its minimum "
                "scaled Jacobian is below 0.1, keep it. By default the chain then runs again with a more faithful "
                "labeling (0.3 times --compactness, one attempt), whose mesh is kept when it is valid (and closer, or "
                "for the mSJ within the bound and higher): a labeling whose charts swallow a thin part (a flipper, an "
                "ear, a leg) leaves it no hexes of its own");
  sub->add_flag("--fabricate", opts->run.fabricate,
                "Also cut the input solid into parts along the simplified map (thesis ch. 6): "
                "parts/ with part_NN.stl, parts.3mf, exploded.ply/.vtk, parts.json");
  add_chamber_option(*sub, opts->chamber);
  auto& c = opts->run.construct;
  sub->add_option("--compactness", c.labeling.compactness,
                  "Compactness vs fidelity trade-off of the labeling (larger: fewer, smoother charts)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--max-volume", c.tetrahedralize.max_volume,
                  "Resolution of the tet mesh: largest tet volume as a fraction of the bounding-box volume (0: no "
                  "bound)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--time-limit", c.time_limit,
                  "Construction budget in seconds: an attempt with others still planned stops at half of what is left, "
                  "the last one at the budget; then the best attempt is certified, or the failure lists what was "
                  "tried (0: no limit, and the result does not depend on the machine's speed)")
      ->capture_default_str()
      ->check(cli::non_negative());
  const std::vector<CLI::Option*> decimation = add_decimation_options(*sub, c);
  CLI::Option* coarse = add_coarse_edge_option(*sub, c);
  sub->add_option("--lambda-min", opts->run.simplify_options.align.lambda_min,
                  "Simplification: stop before an iteration whose lambda is below this (0: until convergence)")
      ->capture_default_str()
      ->check(cli::non_negative());
  // Fault injection for the tests (pipeline.h, RunOptions::inject_failure): hidden from --help.
  sub->add_option("--inject-failure", opts->run.inject_failure, "Testing only: make this stage fail at its start")
      ->check(CLI::IsMember({"input", "construct", "simplify", "fabricate", "hexmesh", "optimize", "quality", "simplify-step-1",
                             "simplify-step-2", "simplify-step-3", "optimize-step-1", "optimize-step-2",
                             "optimize-step-3", "optimize-step-4", "optimize-step-5", "optimize-crossing-1",
                             "optimize-crossing-2", "optimize-distance-1",
                             "optimize-distance-2", "optimize-distance-3", "pad", "construct-unwrapped", "construct-attempt-1", "final-distance", "final-quality"}))
      ->group("");
  opts->command = sub;
  std::vector<CLI::Option*> expert = add_repair_options(*sub, opts->run.repair);
  expert.insert(expert.begin(), coarse);
  expert.insert(expert.begin(), refine_far);
  expert.insert(expert.begin(), decimation.begin(), decimation.end());
  add_expert_options(*sub, expert);
  sub->callback([opts] { run_run(*opts); });
}

}  // namespace polycube::cli
