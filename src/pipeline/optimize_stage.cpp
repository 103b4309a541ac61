//! The optimize stage and its fallbacks (see optimize_stage.h).
#include "pipeline/optimize_stage.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "io/mesh_io.h"
#include "optimize/foldover_check.h"
#include "optimize/hex_optimize.h"
#include "quality/surface_distance.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace polycube::pipeline {

namespace {

//! How much stiffer the boundary barrier of the first fallback is (a boundary that crosses
//! itself; optimize::OptimizeOptions::boundary_barrier).
constexpr double kBarrierRetry = 4.0;

//! The floor of σ in the untangling's ε update of the paper (Garanzha et al. 2021): the slower,
//! surer schedule a gridding is optimized with again when the faster default
//! (optimize::OptimizeOptions::untangle_min_sigma) left it invalid.
constexpr double kPaperSigma = 0.1;

//! At most how many times the first grid's hexes the distance fallback's refinement near the
//! far points makes (step 5): as many as the grid twice as fine everywhere (the next try), whose
//! hexes are 2^(1/3) shorter where the refinement's are half as long.
constexpr double kNearHexes = 2.0;

//! A new gridding of the map for the optimizer.
struct Regridding {
  std::string name;
  int target_hexes;
  mesh::GridSizing sizing;
};

//! Step 4's griddings in order: the map's own sizing (hexes of more even size in the model, so
//! fewer squashed ones in thin parts), then a grid twice as fine (more room in the parts where
//! the optimizer stayed stuck).
std::vector<Regridding> regriddings(int target, mesh::GridSizing sizing) {
  std::vector<Regridding> out;
  if (sizing != mesh::GridSizing::Map) out.push_back({"map sizing", target, mesh::GridSizing::Map});
  out.push_back({"finer grid (2x hexes)", 2 * target, sizing});
  return out;
}

//! The steps of optimize_stage.h, in the order run() takes them. `why_` is why the current mesh
//! failed (empty: it passed).
class OptimizeStage {
 public:
  OptimizeStage(const core::PolycubeMap& map, mesh::GridSizing sizing, const ConstructInput& in, const RunOptions& o,
                const std::filesystem::path& out_dir, RunResult& r, const FileWritten& wrote)
      : map_(map), sizing_(sizing), in_(in), o_(o), out_dir_(out_dir), r_(r), wrote_(wrote),
        // Testing only: "optimize-step-N" counts the first N results as failed (RunOptions);
        // "optimize-crossing-N" as boundaries that cross themselves; "optimize-distance-N" the
        // first N valid meshes of step 5 as too far from the input (2: the first finer one too).
        injected_(injected_steps(o.inject_failure, "optimize-step-")),
        injected_crossings_(injected_steps(o.inject_failure, "optimize-crossing-")),
        injected_far_(injected_steps(o.inject_failure, "optimize-distance-")) {}

  core::HexMesh run(const core::HexMesh& gridded) {
    hex_ = gridded;
    optimize_gridding(hex_, gridded, "");
    pad_instead();
    grid_again();
    if (!why_.empty()) throw core::GeometryError("the optimized hex mesh fails the global fold-over check: " + why_);
    grid_finer_when_far();
    io::write_mesh(out_dir_ / "hex_optimized.mesh", core::to_mesh_data(hex_));
    wrote_(out_dir_ / "hex_optimized.mesh");
    return std::move(hex_);
  }

 private:
  bool falls_back() const { return !why_.empty() && o_.optimize_fallbacks; }

  //! The options of a first optimization, which step 2 may follow: it stops after the
  //! untangling when the boundary then crosses itself (the quality rounds keep the crossings),
  //! so that step 2 starts at once.
  optimize::OptimizeOptions first_try_options(const optimize::OptimizeOptions& schedule) const {
    optimize::OptimizeOptions oo = schedule;
    oo.stop_when_untangled_crosses = o_.optimize_fallbacks && oo.boundary_barrier > 0;
    return oo;
  }

