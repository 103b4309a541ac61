//! The whole construction chain (see construct.h): a plan of attempts, each labeling, repairing
//! and deforming the model; the best kept and certified.
#include "construct/construct.h"

#include "construct/labeling_check.h"
#include "construct/polycube_estimate.h"
#include "construct/tip_corners.h"
#include "construct/turning_points.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "quality/distortion.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <map>
#include <numbers>
#include <optional>

namespace polycube::construct {

namespace {

std::string defects_text(const LabelingCheck& check, std::size_t max_listed = 5) {
  std::string s;
  for (std::size_t i = 0; i < check.defects.size() && i < max_listed; ++i)
    s += (i ? "; " : "") + check.defects[i].reason;
  if (check.defects.size() > max_listed) s += fmt::format("; and {} more", check.defects.size() - max_listed);
  return s;
}

void append(std::string& list, const std::string& item) { list += (list.empty() ? "" : "; ") + item; }

//! The attempts' failures as one "; "-separated list (the report's `tried`).
std::string joined(const std::vector<std::string>& items) {
  std::string list;
  for (const std::string& item : items) append(list, item);
  return list;
}

//! One short line for the error: how many attempts failed and why the first did (shortened);
//! every reason is in ConstructResult::tried and in the log (info level, -v).
std::string failure_summary(const std::vector<std::string>& failures) {
  if (failures.empty()) return "no attempt was run";
  constexpr std::size_t kShort = 160;
  std::string first = failures.front();
  if (first.size() > kShort) first = first.substr(0, kShort) + "...";
  // Alike: the same reason after the attempt's name ("compactness 2: ...").
  const auto reason = [](const std::string& f) { return f.substr(std::min(f.find(": "), f.size())); };
  const auto same = std::count_if(failures.begin(), failures.end(),
                                  [&](const std::string& f) { return reason(f) == reason(failures.front()); });
  return fmt::format("{} attempt(s) failed; the first: {}{}", failures.size(), first,
                     failures.size() > 1 ? fmt::format(" ({} of them alike; -v lists every attempt)", same)
                                         : std::string());
}

//! What every attempt reads: the (rotated) mesh and its boundary as a surface.
struct Model {
  core::TetMesh mesh;               //!< in the frame of the polycube's axes
  core::TetBoundary boundary;       //!< mesh's boundary surface
  std::vector<core::Tri> tris;      //!< its triangles in volume indices
  //! #B label each boundary triangle is held to (-1: free) so that sharp tips become corners
  //! (ConstructOptions::tip_corners), or empty.
  std::vector<int> held;
  int tips = 0;  //!< the tips held to be corners
};

//! Hold the sharp tips of the model's surface to be polycube corners (tip_corners.h).
void hold_tip_corners(Model& m) {
  std::vector<TipCorner> tips = find_tip_corners(m.boundary.surface);
  m.held = tip_corner_labels(m.boundary.surface, tips);
  m.tips = static_cast<int>(tips.size());
  for (const TipCorner& tip : tips) {
    std::string labels;
    for (int l : tip.ring_labels) labels += fmt::format(" {}", label_name(l));
    core::logger().info("construct: tip at vertex {} (angle sum {:.1f} deg) held to a corner:{} within {:.3g}",
                        tip.vertex, tip.angle_sum * 180.0 / std::numbers::pi, labels, tip.radius);
  }
}

//! The model rotated so its normals cluster on the axes (when asked): the labeling and the
//! deformation work on the rotated model; the map's model positions stay the input's.
Model rotated_model(const core::TetMesh& input, const ConstructOptions& o, AxisRotation& rotation) {
  auto& log = core::logger();
  Model m{input, {}, {}, {}, 0};
  if (o.align_axes) {
    rotation = best_axis_rotation(core::boundary(input).surface);
    log.debug("construct: axis alignment: L1 energy of the normals {:.4f}, best rotation {:.4f}", rotation.energy_before,
              rotation.energy_best);
    if (!rotation.rotation.isIdentity()) {
      for (core::Vec3& p : m.mesh.points) p = rotation.rotation * p;
      log.info("construct: model rotated to the axes (normals' L1 energy {:.4f} -> {:.4f})", rotation.energy_before,
               rotation.energy_after);
    }
  }
  m.boundary = core::boundary(m.mesh);
  m.tris = core::boundary_triangles(m.boundary);
  if (o.tip_corners) hold_tip_corners(m);
  return m;
}

//! The pre-deformations of a plan, computed once each (attempts of one pass share theirs).
class Predeformations {
 public:
  Predeformations(const Model& model, const ConstructOptions& o, ConstructTimes& seconds)
      : model_(model), o_(o), seconds_(seconds) {}

