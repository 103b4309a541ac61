//! `polycube simplify MODEL POLYCUBE -o DIR`: polycube simplification by corner alignment
//! (thesis ch. 3): write the simplified, certified map (model.mesh, polycube.mesh) and
//! report.json with corners, planes per axis, domains before/after, iterations and timings.
#include "cli/app.h"
#include "core/errors.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "quality/distortion.h"
#include "simplify/simplify.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <memory>

namespace polycube::cli {

namespace {

struct SimplifyCliOptions {
  std::string model;
  std::string polycube;
  std::string output_dir;
  simplify::SimplifyOptions simplify;
};

double gain(int before, int after) { return before > 0 ? 100.0 * (before - after) / before : 0.0; }

void run_simplify(const SimplifyCliOptions& o) {
  namespace fs = std::filesystem;
  const core::PolycubeMap map = io::read_polycube_map(o.model, o.polycube);
  const simplify::SimplifyResult r = simplify::simplify_map(map, o.simplify);
  const auto& a = r.alignment;

  nlohmann::json j;
  j["input"] = {{"model", o.model}, {"polycube", o.polycube}};
  j["corners"] = r.corners;
  j["edges"] = r.edges;
  j["charts"] = r.charts;
  j["scale"] = a.scale;
  j["lambda_min"] = o.simplify.align.lambda_min;
  j["solver"] = a.solver;
  j["planes_before"] = a.planes_before;
  j["planes_after"] = a.planes_after;
  j["domains"] = {{"hex_before", r.before.hex_domains}, {"hex_after", r.after.hex_domains},
                  {"hex_gain_percent", gain(r.before.hex_domains, r.after.hex_domains)},
                  {"quad_before", r.before.quad_domains}, {"quad_after", r.after.quad_domains},
                  {"quad_gain_percent", gain(r.before.quad_domains, r.after.quad_domains)}};
  nlohmann::json its = nlohmann::json::array();
  for (const auto& it : a.iterations)
    its.push_back({{"lambda", it.lambda}, {"candidates", it.candidates}, {"aligned", it.aligned},
                   {"aligned_total", it.aligned_total}, {"planes", it.planes}, {"shape_energy", it.shape_energy},
                   {"seconds", it.seconds}});
  j["iterations"] = its;
  j["stop_reason"] = a.stop_reason;
  j["aligned_pairs"] = a.aligned.size();
  j["shape_energy"] = a.shape_energy;
  j["max_corner_displacement"] = a.max_displacement;
  nlohmann::json cons = nlohmann::json::array();
  for (const auto& ax : a.system.axes)
    cons.push_back({{"classes", ax.num_classes()}, {"constraints", ax.constraints.size()},
                    {"before_reduction", ax.constraints_before_reduction}});
  j["axes"] = cons;
  j["step"] = simplify::step_name(r.step);  // the fallback step that gave the map (simplify.h)
  j["tried"] = r.tried;
  j["frozen_corners"] = r.frozen_corners;
  j["fit"] = {{"certified", r.fit.certified}, {"failures", r.fit.failures},
              {"inverted_initial", r.fit.inverted_initial}, {"inverted_final", r.fit.inverted_final},
              {"untangle_iterations", r.fit.untangle_iterations}};
  const double structure_seconds = a.seconds_system + a.seconds_pairing + a.seconds_solve + a.seconds_finalize;
  j["seconds"] = {{"validate", r.seconds_validate}, {"extract_structure", r.seconds_structure},
                  {"constraints", a.seconds_system}, {"pairing", a.seconds_pairing},
                  {"alignment", a.seconds_solve}, {"finalization", a.seconds_finalize},
                  {"pairing_alignment_finalization", structure_seconds}, {"domains", r.seconds_domains},
                  {"fit_place", r.fit.seconds_place}, {"fit_untangle", r.fit.seconds_untangle},
                  {"fit_certify", r.fit.seconds_certify}};
  std::string text = fmt::format(
      "corners {}, edges {}, charts {}; scale {:.4g} lattice units per polycube unit\n"
      "planes x/y/z: {}/{}/{} -> {}/{}/{}\n"
      "#D {} -> {} ({:.0f}% gain), #dom {} -> {} ({:.0f}% gain)\n"
      "{} iterations ({}), {} aligned pairs, shape energy {:.4g}, max corner move {:.3g}\n",
      r.corners, r.edges, r.charts, a.scale, a.planes_before[0], a.planes_before[1], a.planes_before[2],
      a.planes_after[0], a.planes_after[1], a.planes_after[2], r.before.hex_domains, r.after.hex_domains,
      gain(r.before.hex_domains, r.after.hex_domains), r.before.quad_domains, r.after.quad_domains,
      gain(r.before.quad_domains, r.after.quad_domains), a.iterations.size(), a.stop_reason, a.aligned.size(),
      a.shape_energy, a.max_displacement);
  if (!r.tried.empty() && r.fit.certified)
    text += fmt::format("fell back to step \"{}\" ({} corners frozen) after: {}\n", simplify::step_name(r.step),
                        r.frozen_corners, fmt::join(r.tried, "; "));
  text += fmt::format("time: pairing+alignment+finalization {:.3f} s (constraints {:.3f}, pairing {:.3f}, "
                      "alignment {:.3f}, finalization {:.3f}); fit {:.3f} s, untangle {:.3f} s\n",
                      structure_seconds, a.seconds_system, a.seconds_pairing, a.seconds_solve, a.seconds_finalize,
                      r.fit.seconds_place, r.fit.seconds_untangle);

  const fs::path dir(o.output_dir);
  fs::create_directories(dir);
  if (r.fit.certified) {
    const auto d0 = quality::map_distortion(map.model_mesh(), map.polycube, {true, false});
    const auto d1 = quality::map_distortion(map.model_mesh(), r.fit.map.polycube, {true, false});
    j["isometric_distortion"] = {{"before_average", d0.isometric.average}, {"before_max", d0.isometric.max},
                                 {"after_average", d1.isometric.average}, {"after_max", d1.isometric.max}};
    text += fmt::format("isometric distortion (volume-normalized) average {:.4f} -> {:.4f}\n", d0.isometric.average,
                        d1.isometric.average);
    io::write_polycube_map(dir / "model.mesh", dir / "polycube.mesh", r.fit.map);
    text += fmt::format("wrote {} and {}\n", (dir / "model.mesh").string(), (dir / "polycube.mesh").string());
  }
  io::write_text_atomic(dir / "report.json", j.dump(2) + "\n");
  if (!r.fit.certified) {
    std::string why;
    for (const auto& f : r.tried.empty() ? r.fit.failures : r.tried) why += (why.empty() ? "" : "; ") + f;
    throw core::GeometryError("simplified map could not be certified (report in " + (dir / "report.json").string() +
                              ", no map written; `run` meshes the unsimplified map then): " + why);
  }
  print_result(j, text);
}

}  // namespace

void register_simplify(CLI::App& app) {
  auto opts = std::make_shared<SimplifyCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "simplify", "Polycube simplification: align corners on the integer lattice for the coarsest block structure");
  sub->add_option("model", opts->model, "Model-space tet mesh of the map (.mesh)")->required();
  sub->add_option("polycube", opts->polycube, "Polycube-space tet mesh of the map (.mesh)")
      ->required();
  sub->add_option("-o,--output", opts->output_dir, "Output folder (model.mesh, polycube.mesh, report.json)")
      ->required();
  auto& al = opts->simplify.align;
  sub->add_option("--lambda-min", al.lambda_min,
                  "Stop before an iteration whose lambda is below this (1: one iteration, 0: until convergence)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--scale", al.scale, "Lattice units per polycube unit (0: automatic, see --resolution)")
      ->capture_default_str()
      ->check(cli::non_negative());
  sub->add_option("--resolution", al.auto_resolution, "Lattice units along the longest side when --scale is 0")
      ->capture_default_str()
      ->check(cli::positive());
  sub->add_option("--max-iterations", al.max_iterations, "At most this many alignment iterations")
      ->capture_default_str()
      ->check(cli::positive());
  sub->add_option("--untangle-iterations", opts->simplify.fit.untangling.max_iterations,
                  "Outer iterations of the untangler")
      ->capture_default_str()
      ->check(cli::positive());
  sub->callback([opts] { run_simplify(*opts); });
}

}  // namespace polycube::cli
