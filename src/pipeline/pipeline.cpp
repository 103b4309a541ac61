//! The whole chain (see pipeline.h).
#include "pipeline/pipeline.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/stopwatch.h"
#include "io/polycube_map_io.h"
#include "mesh/grid.h"
#include "pipeline/fewest_hexes.h"
#include "pipeline/input.h"
#include "pipeline/labeling_fallback.h"
#include "pipeline/optimize_stage.h"
#include "pipeline/parts_output.h"
#include "pipeline/stage_steps.h"
#include "quality/report.h"
#include "quality/surface_distance.h"

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
  // An interrupted labeling fallback's folder (labeling_fallback.h), unless the input is in it.
  const fs::path retry = out_dir / kRetryFolder;
  const fs::path from_retry = fs::weakly_canonical(input, ec).lexically_relative(fs::weakly_canonical(retry, ec));
  if (fs::exists(retry, ec) && (from_retry.empty() || *from_retry.begin() == ".."))
    removed += static_cast<int>(fs::remove_all(retry, ec));
  if (removed > 0) core::logger().info("run: removed {} files of an earlier run in {}", removed, out_dir.string());
}

//! Whether the pad stage runs: padding asked for (selective by default) on an optimized mesh.
bool pads(const RunOptions& o) { return o.hexmesh && o.optimize && o.padding != padding::PaddingMode::None; }