  //! The optimizer's options with the paper's ε schedule (kPaperSigma).
  optimize::OptimizeOptions paper_schedule() const {
    optimize::OptimizeOptions oo = o_.optimize_options;
    oo.untangle_min_sigma = std::min(oo.untangle_min_sigma, kPaperSigma);
    return oo;
  }

  //! Steps 1–2 on `hex`, the gridding `gridded` (named `name`; empty: the first grid), with the
  //! optimizer's ε schedule, then, when neither left a valid mesh and that schedule is faster than
  //! the paper's, once more with the paper's. The faster fall of ε reaches a valid mesh in fewer
  //! outer iterations where the tangle is a few folded hexes in a valid grid, but can stiffen the
  //! barrier before a squashed boundary has unfolded (bench/RESULTS.md, stop 55: fandisk's finer
  //! grid); the paper's schedule then gives what it always gave.
  void optimize_gridding(core::HexMesh& hex, const core::HexMesh& gridded, const std::string& name) {
    const auto named = [&](const char* step) { return name.empty() ? std::string(step) : name + ", " + step; };
    std::vector<optimize::OptimizeOptions> schedules{o_.optimize_options};
    if (o_.optimize_options.untangle_min_sigma > kPaperSigma) schedules.push_back(paper_schedule());
    for (std::size_t i = 0; i < schedules.size(); ++i) {
      const bool last = i + 1 == schedules.size();
      if (i > 0) {
        if (!falls_back()) return;
        record_failure();
        core::logger().warn("optimize: {}; trying the paper's slower untangling schedule", why_);
        r_.optimize_fallback = named("slower untangling schedule");
        hex = gridded;
      }
      why_ = optimize(hex, first_try_options(schedules[i]));
      const std::string stiffer = named(i > 0 ? "slower untangling schedule, stiffer boundary barrier"
                                              : "stiffer boundary barrier");
      retry_with_stiffer_barrier(hex, gridded, stiffer, schedules[i], last);
      if (why_.empty()) return;
    }
  }

  //! Step 1 on `hex` (in place): why it fails the fold-over check, empty when it passes.
  std::string optimize(core::HexMesh& hex, const optimize::OptimizeOptions& oo) {
    const optimize::OptimizeResult opt = optimize::optimize_hex_mesh(hex, in_.target, oo);
    if (opt.distance) in_.distances.remember(hex, *opt.distance);
    r_.iterations_optimize = opt.untangle.iterations + opt.quality.iterations;
    stopped_ = opt.stopped_crossing;
    const std::string why = why_failed(optimize::check_foldover(hex));
    // An injected crossing stands for one found where the optimizer stops, after the untangling.
    early_crossing_ = crossing_ && (stopped_ || checks_ <= injected_crossings_);
    return stopped_ && !why.empty() ? "after the untangling, " + why : why;
  }

  //! Why a checked mesh fails (empty: it passes); sets crossing_ when the boundary crossing
  //! itself is all that is wrong.
  std::string why_failed(const optimize::FoldoverReport& fold) {
    const int k = checks_++;
    crossing_ = k < injected_crossings_ || (k >= injected_ && fold.inverted_hexes == 0 &&
                                            fold.nonpositive_scaled_jacobian == 0 &&
                                            fold.boundary_self_intersections > 0);
    if (k < injected_) return "injected failure";
    if (k < injected_crossings_) return "injected boundary crossing";
    return fold.ok() ? std::string() : fold_summary(fold);
  }

  void record_failure() {
    r_.optimize_tried.push_back(
        fmt::format("{}: {}", r_.optimize_fallback == "none" ? "first grid" : r_.optimize_fallback, why_));
  }