  //! The pre-deformation of `iterations` iterations (computed on first use).
  const PredeformResult& get(int iterations) {
    auto it = cache_.find(iterations);
    if (it != cache_.end()) return it->second;
    PredeformOptions po = o_.predeform;
    po.iterations = iterations;
    PredeformResult pre = predeform(model_.mesh, model_.tris, po);
    seconds_.predeform += pre.seconds;
    core::logger().info("construct: pre-deformation, {} iterations: misalignment {:.4f} -> {:.4f} ({} tets inverted), "
                        "{:.2f} s",
                        pre.iterations, pre.misalignment_before, pre.misalignment_after, pre.inverted, pre.seconds);
    return cache_.emplace(iterations, std::move(pre)).first->second;
  }

 private:
  const Model& model_;
  const ConstructOptions& o_;
  ConstructTimes& seconds_;
  std::map<int, PredeformResult> cache_;
};

//! A labeling for one attempt: graph cut and repair to validity, with the fast polycube
//! estimate of the result (what the attempts are ordered by).
struct AttemptLabeling {
  RepairResult repair;
  double cut_compactness = 0;  //!< the compactness of the graph cut repaired (cut_and_repair)
  PolycubeEstimate estimate;
  bool valid = false;
};

AttemptLabeling label_for_attempt(const core::TriMesh& s, const LabelingOptions& lopt, const std::vector<int>& held,
                                  const ConstructOptions& o, ConstructTimes& seconds) {
  AttemptLabeling out;
  const core::Stopwatch clock;
  RepairOptions ropt = o.repair;
  ropt.held = held;
  CutAndRepair cr = cut_and_repair(s, lopt, ropt);
  out.cut_compactness = cr.cut.compactness;
  out.repair = std::move(cr.repair);
  if (out.repair.valid()) {
    out.estimate = estimate_polycube(s, out.repair.labels);
    core::logger().info("construct: labeling: {} charts, the polycube estimate folds {} triangles ({:.3g}% of the area)",
                        out.repair.check.layout.num_charts(), out.estimate.flipped.size(),
                        100.0 * out.estimate.flipped_area);
    out.valid = true;
  }
  seconds.label += clock.seconds();  // the cut, its repair and the estimate: one step
  return out;
}

//! The optional local moves on a valid labeling, run only on the attempt being deformed (they
//! cost minutes on large models): unfolding against the estimate's folds, straightening the
//! chart boundaries on `shape` (the pre-deformed surface when there is one). The unfolding leaves
//! the `held` labels (the tips held to be corners) as they are.
void refine_labeling(const core::TriMesh& s, const std::vector<core::Vec3>& shape, const std::vector<int>& held,
                     const Attempt& attempt, const ConstructOptions& o, RepairResult& rep, ConstructTimes& seconds) {
  auto& log = core::logger();
  const core::Stopwatch clock;
  if (attempt.unfold_moves > 0) {
    UnfoldResult un = unfold_labeling(s, rep.labels, attempt.unfold_moves, held);
    if (un.moves > 0) {
      log.info("construct: unfolding the labeling: {} move(s), estimate folds {} -> {} triangles", un.moves,
               un.folded_before, un.folded_after);
      rep.labels = std::move(un.labels);
      rep.check = check_labeling(s, rep.labels);
    }
  }
  if (o.straighten_moves > 0) {
    StraightenResult st = straighten_boundaries(s, shape, rep.labels, o.straighten_moves);
    if (st.moves > 0) {
      log.info("construct: straightening chart boundaries: {} move(s), backward steps {} -> {} (length {:.3g} -> {:.3g})",
               st.moves, st.steps_before, st.steps_after, st.backward_before, st.backward_after);
      rep.labels = std::move(st.labels);
      rep.check = check_labeling(s, rep.labels);
    }
  }
  seconds.repair += clock.seconds();
}

//! What one attempt gave.
struct AttemptResult {
  Attempt attempt;
  int repair_moves = 0;
  double cut_compactness = 0;                //!< its labeling's graph cut (AttemptLabeling)
  std::optional<PredeformResult> predeform;  //!< its pre-deformation (points cleared)
  std::optional<DeformResult> deformation;   //!< empty when no valid labeling or an unrealizable one
  int failures = 0;                          //!< inverted tets + wrong-facing triangles (+1 when not untangled)
  bool valid = false;  //!< untangled, every boundary triangle facing its label, certified
  std::string failure;                       //!< why it is not valid
  std::optional<Certificate> certificate;    //!< of `map`, once certified (valid attempts only)
  core::PolycubeMap map;  //!< the deformation's map in the input's frame, when certified
};

//! Failures of a deformation: tets inverted and boundary triangles facing away from their
//! label in polycube space (with every tet positive, such a triangle means the surface folds
//! over itself).
void judge(AttemptResult& r) {
  const DeformResult& d = *r.deformation;
  const auto& P = d.polycube;
  int inverted = 0, wrong_facing = 0;
  for (const auto& c : d.mesh.cells) inverted += !core::positive_tet(P, c);
  for (std::size_t f = 0; f < d.boundary.size(); ++f) wrong_facing += !faces_label(P, d.boundary[f], d.labels[f]);
  r.failures = inverted + wrong_facing + (d.untangle.untangled ? 0 : 1);
  r.valid = d.untangle.untangled && wrong_facing == 0;
  if (!r.valid)
    r.failure = fmt::format("{}: {} tets stay inverted, {} boundary triangles face away from their label",
                            r.attempt.name(), d.untangle.inverted_after, wrong_facing);
}

//! A planned attempt with its labeling: every attempt is labeled before any is deformed, so
//! the deformations (minutes each) can run in order of their labelings' promise.
struct LabeledAttempt {
  Attempt attempt;
  AttemptLabeling labeling;
  const PredeformResult* predeform = nullptr;  //!< owned by the plan's Predeformations
  std::string failure;                         //!< why there is no valid labeling
};

//! Label one attempt (on the pre-deformed normals when it has a pre-deformation) and repair.
LabeledAttempt label_attempt(const Attempt& attempt, const Model& model, Predeformations& predeformations,
                             const ConstructOptions& o, ConstructTimes& seconds) {
  LabeledAttempt la;
  la.attempt = attempt;
  if (attempt.predeform_iterations > 0) la.predeform = &predeformations.get(attempt.predeform_iterations);
  // The fidelity term reads the normals of the pre-deformed surface (the compactness term
  // keeps the model's, so chart boundaries stay smooth).
  LabelingOptions lopt = o.labeling;
  lopt.compactness = attempt.compactness;
  lopt.penalty = steering_penalty(model.held);
  if (la.predeform) lopt.data_normals = triangle_normals(la.predeform->points, model.tris);
  la.labeling = label_for_attempt(model.boundary.surface, lopt, model.held, o, seconds);
  const RepairResult& rep = la.labeling.repair;
  if (!la.labeling.valid)
    la.failure = fmt::format("{}: no valid labeling ({} defect(s): {})", attempt.name(), rep.check.defects.size(),
                             defects_text(rep.check, 2));
  return la;
}

//! Deform a labeled attempt (from its pre-deformed positions when it has some) and judge it.
AttemptResult deform_attempt(const LabeledAttempt& la, const Model& model, const ConstructOptions& o,
                             const std::function<bool()>& expired, ConstructTimes& seconds) {
  AttemptResult r;
  r.attempt = la.attempt;
  RepairResult rep = la.labeling.repair;
  r.repair_moves = rep.moves;
  r.cut_compactness = la.labeling.cut_compactness;
  std::vector<core::Vec3> shape = model.boundary.surface.points;  // the chart boundaries are straightened on it
  if (const PredeformResult* pre = la.predeform) {
    for (std::size_t i = 0; i < shape.size(); ++i) shape[i] = pre->points[model.boundary.vertex_map[i]];
    r.predeform = PredeformResult{{}, pre->iterations, pre->misalignment_before, pre->misalignment_after,
                                  pre->inverted, pre->seconds};  // its figures, not its points
  }
  refine_labeling(model.boundary.surface, shape, model.held, la.attempt, o, rep, seconds);
  core::logger().info("construct: attempt ({}): labeling valid ({} charts)", la.attempt.name(),
                      rep.check.layout.num_charts());
  DeformOptions deform = o.deform;
  deform.untangle.expired = expired;
  try {
    r.deformation = deform_to_polycube(model.mesh, model.tris, rep.labels, deform,
                                       la.predeform ? &la.predeform->points : nullptr);
  } catch (const UnrealizableLabeling& e) {
    r.failure = fmt::format("{}: {}", la.attempt.name(), e.what());
    core::logger().info("construct: attempt ({}): {}", la.attempt.name(), e.what());
    return r;
  }
  const DeformResult& d = *r.deformation;
  seconds.deform += d.seconds_linear;
  seconds.untangle += d.seconds_untangle;
  core::logger().info("construct: deformation {:.2f} s ({} inverted after the linear step), untangling {:.2f} s "
                      "({} iterations, {} Newton steps, min det {:.3g}, {} inverted)",
                      d.seconds_linear, d.inverted_after_linear, d.seconds_untangle, d.untangle.iterations,
                      d.untangle.newton_steps, d.untangle.min_det, d.untangle.inverted_after);
  judge(r);
  return r;
}

//! Label every attempt of the plan; the ones without a valid labeling are dropped (their
//! reason goes to `failures`).
std::vector<LabeledAttempt> label_plan(const std::vector<Attempt>& plan, const Model& model,
                                       Predeformations& predeformations, const ConstructOptions& o,
                                       ConstructTimes& seconds, std::vector<std::string>& failures) {
  std::vector<LabeledAttempt> labeled;
  for (const Attempt& attempt : plan) {
    LabeledAttempt la = label_attempt(attempt, model, predeformations, o, seconds);
    if (la.labeling.valid)
      labeled.push_back(std::move(la));
    else
      failures.push_back(la.failure);
  }
  return labeled;
}

//! Order the labeled attempts by their chance of success. The plan's first attempt (the
//! user's labeling) stays first: it certifies every shared model, whatever its estimate folds
//! (fandisk's folds 5.8 % of the area and succeeds; bench/RESULTS.md). The fallbacks follow
//! by the fast estimate's folded area, the surface the deformation will have to unfold: on the
//! models where the first attempt fails, the plan's own order tried the labelings that fold
//! most first. Equal areas keep the plan's order.
void order_by_promise(std::vector<LabeledAttempt>& labeled, const Attempt& first) {
  auto begin = labeled.begin();
  if (begin != labeled.end() && begin->attempt == first) ++begin;
  std::stable_sort(begin, labeled.end(), [](const LabeledAttempt& a, const LabeledAttempt& b) {
    return a.labeling.estimate.flipped_area < b.labeling.estimate.flipped_area;
  });
}

//! The order the attempts will be deformed in, with their estimates (for the log).
void log_order(const std::vector<LabeledAttempt>& labeled) {
  std::string order;
  for (const LabeledAttempt& la : labeled)
    append(order, fmt::format("{} ({:.3g}% folded)", la.attempt.name(), 100.0 * la.labeling.estimate.flipped_area));
  core::logger().info("construct: attempts in order: {}", order);
}

//! When an attempt started at `now` must stop (seconds since the construction started; 0: no
//! limit): at the budget when it is the last allowed attempt, else halfway through what is
//! left, so that a hopeless attempt leaves time for the others.
double attempt_deadline(double time_limit, double now, bool others_left) {
  if (time_limit <= 0) return 0;
  return others_left ? now + 0.5 * std::max(0.0, time_limit - now) : std::max(time_limit, now);
}

core::PolycubeMap map_of(const DeformResult& d, const core::TetMesh& input,
                         const AxisRotation& rotation);

//! The attempt's map as it will be written (the input's frame) and its certificate.
void certify_map(AttemptResult& r, const core::TetMesh& input, const ConstructOptions& o,
                 ConstructResult& res) {
  const core::Stopwatch clock;
  const DeformResult& d = *r.deformation;
  r.map = map_of(d, input, res.axis_rotation);
  r.certificate = certify_polycube_map(r.map, d.boundary, d.labels, o.certify);
  res.seconds.certify += clock.seconds();
}

//! Certify an attempt judged valid. Every tet positive and every boundary triangle facing its
//! label do not keep the polycube's boundary from crossing itself elsewhere; such an attempt is
//! not valid, and the plan goes on to the next one rather than stopping with it.
void certify_attempt(AttemptResult& r, const core::TetMesh& input, const ConstructOptions& o,
                     bool inject_failure, ConstructResult& res) {
  certify_map(r, input, o, res);
  if (inject_failure) r.certificate->failures.push_back("injected failure");
  if (r.certificate->certified()) return;
  r.valid = false;
  r.failures = 1;
  r.failure = fmt::format("{}: not certified: {}", r.attempt.name(), r.certificate->reason());
  core::logger().info("construct: attempt ({}) not certified: {}", r.attempt.name(),
                      r.certificate->reason());
}

//! Run the plan: label its first attempt (the user's labeling, deformed first whatever the
//! others' estimates, order_by_promise) and deform it; only when it fails, label the others,
//! order them, and deform them in turn until one is valid and certified. The labelings of the
//! fallbacks (a pre-deformation among them) are never looked at when the first attempt
//! certifies, as it does on every shared model. Keep the attempt with the fewest failures (the
//! first valid one). `failures` lists why the others failed.
std::optional<AttemptResult> run_plan(const std::vector<Attempt>& plan, const Model& model,
                                      const core::TetMesh& input, const ConstructOptions& o,
                                      const core::Stopwatch& clock, ConstructResult& res,
                                      std::vector<std::string>& failures) {
  if (plan.empty()) return std::nullopt;
  Predeformations predeformations(model, o, res.seconds);
  const std::vector<Attempt> first(plan.begin(), plan.begin() + 1), rest(plan.begin() + 1, plan.end());
  std::vector<LabeledAttempt> labeled = label_plan(first, model, predeformations, o, res.seconds, failures);
  bool all_labeled = rest.empty();
  std::optional<AttemptResult> kept;
  const auto max_attempts = static_cast<std::size_t>(std::max(0, o.max_attempts));
  for (std::size_t i = 0; i < max_attempts; ++i) {
    if (res.attempts > 0 && o.time_limit > 0 && clock.seconds() > o.time_limit) {
      failures.push_back(fmt::format("time limit of {:g} s reached after {} attempt(s)", o.time_limit, res.attempts));
      break;
    }
    if (i == labeled.size() && !all_labeled) {
      std::vector<LabeledAttempt> more = label_plan(rest, model, predeformations, o, res.seconds, failures);
      labeled.insert(labeled.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
      order_by_promise(labeled, plan.front());
      log_order(labeled);
      all_labeled = true;
    }
    if (i >= labeled.size()) break;
    // Attempts planned: the whole plan until the fallbacks are labeled, then those with a labeling.
    const int count = static_cast<int>(std::min(all_labeled ? labeled.size() : plan.size(), max_attempts));
    const LabeledAttempt& la = labeled[i];
    if (o.on_attempt) o.on_attempt(static_cast<int>(i) + 1, count, la.attempt, clock.seconds());
    ++res.attempts;
    const double started = clock.seconds();
    const double deadline = attempt_deadline(o.time_limit, started, static_cast<int>(i) + 1 < count);
    const std::function<bool()> expired = [&clock, deadline] { return deadline > 0 && clock.seconds() > deadline; };
    AttemptResult r = deform_attempt(la, model, o, expired, res.seconds);
    if (deadline > 0 && clock.seconds() > deadline && !r.valid)
      r.failure += fmt::format(" (stopped at its budget of {:.0f} s)", deadline - started);
    if (static_cast<int>(i) < o.inject_failed_attempts && r.valid) {
      r.valid = false;
      r.failures = 1;
      r.failure = la.attempt.name() + ": injected failure";
    }
    if (r.valid) certify_attempt(r, input, o, static_cast<int>(i) < o.inject_uncertified_attempts, res);
    if (!r.failure.empty()) failures.push_back(r.failure);
    if (r.deformation && (!kept || r.valid || r.failures < kept->failures)) kept = std::move(r);
    if (kept && kept->valid) break;
  }
  return kept;
}

//! The map of a deformation, with the input's model positions (the deformation worked in the
//! rotated frame; vertices it added are rotated back).
core::PolycubeMap map_of(const DeformResult& d, const core::TetMesh& input, const AxisRotation& rotation) {
  core::PolycubeMap map;
  map.tets = d.mesh.cells;
  map.model = d.mesh.points;
  if (!rotation.rotation.isIdentity()) {
    const Eigen::Matrix3d back = rotation.rotation.transpose();
    for (std::size_t v = 0; v < map.model.size(); ++v)
      map.model[v] = v < input.points.size() ? input.points[v] : core::Vec3(back * map.model[v]);
  }
  map.polycube = d.polycube;
  return map;
}

//! The deformation's labeled boundary in core::boundary() order (the order of the written
//! Triangles blocks), as a surface in the rotated frame where the labels are axes.
core::TriMesh boundary_in_core_order(const DeformResult& d, std::vector<core::Tri>& boundary, std::vector<int>& labels) {
  std::vector<std::pair<std::array<int, 3>, int>> keys(d.boundary.size());
  for (std::size_t i = 0; i < d.boundary.size(); ++i) {
    std::array<int, 3> k{d.boundary[i][0], d.boundary[i][1], d.boundary[i][2]};
    std::sort(k.begin(), k.end());
    keys[i] = {k, d.labels[i]};
  }
  std::sort(keys.begin(), keys.end());
  core::TriMesh surface;
  surface.points = d.mesh.points;
  for (const core::Tri& tri : core::boundary_triangles(core::boundary(d.mesh))) {
    std::array<int, 3> k{tri[0], tri[1], tri[2]};
    std::sort(k.begin(), k.end());
    const auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    PC_REQUIRE(it != keys.end() && it->first == k, "construct: certified boundary lost a triangle");
    boundary.push_back(tri);
    labels.push_back(it->second);
    surface.cells.push_back(tri);
  }
  return surface;
}

//! The figures of a certified map: its layout, the labeling's fidelity, its distortion.
void describe(const DeformResult& d, const core::TriMesh& surface, ConstructResult& res) {
  const LabelingCheck check = check_labeling(surface, res.labels);
  res.charts = check.layout.num_charts();
  res.corners = static_cast<int>(check.layout.corners.size());
  res.boundaries = check.layout.num_boundaries;
  res.fidelity = labeling_fidelity(surface, res.labels);
  quality::DistortionOptions dopt;
  dopt.normalize_volume = true;
  dopt.keep_per_tet = false;
  const quality::MapDistortion dist = quality::map_distortion(d.mesh, d.polycube, dopt);
  res.isometric_average = dist.isometric.average;
  res.isometric_max = dist.isometric.max;
  res.conformal_average = dist.conformal.average;
  res.conformal_max = dist.conformal.max;
}

//! The kept attempt's figures into the report.
void report_attempt(const AttemptResult& kept, ConstructResult& res) {
  const DeformResult& d = *kept.deformation;
  res.attempt = kept.attempt;
  res.repair_moves = kept.repair_moves;
  res.cut_compactness = kept.cut_compactness;
  if (kept.predeform) res.predeform = *kept.predeform;
  res.split_triangles = d.split_triangles;
  res.split_edges = d.split_edges;
  res.split_faces = d.split_faces;
  res.refined_edges = d.refined_edges;
  res.boundary_first = d.boundary_first;
  res.inverted_after_linear = d.inverted_after_linear;
  res.untangle = d.untangle;
}

}  // namespace

std::string Attempt::name() const {
  return fmt::format("{}compactness {:.3g}", retry ? "pre-deformed, " : "", compactness);
}

std::vector<Attempt> plan_attempts(const ConstructOptions& o) {
  std::vector<double> factors{1.0};
  factors.insert(factors.end(), o.retry_compactness_factors.begin(), o.retry_compactness_factors.end());
  std::vector<Attempt> plan;
  for (double f : factors) plan.push_back({o.predeform.iterations, o.unfold_moves, o.labeling.compactness * f, false});
  if (o.predeform.iterations == 0 && o.predeform_retry > 0)
    for (double f : factors)
      plan.push_back({o.predeform_retry, std::max(o.unfold_moves, o.predeform_retry_unfold_moves),
                      o.labeling.compactness * f, true});
  return plan;
}

ConstructResult construct_from_prepared(const core::TetMesh& input, const ConstructOptions& o) {
  const core::Stopwatch clock;
  ConstructResult res;
  const Model model = rotated_model(input, o, res.axis_rotation);
  res.tip_corners = model.tips;
  std::vector<std::string> failures;
  std::optional<AttemptResult> kept =
      run_plan(plan_attempts(o), model, input, o, clock, res, failures);
  res.tried = joined(failures);
  if (!failures.empty()) core::logger().info("construct: failed attempts: {}", res.tried);
  if (!kept) throw NoValidLabeling("no valid polycube labeling reached: " + failure_summary(failures));
  if (!kept->valid)
    core::logger().warn("construct: no attempt was valid ({})", failure_summary(failures));
  report_attempt(*kept, res);

  if (!kept->certificate) certify_map(*kept, input, o, res);  // valid attempts were in the plan
  const DeformResult& d = *kept->deformation;
  res.map = std::move(kept->map);
  res.certificate = *kept->certificate;
  if (!res.certificate.certified())
    throw NotCertified("polycube map not certified: " + res.certificate.reason() +
                           (failures.empty() ? std::string() : " (attempts: " + failure_summary(failures) + ")"),
                       res.map, d.boundary, d.labels);
  const core::Stopwatch describe_clock;
  describe(d, boundary_in_core_order(d, res.boundary, res.labels), res);
  res.seconds.certify += describe_clock.seconds();
  res.seconds.total = clock.seconds();
  return res;
}

namespace {

//! TetGen (again with a volume bound when its mesh is too coarse), then the attempts.
ConstructResult construct_tetrahedralized(const core::TriMesh& surface, const ConstructOptions& o) {
  const core::Stopwatch clock;
  TetrahedralizeResult tr = tetrahedralize(surface, o.tetrahedralize);
  if (o.tetrahedralize.max_volume == 0.0 && o.min_tets > 0 && tr.mesh.num_cells() < o.min_tets) {
    // Too coarse an interior leaves too little room to open a polycube corner where the
    // model's surface is nearly flat: bound the tet volume so that the volume alone asks for
    // about min_tets tets.
    double volume = 0.0;
    for (const auto& c : tr.mesh.cells) {
      const auto& p = tr.mesh.points;
      volume += (p[c[1]] - p[c[0]]).dot((p[c[2]] - p[c[0]]).cross(p[c[3]] - p[c[0]])) / 6.0;
    }
    const core::Vec3 ext = core::bounding_box(surface.points).extent();
    const double box = ext.x() * ext.y() * ext.z();
    if (volume > 0.0 && box > 0.0) {
      TetrahedralizeOptions finer = o.tetrahedralize;
      finer.max_volume = 2.0 * volume / o.min_tets / box;
      core::logger().info("construct: {} tets is below {}: tetrahedralize again with max volume {:.3g} of the box",
                          tr.mesh.num_cells(), o.min_tets, finer.max_volume);
      tr = tetrahedralize(surface, finer);
    }
  }
  const double t_tet = clock.seconds();
  ConstructResult res = construct_from_prepared(tr.mesh, o);
  res.tetgen_tets = tr.tetgen_tets;
  res.refine = tr.refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

//! The surface split until no edge exceeds the diagonal over `coarse_edge_ratio`, or nullopt when
//! no edge does (the labeling failed for another reason).
//! The most triangles a coarse surface is split into: enough for the coarsest solids (a
//! tetrahedron ends at a few thousand triangles); a cap so that a fine surface with a few long
//! edges is not multiplied beyond what TetGen takes.
constexpr int kMaxCoarseTriangles = 200000;

std::optional<core::TriMesh> refined_coarse_surface(const core::TriMesh& surface, const ConstructOptions& o,
                                                    SurfaceRefinement& done) {
  if (o.coarse_edge_ratio <= 0.0) return std::nullopt;
  const double max_edge = core::bounding_box(surface.points).extent().norm() / o.coarse_edge_ratio;
  if (longest_edge(surface) <= max_edge) return std::nullopt;
  core::TriMesh finer = subdivide_to(surface, max_edge, kMaxCoarseTriangles, done);
  if (done.levels == 0) return std::nullopt;
  return finer;
}



//! What the user can do about a labeling that failed, when the shape says: a solid much thinner
//! than it is wide (a slab of 1 x 1 x 1e-6) leaves its sides too narrow for charts of their own.
//! Its mean thickness 2 V / A is exact for a slab (and 2r/3 for a ball of radius r).
std::string labeling_hint(const core::TriMesh& surface, const SurfaceRefinement& done) {
  std::string hint;
  if (done.levels > 0)
    hint += fmt::format("; the surface was refined from {} to {} triangles first", done.triangles_before,
                        done.triangles_after);
  double area = 0.0;
  for (const core::Tri& t : surface.cells)
    area += 0.5 * (surface.points[t[1]] - surface.points[t[0]]).cross(surface.points[t[2]] - surface.points[t[0]]).norm();
  const double diagonal = core::bounding_box(surface.points).extent().norm();
  const double thickness = area > 0.0 ? 2.0 * std::abs(core::signed_volume(surface)) / area : 0.0;
  constexpr double kThin = 1e-3;  // of the diagonal: far below any part the tool is meant for
  if (diagonal > 0.0 && thickness < kThin * diagonal)
    hint += fmt::format(
        "; the solid is thin (mean thickness 2 volume / area = {:.3g}, {:.2g} of its diagonal): its sides are too narrow "
        "to label; thicken it",
        thickness, thickness / diagonal);
  return hint;
}



//! The construction of a surface at the resolution it is given: refined first when it is too
//! coarse to label (coarse_surface.h).
ConstructResult construct_surface(const core::TriMesh& surface, const ConstructOptions& o) {
  const core::Stopwatch clock;
  SurfaceRefinement done;
  std::optional<core::TriMesh> finer;
  try {
    return construct_tetrahedralized(surface, o);
  } catch (const NoValidLabeling& e) {
    finer = refined_coarse_surface(surface, o, done);
    if (!finer) throw NoValidLabeling(e.what() + labeling_hint(surface, done));
    core::logger().warn(
        "construct: no valid labeling on {} triangles (longest edge {:.4g}): the surface is too coarse; every "
        "triangle split into {} at its edges' midpoints ({} triangles, longest edge {:.4g}, the surface unchanged), "
        "constructing again",
        done.triangles_before, done.longest_edge_before, 1 << (2 * done.levels), done.triangles_after,
        done.longest_edge_after);
  }
  const double failed = clock.seconds();
  ConstructOptions coarse = o;
  coarse.tip_corners = true;  // every vertex of the input is a feature of the shape
  for (;;) {
    try {
      ConstructResult res = construct_tetrahedralized(*finer, coarse);
      res.coarse_refinement = done;
      res.seconds.total += failed;
      return res;
    } catch (const NoValidLabeling& e) {
      throw NoValidLabeling(e.what() + labeling_hint(surface, done));
    } catch (const TetgenFailed& e) {
      // TetGen's degenerate cases on a split surface (many coplanar points) depend on the split:
      // a triangular bipyramid split 4, 16, 64 or 256 times stops TetGen, 1,024 times does not.
      if (4 * finer->num_cells() > kMaxCoarseTriangles) throw;
      SurfaceRefinement again;
      *finer = subdivide_to(*finer, 0.5 * longest_edge(*finer), kMaxCoarseTriangles, again);
      done.levels += again.levels;
      done.triangles_after = again.triangles_after;
      done.longest_edge_after = again.longest_edge_after;
      core::logger().warn("construct: {}; every triangle split into four once more ({} triangles)", e.what(),
                          done.triangles_after);
    }
  }
}

//! The input surface, or the surface decimated when it is finer than the construction needs.
std::optional<core::TriMesh> decimated_for_construction(const core::TriMesh& surface, const ConstructOptions& o,
                                                        SurfaceDecimation& done) {
  const double tolerance = o.decimation_tolerance * core::bounding_box(surface.points).extent().norm();
  if (o.max_triangles <= 0 || static_cast<int>(surface.num_cells()) <= o.max_triangles) return std::nullopt;
  std::optional<core::TriMesh> decimated =
      decimate_surface(surface, std::min(o.decimate_to, o.max_triangles), tolerance, done);
  if (decimated)
    core::logger().info(
        "construct: the surface has {} triangles, more than the construction needs: decimated to {} (no vertex "
        "farther than {:.3g} from it, {:.2g} of the diagonal; {:.1f} s); the map is of the decimated solid "
        "(--max-triangles)",
        done.triangles_before, done.triangles_after, done.tolerance, o.decimation_tolerance, done.seconds);
  return decimated;
}

}  // namespace

ConstructResult construct_polycube(const core::TriMesh& surface, const ConstructOptions& o) {
  SurfaceDecimation decimation;
  const std::optional<core::TriMesh> decimated = decimated_for_construction(surface, o, decimation);
  ConstructResult res = construct_surface(decimated ? *decimated : surface, o);
  res.decimation = decimation;
  res.seconds.decimate = decimation.seconds;
  res.seconds.total += decimation.seconds;
  return res;
}

ConstructResult construct_polycube(core::TetMesh mesh, const ConstructOptions& o) {
  const core::Stopwatch clock;
  prepare_tet_mesh(mesh);
  const RefineStats refine = refine_boundary(mesh);
  const double t_tet = clock.seconds();
  ConstructResult res = construct_from_prepared(mesh, o);
  res.refine = refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

}  // namespace polycube::construct
