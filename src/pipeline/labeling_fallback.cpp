#include "pipeline/labeling_fallback.h"

#include "core/errors.h"
#include "core/log.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <system_error>
#include <utility>

namespace polycube::pipeline {

namespace {

//! The options of the retry: 0.3 times the compactness, one construction attempt, no wrap.
RunOptions faithful_options(const RunOptions& o) {
  RunOptions f = o;
  f.construct.labeling.compactness = o.construct.labeling.compactness * kFaithfulFactor;
  f.construct.retry_compactness_factors.clear();
  f.construct.predeform_retry = 0;
  f.wrap_fallback = false;
  f.labeling_fallback = false;
  f.inject_failure.clear();
  return f;
}

//! Remove the files `files` lists (never `input`, which may be an earlier run's output).
void remove_files(const std::vector<std::string>& files, const std::filesystem::path& input) {
  std::error_code ec;
  for (const std::string& f : files)
    if (!std::filesystem::equivalent(f, input, ec)) std::filesystem::remove(f, ec);
}

//! Move the retry's files from `from` into `to` (same layout); their new paths replace the old.
void move_files(std::vector<std::string>& files, const std::filesystem::path& from, const std::filesystem::path& to) {
  namespace fs = std::filesystem;
  for (std::string& f : files) {
    const fs::path dest = to / fs::path(f).lexically_relative(from);
    std::error_code ec;
    fs::create_directories(dest.parent_path(), ec);
    fs::rename(f, dest, ec);
    if (ec)
      throw core::OutputError(fmt::format("cannot move {} to {}: {}", f, dest.string(), ec.message()));
    f = dest.string();
  }
}

//! Why the first chain gets the retry: "optimize" (no valid mesh: the optimizer and its
//! fallbacks, or the final check, left hexes inverted), "distance" (beyond the bound),
//! "quality" (an mSJ below kPoorMinSJ while within it), or empty (no retry). The hidden
//! injections "final-distance" and "final-quality" stand for a first mesh beyond any retry's
//! distance or below any retry's mSJ; "optimize" (a stage's injected failure) for the first.
std::string retry_reason(const RunResult& first, const RunOptions& o) {
  if (!first.ok()) {
    // Without the optimizer (--no-optimize) a gridded mesh with inverted hexes is what was asked for.
    const bool no_valid_mesh = first.failed_stage == "optimize" || first.failed_stage == "quality";
    return no_valid_mesh && o.optimize && !first.bad_input ? "optimize" : "";
  }
  if (first.hausdorff_relative < 0) return {};
  const double bound = o.optimize_options.hausdorff_bound;
  if (o.inject_failure == "final-distance" || (bound > 0 && first.hausdorff_relative > bound)) return "distance";
  if (o.inject_failure == "final-quality" || (first.msj > -1.5 && first.msj < kPoorMinSJ)) return "quality";
  return {};
}

//! Why the retry's result `retry` does not replace `first` (empty: it does): it must be valid,
//! and closer to the input when the first was beyond the bound; within the bound and higher in
//! mSJ when the first was poor.
std::string why_not_kept(const RunResult& first, const RunResult& retry, const std::string& reason,
                         const RunOptions& o) {
  if (!retry.ok()) return fmt::format("stage {} failed: {}", retry.failed_stage, retry.failure);
  if (reason == "optimize") return {};  // a valid mesh, whatever its figures, against none
  const bool injected = o.inject_failure == "final-" + reason;
  if (reason == "distance") {
    const double first_distance = injected ? std::numeric_limits<double>::infinity() : first.hausdorff_relative;
    if (retry.hausdorff_relative >= first_distance)
      return fmt::format("{:.3f} % of the diagonal from the input, not closer", 100 * retry.hausdorff_relative);
    return {};
  }
  const double bound = o.optimize_options.hausdorff_bound;
  if (bound > 0 && retry.hausdorff_relative > bound)
    return fmt::format("{:.3f} % of the diagonal from the input, beyond the bound", 100 * retry.hausdorff_relative);
  if (retry.msj <= (injected ? -1.0 : first.msj)) return fmt::format("mSJ {:.3f}, not higher", retry.msj);
  return {};
}

}  // namespace

bool wants_faithful_labeling(const RunResult& first, const RunOptions& o) {
  if (!o.labeling_fallback || !first.construct_fallback.empty()) return false;
  return !retry_reason(first, o).empty();
}

RunResult with_faithful_labeling(const std::filesystem::path& input, const std::filesystem::path& out_dir,
                                 const RunOptions& o, RunResult first, const Chain& chain) {
  namespace fs = std::filesystem;
  const RunOptions f = faithful_options(o);
  LabelingFallback record;
  record.tried = true;
  record.reason = retry_reason(first, o);
  record.compactness = f.construct.labeling.compactness;
  record.charts_first = first.charts;
  record.distance_first = first.hausdorff_relative;
  record.msj_first = first.msj;
  record.failure_first = first.ok() ? std::string() : first.failed_stage + ": " + first.failure;
  const std::string what =
      first.ok() ? fmt::format("the mesh is {:.3f} % of the diagonal from the input (bound {:.3f} %), mSJ {:.3f}",
                               100 * first.hausdorff_relative, 100 * o.optimize_options.hausdorff_bound, first.msj)
                 : fmt::format("no valid mesh ({})", record.failure_first);
  core::logger().warn("run: {}, with a labeling of {} charts; running the chain again with a more faithful labeling "
                      "(compactness {:.3g}), which gives thin parts charts of their own",
                      what, first.charts, record.compactness);
  const fs::path folder = out_dir / kRetryFolder;
  RunResult retry = chain(input, folder, f);
  record.distance_retry = retry.ok() ? retry.hausdorff_relative : -1.0;
  record.msj_retry = retry.ok() ? retry.msj : -2.0;
  record.charts_retry = retry.charts;
  record.why_not = why_not_kept(first, retry, record.reason, o);
  std::error_code ec;
  if (!record.why_not.empty()) {
    fs::remove_all(folder, ec);
    core::logger().warn("run: the more faithful labeling is not kept ({}); keeping the first mesh", record.why_not);
    first.total_seconds += retry.total_seconds;
    first.labeling_fallback = record;
    return first;
  }
  remove_files(first.files, input);
  move_files(retry.files, folder, out_dir);
  fs::remove_all(folder, ec);
  core::logger().info("run: the more faithful labeling is kept: {:.3f} % of the diagonal from the input, mSJ {:.3f}",
                      100 * record.distance_retry, record.msj_retry);
  record.kept = true;
  retry.total_seconds += first.total_seconds;
  retry.peak_memory_mib = std::max(retry.peak_memory_mib, first.peak_memory_mib);
  retry.labeling_fallback = record;
  return retry;
}

}  // namespace polycube::pipeline