  //! Step 2 on `hex`, the optimized `gridded`: when it failed by its boundary crossing itself
  //! only, `gridded` is optimized again with the stiffer barrier (otherwise the options of
  //! `schedule`), under the fallback name `name`. Its cost is one optimization; when it fails
  //! too, `hex` keeps the first result (the one the later steps pad).
  //! A first optimization that stopped after the untangling (first_try_options) gets its quality
  //! rounds when the retry fails too and `last` (no other schedule follows): its mesh is the one
  //! the later steps pad. When another schedule follows, the retry runs only for a crossing
  //! found after the untangling: one that the quality rounds made after a fast untangling goes
  //! to the slower schedule, which has its own retry (bench/RESULTS.md, stop 56: fandisk's
  //! finer grid, whose fast retry crossed itself too and cost a full optimization).
  void retry_with_stiffer_barrier(core::HexMesh& hex, const core::HexMesh& gridded, const std::string& name,
                                  const optimize::OptimizeOptions& schedule, bool last) {
    if (!falls_back() || !crossing_ || schedule.boundary_barrier <= 0 || (!last && !early_crossing_)) return;
    record_failure();
    core::logger().warn("optimize: {}; trying a stiffer boundary barrier", why_);
    r_.optimize_fallback = name;
    const bool first_stopped = stopped_;
    core::HexMesh first = std::exchange(hex, gridded);
    optimize::OptimizeOptions stiffer = schedule;
    stiffer.boundary_barrier *= kBarrierRetry;
    why_ = optimize(hex, stiffer);
    if (why_.empty() || !last) return;
    if (!first_stopped) {
      hex = std::move(first);
      return;
    }
    core::logger().warn("optimize: {}; optimizing the first mesh in full", why_);
    hex = gridded;
    const int iterations = r_.iterations_optimize;  // the report keeps the retry's, as when it did not stop
    optimize::optimize_hex_mesh(hex, in_.target, schedule);
    r_.iterations_optimize = iterations;
  }

  //! Step 3: padding costs one optimization, a new gridding's more.
  void pad_instead() {
    for (const padding::PaddingMode mode : {padding::PaddingMode::Selective, padding::PaddingMode::Global}) {
      if (!falls_back()) return;
      const std::string name = fmt::format("{} padding", padding::mode_name(mode));
      record_failure();
      core::logger().warn("optimize: {}; trying {}", why_, name);
      r_.optimize_fallback = name;
      first_grid_ = false;
      try {
        std::optional<padding::PadResult> p = pad_and_record(
            hex_, in_, o_, mode, fmt::format("{} (optimize fallback)", padding::mode_name(mode)), out_dir_, r_, wrote_);
        if (!p) {
          why_ = "nothing to pad";
          continue;
        }
        why_ = why_failed(p->check);
        if (why_.empty()) hex_ = std::move(p->mesh);
        else discard_padded(out_dir_, r_);
      } catch (const core::Error& e) {
        why_ = e.what();
      }
    }
  }

  //! Step 4.
  void grid_again() {
    for (const Regridding& g : regriddings(o_.target_hexes, sizing_)) {
      if (!falls_back()) return;
      record_failure();
      core::logger().warn("optimize: {}; gridding again: {}", why_, g.name);
      hex_ = grid_and_write(map_, g.target_hexes, g.sizing, out_dir_, r_, wrote_);
      r_.optimize_fallback = g.name;
      r_.padding = "none";
      first_grid_ = false;
      why_ = optimize(hex_, paper_schedule());
    }
  }

