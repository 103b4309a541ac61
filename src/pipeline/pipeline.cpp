//! The whole chain (see pipeline.h).
#include "pipeline/pipeline.h"

#include "core/stopwatch.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "pipeline/parts_output.h"
#include "io/polycube_map_io.h"
#include "mesh/grid.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "pipeline/input.h"
#include "quality/report.h"
#include "quality/scaled_jacobian.h"

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <optional>
#include <string>
#include <utility>

#include <sys/resource.h>

namespace polycube::pipeline {

namespace {


//! Testing only: N for an injected failure "<prefix>N" with N in 1..4 (RunOptions::inject_failure), else 0.
int injected_steps(const std::string& inject, const std::string& prefix) {
  if (inject.size() != prefix.size() + 1 || inject.rfind(prefix, 0) != 0) return 0;
  const char n = inject.back();
  return n >= '1' && n <= '4' ? n - '0' : 0;
}

//! How much stiffer the boundary barrier of the optimize stage's first fallback is (a boundary
//! that crosses itself; optimize::OptimizeOptions::boundary_barrier).
constexpr double kBarrierRetry = 4.0;

//! Every stage's name, in order (simplify and optimize can be turned off).
constexpr const char* kStages[] = {"input",    "construct", "simplify", "fabricate",
                                   "hexmesh",  "optimize",  "pad",      "quality"};

//! Signed volume of the map's polycube (lattice units cubed when it is integer).
double polycube_volume(const core::PolycubeMap& map) {
  double v = 0.0;
  for (const auto& t : map.tets) {
    const core::Vec3 a = map.polycube[t[1]] - map.polycube[t[0]];
    const core::Vec3 b = map.polycube[t[2]] - map.polycube[t[0]];
    const core::Vec3 c = map.polycube[t[3]] - map.polycube[t[0]];
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

void write_vtk(const std::filesystem::path& path, core::MeshData data, std::vector<core::Field> fields) {
  data.cell_data = std::move(fields);
  io::write_mesh(path, data);
}

//! Runs the stages in order; the first failure stops the chain.
class Runner {
 public:
  Runner(RunResult& r, const RunOptions& o, int count) : r_(r), o_(o), count_(count) {}

  //! Run `body` as stage `name`; false when it (or an earlier stage) failed.
  template <class F>
  bool stage(const std::string& name, F&& body) {
    if (!r_.ok()) return false;
    ++index_;
    if (o_.on_stage) o_.on_stage(index_, count_, name);
    core::logger().info("run: stage {}/{}: {}", index_, count_, name);
    StageRecord rec{name, 0.0, false};
    const core::Stopwatch clock;
    try {
      // One progress bar per stage: the stage's own long steps fill it (core/progress.h).
      core::ProgressTask progress(name, 1);
      if (o_.inject_failure == name) throw core::GeometryError("injected failure (--inject-failure " + name + ")");
      body();
      progress.step();
      progress.finish();
      rec.ok = true;
    } catch (const core::OutputError& e) {
      fail(name, e.what(), true);  // a file that cannot be written is the user's to fix, in any stage
    } catch (const core::InputError& e) {
      // Only the stages that read and process the input file can blame it (see RunResult).
      fail(name, e.what(), name == "input" || name == "construct");
    } catch (const core::Error& e) {
      fail(name, e.what(), false);
    } catch (const std::bad_alloc&) {
      fail(name, "out of memory", false);
    }
    rec.seconds = clock.seconds();
    r_.stages.push_back(rec);
    return rec.ok;
  }

 private:
  void fail(const std::string& name, const std::string& why, bool bad_input) {
    r_.failed_stage = name;
    r_.failure = why;
    r_.bad_input = bad_input;
  }
  RunResult& r_;
  const RunOptions& o_;
  int count_;
  int index_ = 0;
};

//! Grid the map at about `target` hexes with `sizing`; write hex.mesh and quad.vtk and record
//! the gridded mesh's figures in r. Returns the hex mesh.
core::HexMesh grid_and_write(const core::PolycubeMap& map, int target, mesh::GridSizing sizing,
                             const ConstructInput& in, const std::filesystem::path& out_dir, RunResult& r,
                             const std::function<void(const std::filesystem::path&)>& wrote) {
  mesh::GridOptions go;
  go.target_hexes = target;
  go.sizing = sizing;
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
  qo.target = &in.target;
  const quality::QuadReport qr = quality::quad_report(g.quad_model, qo);
  write_vtk(out_dir / "quad.vtk", core::to_mesh_data(g.quad_model), qr.fields());
  wrote(out_dir / "quad.vtk");
  return std::move(g.hex_model);
}

std::string fold_summary(const optimize::FoldoverReport& fold) {
  return fmt::format("{} inverted hexes, {} with a non-positive scaled Jacobian, {} boundary self-intersections",
                     fold.inverted_hexes, fold.nonpositive_scaled_jacobian, fold.boundary_self_intersections);
}

//! Optimize the hex mesh in place and run the global fold-over check on the result.
optimize::FoldoverReport optimize_and_check(core::HexMesh& hex, const ConstructInput& in,
                                            const optimize::OptimizeOptions& oo, RunResult& r) {
  const optimize::OptimizeResult opt = optimize::optimize_hex_mesh(hex, in.target, oo);
  r.iterations_optimize = opt.untangle.iterations + opt.quality.iterations;
  return optimize::check_foldover(hex);
}

//! The facets `mode` pads on this mesh; empty when selective padding finds nothing to pad.
std::vector<std::uint8_t> padding_facets(const core::HexMesh& hex, padding::PaddingMode mode, const RunOptions& o,
                                         RunResult& r) {
  if (mode == padding::PaddingMode::Global) return padding::boundary_selection(hex);
  const padding::SelectivePlan plan =
      padding::plan_selective_padding(hex, o.padding_analysis, o.padding_selection);
  r.padding_hard_facets = plan.analysis.hard_facets;
  r.padding_plan_optimal = plan.selection.optimal;
  r.padding_plan_gap = plan.selection.gap;
  r.padding_plan_solver = plan.selection.solver;
  r.padding_analysis_seconds = plan.analysis.seconds;
  r.padding_solve_seconds = plan.selection.seconds;
  r.padding_selected_facets = plan.selection.selected;
  r.padding_edge_turns = plan.selection.edge_turns;
  r.padding_vertex_turns = plan.selection.vertex_turns;
  if (plan.selection.selected == 0) return {};
  return plan.selection.facets;
}

//! Pad the mesh (`mode`), optimize and check it (padding/padding.h); record the figures and
//! write hex_padded.mesh and hex_padded.vtk when the result passes the check. Nothing when
//! there is nothing to pad. A facet set the insertion refuses comes back as an error, like a
//! failed check.
std::optional<padding::PadResult> pad_and_record(const core::HexMesh& hex, const ConstructInput& in,
                                                 const RunOptions& o, padding::PaddingMode mode, const std::string& how,
                                                 const std::filesystem::path& out_dir, RunResult& r,
                                                 const std::function<void(const std::filesystem::path&)>& wrote) {
  // Two steps for the progress bar: which facets (the selective plan solves a MILP), then the
  // sheet and its optimization.
  core::ProgressTask progress("pad", 2);
  const std::vector<std::uint8_t> facets = padding_facets(hex, mode, o, r);
  progress.step();
  if (facets.empty()) return std::nullopt;
  padding::PadResult p = padding::pad_hex_mesh(hex, in.target, facets, o.padding_options);
  progress.step();
  progress.finish();
  r.padding = how;
  r.padding_added = p.added_hexes;
  r.singular_vertices_before = p.before.singular_vertices;
  r.singular_edges_before = p.before.singular_edges;
  r.singular_vertices_after = p.after.singular_vertices;
  r.singular_edges_after = p.after.singular_edges;
  r.padding_insert_seconds = p.insert_seconds;
  r.padding_optimize_seconds = p.optimization.seconds;
  r.iterations_optimize = p.optimization.untangle.iterations + p.optimization.quality.iterations;
  if (p.check.ok()) {
    io::write_mesh(out_dir / "hex_padded.mesh", core::to_mesh_data(p.mesh));
    wrote(out_dir / "hex_padded.mesh");
    io::write_mesh(out_dir / "hex_padded.vtk", padding::padded_mesh_data(p));
    wrote(out_dir / "hex_padded.vtk");
  }
  return p;
}

//! Remove the files an earlier run wrote into this folder, and only those: a run that writes
//! fewer (--no-optimize after a full run, a padding not kept) would otherwise leave an earlier
//! hex_optimized.mesh or hex_padded.mesh beside its own files, as if it had written them.
//! The input itself is never removed (a run may read an earlier run's construct/model.mesh).
void clear_earlier_run(const std::filesystem::path& out_dir, const std::filesystem::path& input) {
  namespace fs = std::filesystem;
  int removed = 0;
  std::error_code ec;
  for (const char* name : {"construct/model.mesh", "construct/polycube.mesh", "simplify/model.mesh",
                           "simplify/polycube.mesh", "hex.mesh", "quad.vtk", "hex_optimized.mesh", "hex_padded.mesh",
                           "hex_padded.vtk", "hex_quality.vtk", "report.json"}) {
    const fs::path p = out_dir / name;
    if (fs::exists(p, ec) && !fs::equivalent(p, input, ec)) removed += fs::remove(p, ec) ? 1 : 0;
  }
  removed += remove_earlier_parts(out_dir / "parts");
  if (removed > 0) core::logger().info("run: removed {} files of an earlier run in {}", removed, out_dir.string());
}

//! Whether the pad stage runs: padding asked for (selective by default) on an optimized mesh.
bool pads(const RunOptions& o) { return o.hexmesh && o.optimize && o.padding != padding::PaddingMode::None; }

//! Whether a requested padding is kept (RunOptions::padding_usable_min_sj).
bool padding_pays(const padding::PadResult& p, const RunOptions& o) {
  const double after = p.after.scaled_jacobian.min;
  return after >= p.before.scaled_jacobian.min || after >= o.padding_usable_min_sj;
}

//! Forget a padded mesh that is not kept (only an injected failure can reject a mesh that
//! passed the check, the only one pad_and_record writes).
void discard_padded(const std::filesystem::path& out_dir, RunResult& r) {
  for (const char* name : {"hex_padded.mesh", "hex_padded.vtk"}) {
    std::error_code ec;
    std::filesystem::remove(out_dir / name, ec);
    std::erase(r.files, (out_dir / name).string());
  }
}

//! A second gridding for the optimizer when the first one's result fails the fold-over check.
struct OptimizeFallback {
  std::string name;
  int target_hexes;
  mesh::GridSizing sizing;
};

//! The fallbacks in order: the map's own sizing (hexes of more even size in the model, so
//! fewer squashed ones in thin parts), then a grid twice as fine (more room in the parts where
//! the optimizer stayed stuck).
std::vector<OptimizeFallback> optimize_fallbacks(int target, mesh::GridSizing sizing) {
  std::vector<OptimizeFallback> out;
  if (sizing != mesh::GridSizing::Map) out.push_back({"map sizing", target, mesh::GridSizing::Map});
  out.push_back({"finer grid (2x hexes)", 2 * target, sizing});
  return out;
}

//! The fabricate stage: decompose, check, write parts/ (nothing when a part fails its checks or
//! the chamber, so a failed stage leaves no half-made assembly).
void fabricate_and_write(const core::PolycubeMap& map, const core::TriMesh& solid, const RunOptions& o,
                         const std::filesystem::path& dir, RunResult& r,
                         const std::function<void(const std::filesystem::path&)>& wrote) {
  MillOptions mill;
  mill.directions = o.fabricate_mill_directions;
  const Fabrication f = fabricate_solid(map, solid, o.fabricate_options, o.fabricate_print, mill);
  r.part_boxes = f.decomposition.boxes;
  r.parts = static_cast<int>(f.decomposition.parts.parts.size());
  r.unfit_parts = f.decomposition.unfit_parts;
  r.support_whole_percent = 100.0 * f.whole.support_fraction;
  r.support_parts_percent = 100.0 * f.parts_support_fraction();
  r.three_axis_percent = 100.0 * f.parts_three_axis_fraction();
  r.four_axis_percent = 100.0 * f.parts_four_axis_fraction();
  check_parts(f);
  for (const auto& file : write_parts(dir, f)) wrote(file);
}

}  // namespace

double RunResult::seconds(const std::string& stage) const {
  for (const auto& s : stages)
    if (s.name == stage) return s.seconds;
  return 0.0;
}

RunResult run_pipeline(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                       const RunOptions& o) {
  namespace fs = std::filesystem;
  const core::Stopwatch clock;
  RunResult r;
  if (o.target_hexes <= 0) throw core::InputError("the target number of hexes must be positive");
  const bool injects_step = injected_steps(o.inject_failure, "simplify-step-") > 0 ||
                            injected_steps(o.inject_failure, "optimize-step-") > 0 ||
                            injected_steps(o.inject_failure, "optimize-crossing-") > 0;
  if (!o.inject_failure.empty() && !injects_step &&
      std::find(std::begin(kStages), std::end(kStages), o.inject_failure) == std::end(kStages))
    throw core::InputError("inject_failure: no stage named " + o.inject_failure);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw core::InputError(fmt::format("cannot create the output folder {}: {}", out_dir.string(), ec.message()));

  clear_earlier_run(out_dir, input);

  const int count = 2 + (o.simplify ? 1 : 0) + (o.fabricate ? 1 : 0) +
                    (o.hexmesh ? 2 + (o.optimize ? 1 : 0) +
                                     (pads(o) ? 1 : 0)
                               : 0);
  Runner run(r, o, count);
  auto wrote = [&](const fs::path& p) { r.files.push_back(p.string()); };

  // 1. input checks (cheap: a surface that is open or non-manifold stops here, exit 2)
  ConstructInput in;
  run.stage("input", [&] {
    in = read_construct_input(input, o.repair);
    r.repairs = in.repairs;
  });

  // 2. construction
  core::PolycubeMap map;
  run.stage("construct", [&] {
    const construct::ConstructResult c = construct_from_input(in, input, o.construct);
    r.tets = c.map.num_tets();
    r.construct_attempt = c.attempt.name();
    r.construct_attempts = c.attempts;
    r.coarse_levels = c.coarse_refinement.levels;
    if (c.coarse_refinement.levels > 0) r.coarse_triangles = c.coarse_refinement.triangles_after;
    r.coarse_tip_corners = c.tip_corners;
    r.charts = c.charts;
    r.corners = c.corners;
    r.isometric_average = c.isometric_average;
    r.isometric_max = c.isometric_max;
    fs::create_directories(out_dir / "construct");
    io::write_polycube_map(out_dir / "construct" / "model.mesh", out_dir / "construct" / "polycube.mesh", c.map);
    wrote(out_dir / "construct" / "model.mesh");
    wrote(out_dir / "construct" / "polycube.mesh");
    map = c.map;
  });

  // 3. simplification (with its fallbacks: simplify.h)
  mesh::GridSizing grid_sizing = o.grid_sizing;
  if (o.simplify)
    run.stage("simplify", [&] {
      // The lattice of the simplification is the coarsest hex mesh: when the target asks for
      // fewer hexes than its default resolution gives, make it coarser (gridding then scales
      // by an integer, so it can only refine).
      simplify::SimplifyOptions so = o.simplify_options;
      if (so.align.scale <= 0.0) {
        const double longest = core::bounding_box(map.polycube).extent().maxCoeff();
        const double vol = polycube_volume(map);
        if (longest > 0.0 && vol > 0.0) {
          const double res = longest * std::cbrt(o.target_hexes / vol);
          so.align.auto_resolution = std::clamp(std::round(res), 4.0, so.align.auto_resolution);
        }
      }
      so.inject_failed_steps = injected_steps(o.inject_failure, "simplify-step-");
      const simplify::SimplifyResult s = simplify::simplify_map(map, so);
      r.simplify_step = simplify::step_name(s.step);
      r.simplify_tried = s.tried;
      r.frozen_corners = s.frozen_corners;
      r.hex_domains_before = s.before.hex_domains;
      r.quad_domains_before = s.before.quad_domains;
      if (!s.fit.certified) {
        // Every step failed: the unsimplified map, gridded with the map's own sizing (its
        // planes are not on one lattice), loses the whole simplification but not the mesh.
        core::logger().warn("simplify: no step could be certified ({}); meshing the unsimplified map",
                            fmt::join(s.tried, "; "));
        r.simplify_step = "unsimplified";
        r.hex_domains_after = s.before.hex_domains;
        r.quad_domains_after = s.before.quad_domains;
        grid_sizing = mesh::GridSizing::Map;
        return;
      }
      r.hex_domains_after = s.after.hex_domains;
      r.quad_domains_after = s.after.quad_domains;
      fs::create_directories(out_dir / "simplify");
      io::write_polycube_map(out_dir / "simplify" / "model.mesh", out_dir / "simplify" / "polycube.mesh", s.fit.map);
      wrote(out_dir / "simplify" / "model.mesh");
      wrote(out_dir / "simplify" / "polycube.mesh");
      map = s.fit.map;
    });

  // 3b. the solid cut into parts along the map's boxes (on request)
  if (o.fabricate)
    run.stage("fabricate", [&] { fabricate_and_write(map, in.target, o, out_dir / "parts", r, wrote); });
  if (!o.hexmesh) {
    r.total_seconds = clock.seconds();
    return r;
  }

  // 4. gridding at the scale nearest the target (an integer polycube is never scaled below 1,
  //    so the simplified planes stay distinct and aligned: mesh/grid.h).
  core::HexMesh hex;
  auto add_file = [&](const fs::path& p) {
    if (std::find(r.files.begin(), r.files.end(), p.string()) == r.files.end()) wrote(p);
  };
  run.stage("hexmesh", [&] { hex = grid_and_write(map, o.target_hexes, grid_sizing, in, out_dir, r, add_file); });

  // 5. optimization (hex mesh untangling and quality improvement); when the result fails the
  //    fold-over check, the map is gridded again (OptimizeFallback) and optimized once more.
  if (o.optimize)
    run.stage("optimize", [&] {
      // Testing only: "optimize-step-N" counts the first N results as failed (RunOptions).
      // "optimize-crossing-N": the first N results count as boundaries that cross themselves.
      const int injected = injected_steps(o.inject_failure, "optimize-step-");
      const int injected_crossings = injected_steps(o.inject_failure, "optimize-crossing-");
      int checks = 0;
      bool crossing = false;  // the last result failed by its boundary crossing itself only
      auto why_failed = [&](const optimize::FoldoverReport& fold) {
        const int k = checks++;
        crossing = k < injected_crossings || (k >= injected && fold.inverted_hexes == 0 &&
                                              fold.nonpositive_scaled_jacobian == 0 && fold.boundary_self_intersections > 0);
        if (k < injected) return std::string("injected failure");
        if (k < injected_crossings) return std::string("injected boundary crossing");
        return fold.ok() ? std::string() : fold_summary(fold);
      };
      const core::HexMesh gridded = hex;
      std::string why = why_failed(optimize_and_check(hex, in, o.optimize_options, r));
      auto record_failure = [&] {
        r.optimize_tried.push_back(
            fmt::format("{}: {}", r.optimize_fallback == "none" ? "first grid" : r.optimize_fallback, why));
      };
      // A valid mesh whose boundary crosses itself: the same grid once more, with the barrier
      // that keeps the boundary quads facing the target's side kBarrierRetry times stiffer. Its
      // cost is one optimization, and it keeps the hexes the user asked for (padding adds some).
      if (!why.empty() && crossing && o.optimize_fallbacks && o.optimize_options.boundary_barrier > 0) {
        record_failure();
        core::logger().warn("optimize: {}; trying a stiffer boundary barrier", why);
        r.optimize_fallback = "stiffer boundary barrier";
        core::HexMesh first = std::exchange(hex, gridded);
        optimize::OptimizeOptions stiffer = o.optimize_options;
        stiffer.boundary_barrier *= kBarrierRetry;
        why = why_failed(optimize_and_check(hex, in, stiffer, r));
        if (!why.empty()) hex = std::move(first);  // padding pads the first result, as without this retry
      }
      // Padding first (selective, then global): the new layer frees the boundary hexes the
      // gridding squashed, and costs one optimization instead of a new gridding's (thesis ch. 4).
      for (const padding::PaddingMode mode : {padding::PaddingMode::Selective, padding::PaddingMode::Global}) {
        if (why.empty() || !o.optimize_fallbacks) break;
        const std::string name = fmt::format("{} padding", padding::mode_name(mode));
        record_failure();
        core::logger().warn("optimize: {}; trying {}", why, name);
        r.optimize_fallback = name;
        try {
          std::optional<padding::PadResult> p =
              pad_and_record(hex, in, o, mode, fmt::format("{} (optimize fallback)", padding::mode_name(mode)), out_dir,
                             r, add_file);
          if (!p) {
            why = "nothing to pad";
            continue;
          }
          why = why_failed(p->check);
          if (why.empty()) hex = std::move(p->mesh);
          else discard_padded(out_dir, r);
        } catch (const core::Error& e) {
          why = e.what();
        }
      }
      for (const OptimizeFallback& fb : optimize_fallbacks(o.target_hexes, grid_sizing)) {
        if (why.empty() || !o.optimize_fallbacks) break;
        record_failure();
        core::logger().warn("optimize: {}; gridding again: {}", why, fb.name);
        hex = grid_and_write(map, fb.target_hexes, fb.sizing, in, out_dir, r, add_file);
        r.optimize_fallback = fb.name;
        r.padding = "none";
        why = why_failed(optimize_and_check(hex, in, o.optimize_options, r));
      }
      if (!why.empty()) throw core::GeometryError("the optimized hex mesh fails the global fold-over check: " + why);
      io::write_mesh(out_dir / "hex_optimized.mesh", core::to_mesh_data(hex));
      add_file(out_dir / "hex_optimized.mesh");
    });

  // 6. padding (selective by default; unless the optimize stage has padded already). A padding
  //    that fails, or costs quality (padding_pays), leaves the optimized mesh as the result: the
  //    mesh was valid before it, and padding is an improvement, not a step the result needs.
  if (pads(o) && r.ok() && r.padding == "none")
    run.stage("pad", [&] {
      const std::string mode = padding::mode_name(o.padding);
      std::optional<padding::PadResult> p;
      std::string failure;
      try {
        p = pad_and_record(hex, in, o, o.padding, mode, out_dir, r, add_file);
        if (p && !p->check.ok()) failure = "the padded mesh fails the global fold-over check: " + fold_summary(p->check);
      } catch (const core::Error& e) {
        failure = e.what();
      }
      if (!failure.empty()) {
        discard_padded(out_dir, r);
        r.padding = fmt::format("{} (failed, not kept: {})", mode, failure);
        core::logger().warn("pad: {} padding failed ({}); keeping the optimized mesh", mode, failure);
        return;
      }
      if (!p) {
        r.padding = "none (nothing to pad)";
        return;
      }
      r.msj_unpadded = p->before.scaled_jacobian.min;
      r.msj_padded = p->after.scaled_jacobian.min;
      if (!padding_pays(*p, o)) {
        r.padding += fmt::format(" (not kept: mSJ {:.3f} -> {:.3f})", r.msj_unpadded, r.msj_padded);
        core::logger().warn("pad: the padded mesh's mSJ {:.3f} is below the unpadded {:.3f} and {:g}; keeping the "
                            "unpadded mesh (the padded one is in hex_padded.mesh)",
                            r.msj_padded, r.msj_unpadded, o.padding_usable_min_sj);
        return;
      }
      hex = std::move(p->mesh);
    });

  // 7. quality of the final hex mesh
  run.stage("quality", [&] {
    quality::ReportOptions qo;
    qo.target = &in.target;
    const quality::HexReport h = quality::hex_report(hex, qo);
    r.msj = h.sj.min;
    r.asj = h.sj.average;
    r.inverted = h.sj.inverted;
    if (h.domains) r.final_domains = h.domains->domains;
    if (h.distance) r.hausdorff_relative = h.distance->relative;
    write_vtk(out_dir / "hex_quality.vtk", core::to_mesh_data(hex), h.fields());
    wrote(out_dir / "hex_quality.vtk");
    if (r.inverted > 0)
      throw core::GeometryError(fmt::format("the final hex mesh has {} inverted hexes", r.inverted));
  });

  r.total_seconds = clock.seconds();
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) r.peak_memory_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
  return r;
}

}  // namespace polycube::pipeline