//! The pad stage's kept result `padded`, or the padded mesh of the plan at λ = 0 where
//! `candidate` (fewest_hexes.h) gives one that passes the same rules with an mSJ at least as high:
//! as good a mesh with fewer hexes. `hex` becomes the kept mesh, hex_padded.* its files.
void keep_fewest_hexes(core::HexMesh& hex, const RunOptions& o, const std::string& mode,
                       padding::PadResult& padded, double unpadded_distance, FewestHexesCandidate& candidate,
                       const std::filesystem::path& out_dir, RunResult& r,
                       const std::function<void(const std::filesystem::path&)>& wrote) {
  const double planned_seconds = r.padding_analysis_seconds + r.padding_solve_seconds;
  RunResult fewest_r = r;
  std::optional<padding::PadResult> fewest;
  try {
    fewest = candidate.take(mode + " (lambda 0)", fewest_r);
  } catch (const core::Error& e) {
    fewest_r.padding_fewest_hexes = fmt::format("lambda 0: failed ({})", e.what());
  }
  r.padding_fewest_hexes = fewest_r.padding_fewest_hexes;
  if (fewest) {
    const double msj = fewest->after.scaled_jacobian.min, msj_planned = padded.after.scaled_jacobian.min;
    std::string why = fewest->check.ok() ? padding::why_not_kept(*fewest, unpadded_distance,
                                                                 o.optimize_options.hausdorff_bound,
                                                                 o.padding_usable_min_sj)
                                         : "it fails the fold-over check: " + fold_summary(fewest->check);
    if (why.empty() && msj < msj_planned) why = fmt::format("mSJ {:.3f} below lambda {:g}'s {:.3f}", msj,
                                                            o.padding_selection.lambda, msj_planned);
    r.padding_fewest_hexes = fmt::format(
        "lambda 0: {} hexes added (lambda {:g}: {}, planned in {:.1f} s), mSJ {:.3f}, #Sv {}: {}", fewest->added_hexes,
        o.padding_selection.lambda, padded.added_hexes, planned_seconds, msj, fewest->after.singular_vertices,
        why.empty() ? "kept" : "not kept, " + why);
    core::logger().info("pad: {}", r.padding_fewest_hexes);
    if (why.empty()) {
      fewest_r.padding_fewest_hexes = r.padding_fewest_hexes;
      fewest_r.msj_padded = msj;
      r = std::move(fewest_r);
      write_padded(*fewest, out_dir, wrote);
      hex = std::move(fewest->mesh);
      return;
    }
  }
  hex = std::move(padded.mesh);
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

namespace {

//! The chain, stage by stage, without the labeling fallback.
RunResult run_chain(const std::filesystem::path& input, const std::filesystem::path& out_dir, const RunOptions& o) {
  namespace fs = std::filesystem;
  const core::Stopwatch clock;
  RunResult r;
  if (o.target_hexes <= 0) throw core::InputError("the target number of hexes must be positive");
  const bool injects_step = o.inject_failure == "construct-unwrapped" || o.inject_failure == "construct-attempt-1" ||
                            injected_steps(o.inject_failure, "simplify-step-") > 0 ||
                            injected_steps(o.inject_failure, "optimize-step-") > 0 ||
                            injected_steps(o.inject_failure, "optimize-crossing-") > 0 ||
                            injected_steps(o.inject_failure, "optimize-distance-") > 0 ||
                            o.inject_failure == "final-distance" || o.inject_failure == "final-quality";
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
    if (in.surface) r.input_triangles = static_cast<int>(in.surface->num_cells());
  });

  // 2. construction
  core::PolycubeMap map;
  run.stage("construct", [&] {
    WrapFallback wrap;
    construct::ConstructOptions co = o.construct;
    if (o.inject_failure == "construct-attempt-1") co.inject_failed_attempts = 1;
    const construct::ConstructResult c = construct_with_wrap_fallback(
        in, input, co, o.repair, o.wrap_fallback, o.inject_failure == "construct-unwrapped", wrap);
    r.construct_fallback = wrap.taken;
    r.construct_fallback_why = wrap.why;
    r.tets = c.map.num_tets();
    r.construct_attempt = c.attempt.name();
    if (c.cut_compactness != c.attempt.compactness)
      r.construct_attempt += fmt::format(", cut at {:.3g} (valid without repair)", c.cut_compactness);
    r.construct_attempts = c.attempts;
    r.decimated_triangles = c.decimation.triangles_after;
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
  //    A map whose planes are not on one lattice (--no-simplify) may not snap at one scale:
  //    then it is gridded with its own sizing, as the unsimplified fallback of simplify is.
  run.stage("hexmesh", [&] {
    try {
      hex = grid_and_write(map, o.target_hexes, grid_sizing, out_dir, r, add_file);
    } catch (const core::GeometryError& e) {
      if (grid_sizing == mesh::GridSizing::Map) throw;
      core::logger().warn("hexmesh: {}; gridding with the map's own sizing", e.what());
      r.grid_sizing_fallback = fmt::format("map sizing ({})", e.what());
      grid_sizing = mesh::GridSizing::Map;
      hex = grid_and_write(map, o.target_hexes, grid_sizing, out_dir, r, add_file);
    }
  });

  // 5. optimization (hex mesh untangling and quality improvement), with its fallbacks when the
  //    result fails the fold-over check or stays too far from the input (optimize_stage.h).
  if (o.optimize)
    run.stage("optimize", [&] { hex = optimize_with_fallbacks(hex, map, grid_sizing, in, o, out_dir, r, add_file); });

  // 6. padding (selective by default; unless the optimize stage has padded already). A padding
  //    that fails, or costs quality or surface fidelity (padding::why_not_kept), leaves the
  //    optimized mesh as the result: the mesh was valid before it, and padding is an
  //    improvement, not a step the result needs.
  if (pads(o) && r.ok() && r.padding == "none")
    run.stage("pad", [&] {
      const std::string mode = padding::mode_name(o.padding);
      std::optional<padding::PadResult> p;
      std::string failure;
      const double unpadded_distance = in.distances.measure(hex, in.target).relative;  // remembered: no new measure
      FewestHexesCandidate candidate(hex, in, o);
      try {
        p = pad_and_record(hex, in, o, o.padding, mode, out_dir, r, add_file,
                           [&](int selected) { candidate.planned(selected); });
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
      const std::string why = padding::why_not_kept(*p, unpadded_distance, o.optimize_options.hausdorff_bound,
                                                     o.padding_usable_min_sj);
      if (!why.empty()) {
        r.padding += fmt::format(" (not kept: mSJ {:.3f} -> {:.3f}, Hausdorff {:.3f} % -> {:.3f} %)", r.msj_unpadded,
                                 r.msj_padded, 100 * unpadded_distance, 100 * p->distance.relative);
        core::logger().warn("pad: the padded mesh is not kept: {}; keeping the unpadded mesh (the padded one is in "
                            "hex_padded.mesh)",
                            why);
        return;
      }
      keep_fewest_hexes(hex, o, mode, *p, unpadded_distance, candidate, out_dir, r, add_file);
    });

  // 7. quality of the final hex mesh
  run.stage("quality", [&] {
    const quality::HexReport h = quality::hex_report(hex);
    r.msj = h.sj.min;
    r.asj = h.sj.average;
    r.inverted = h.sj.inverted;
    if (h.domains) r.final_domains = h.domains->domains;
    r.hausdorff_relative = in.distances.measure(hex, in.target).relative;
    if (in.unwrapped) r.hausdorff_unwrapped_relative = quality::hausdorff_distance(hex, *in.unwrapped).relative;
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

}  // namespace

RunResult run_pipeline(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                       const RunOptions& o) {
  RunResult first = run_chain(input, out_dir, o);
  if (!wants_faithful_labeling(first, o)) return first;
  return with_faithful_labeling(input, out_dir, o, std::move(first), run_chain);
}

}  // namespace polycube::pipeline