  //! Step 5. The optimizer's drift and fit retries have already pulled the boundary to the
  //! surface where its hexes allow; a mesh still too far has hexes too coarse for some feature
  //! (a thin part, a crease between grid planes). With RunOptions::refine_far, first the grid
  //! with twice the cells in the unit slabs of the polycube that hold the points where the mesh
  //! misses the input (try_finer says which), which halves the hexes there at the cost of those
  //! slabs only; then, while still beyond the bound, the grid twice as fine everywhere (its
  //! hexes 2^(1/3) shorter). Each is
  //! kept when it is valid and closer than the mesh kept before; the first grid stays otherwise.
  //! hex.mesh is written again for the kept one (gridding is deterministic, and cheap beside an
  //! optimization).
  void grid_finer_when_far() {
    const double bound = o_.optimize_options.hausdorff_bound;
    if (!o_.optimize_fallbacks || !first_grid_ || bound <= 0) return;
    const quality::SurfaceDistance& d = in_.distances.measure(hex_, in_.target);
    const bool injected = far_checks_++ < injected_far_;
    double far = injected ? std::numeric_limits<double>::infinity() : d.relative;
    if (far <= bound) return;
    why_ = injected ? std::string("injected distance")
                    : fmt::format("{:.3f} % of the diagonal from the input (bound {:.3f} %)", 100 * far, 100 * bound);
    record_failure();
    const std::string first_name = r_.optimize_fallback;
    const Finer first{first_name, o_.target_hexes, {}, r_.iterations_optimize, false, first_name};
    Finer kept = first;
    const std::vector<core::Vec3> near =
        o_.refine_far ? mesh::polycube_points(map_, far_points(d)) : std::vector<core::Vec3>{};
    Finer tries[] = {{"finer grid near the far points (2x cells there)", o_.target_hexes, near, 0, true, {}},
                     {"finer grid for the distance (2x hexes)", 2 * o_.target_hexes, {}, 0, false, {}}};
    gridded_ = first.name;
    for (Finer& f : tries) {
      if (far <= bound) break;
      if (f.local && !o_.refine_far) continue;
      if (kept.name != first.name) record_failure();  // kept, still too far: why_ says how far
      const std::optional<double> closer = try_finer(f, far);
      if (!closer) continue;
      far = *closer;
      kept = f;
      kept.iterations = r_.iterations_optimize;
      kept.fallback = r_.optimize_fallback;  // with the schedule or retry that gave it
    }
    r_.optimize_fallback = kept.fallback;
    r_.iterations_optimize = kept.iterations;
    if (gridded_ != kept.name)  // the kept mesh's gridding was overwritten
      grid_and_write(map_, kept.target_hexes, sizing_, out_dir_, r_, wrote_, kept.near);
    if (kept.name == first.name)
      core::logger().warn("optimize: no finer grid was valid and closer; keeping the first grid's mesh");
    why_.clear();
  }

  //! Where the mesh misses the input, the farthest first: the two points where the distance is
  //! largest (also for an injected distance), then the input's vertices farther than the bound
  //! from the mesh's boundary and the boundary's vertices farther than it from the input.
  std::vector<core::Vec3> far_points(const quality::SurfaceDistance& d) const {
    const double bound = o_.optimize_options.hausdorff_bound * d.reference_diagonal;
    const core::TriMesh boundary = quality::triangulate(core::boundary(hex_).surface);
    std::vector<quality::FarVertex> far = quality::vertices_farther_than(in_.target, boundary, bound);
    const std::vector<quality::FarVertex> mesh_side = quality::vertices_farther_than(boundary, in_.target, bound);
    far.insert(far.end(), mesh_side.begin(), mesh_side.end());
    std::stable_sort(far.begin(), far.end(),
                     [](const quality::FarVertex& a, const quality::FarVertex& b) { return a.distance > b.distance; });
    std::vector<core::Vec3> out{d.reference_to_surface.worst_point, d.surface_to_reference.worst_point};
    for (const quality::FarVertex& v : far) out.push_back(v.point);
    return out;
  }

  //! One gridding of step 5.
  struct Finer {
    std::string name;
    int target_hexes = 0;
    std::vector<core::Vec3> near;  //!< the points around which the cells are doubled
    int iterations = 0;            //!< the optimizer's iterations for the mesh (once kept)
    bool local = false;            //!< refined near the far points only (RunOptions::refine_far)
    std::string fallback;          //!< the step that gave its mesh (once kept): name, schedule, retry
  };

  //! Grid `f`, optimize it (with step 2 when its boundary crosses itself) and make it the mesh
  //! when it is valid and closer than `far`: returns its distance then, nothing otherwise (the
  //! reason recorded in optimize_tried). A near refinement gets the farthest points whose slabs
  //! make at most kNearHexes times the first grid's hexes (all of them, else the first half, and
  //! so on: f.near is the farthest first); beyond that, the grid twice as fine is as fine there,
  //! and finer elsewhere, so none is tried.
  std::optional<double> try_finer(Finer& f, double far) {
    gridded_ = f.name;
    if (!f.local)
      return optimize_finer(f.name, grid_and_write(map_, f.target_hexes, sizing_, out_dir_, r_, wrote_), far);
    const int plain = r_.hexes;
    for (std::size_t k = f.near.size(); k > 0; k /= 2) {
      f.near.resize(k);
      const core::HexMesh grid = grid_and_write(map_, f.target_hexes, sizing_, out_dir_, r_, wrote_, f.near);
      if (r_.hexes <= kNearHexes * plain) {
        core::logger().info("optimize: {}: the slabs of the {} farthest points, {} hexes", f.name, k, r_.hexes);
        return optimize_finer(f.name, grid, far);
      }
    }
    core::logger().info("optimize: {}: more than {}x the first grid's hexes even for the farthest point; not tried",
                        f.name, kNearHexes);
    return std::nullopt;
  }

  std::optional<double> optimize_finer(const std::string& name, const core::HexMesh& grid, double far) {
    core::logger().warn("optimize: {}; gridding again: {}", why_, name);
    r_.optimize_fallback = name;
    core::HexMesh finer = grid;
    optimize_gridding(finer, grid, name);
    if (why_.empty()) {
      const bool injected = far_checks_++ < injected_far_;
      const double closer = injected ? far : distance(finer);
      if (closer < far) {
        hex_ = std::move(finer);
        why_ = fmt::format("{:.3f} % of the diagonal from the input", 100 * closer);
        return closer;
      }
      why_ = injected ? std::string("injected distance")
                      : fmt::format("{:.3f} % of the diagonal from the input, not closer", 100 * closer);
    }
    record_failure();
    r_.optimize_tried.back() += " (not kept)";
    core::logger().warn("optimize: {}: {}; not kept", name, why_);
    return std::nullopt;
  }

  double distance(const core::HexMesh& hex) const { return in_.distances.measure(hex, in_.target).relative; }

  const core::PolycubeMap& map_;
  const mesh::GridSizing sizing_;
  const ConstructInput& in_;
  const RunOptions& o_;
  const std::filesystem::path& out_dir_;
  RunResult& r_;
  const FileWritten& wrote_;
  const int injected_, injected_crossings_, injected_far_;
  core::HexMesh hex_;
  std::string why_;
  int checks_ = 0;
  int far_checks_ = 0;
  std::string gridded_;  //!< step 5: the name of the gridding hex.mesh holds
  bool crossing_ = false;   //!< the last result failed by its boundary crossing itself only
  bool stopped_ = false;    //!< the last optimization stopped after its untangling (first_try_options)
  bool early_crossing_ = false;  //!< the last result crossed itself already after its untangling
  bool first_grid_ = true;  //!< hex_ comes from the first gridding, unpadded
};

}  // namespace

core::HexMesh optimize_with_fallbacks(const core::HexMesh& gridded, const core::PolycubeMap& map,
                                      mesh::GridSizing sizing, const ConstructInput& in, const RunOptions& o,
                                      const std::filesystem::path& out_dir, RunResult& r, const FileWritten& wrote) {
  return OptimizeStage(map, sizing, in, o, out_dir, r, wrote).run(gridded);
}

}  // namespace polycube::pipeline
