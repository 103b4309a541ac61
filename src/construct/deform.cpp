//! Polycube deformation (see deform.h): the steps, each one function of mapping/.
#include "construct/deform.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "mapping/boundary_first.h"
#include "mapping/ghost_tets.h"
#include "mapping/labeled_mesh.h"

#include <Eigen/LU>
#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace polycube::construct {

namespace {

using core::Tri;
using core::Vec3;
using mapping::LabeledTetMesh;

//! Steps 1–2: split what the chart constraints would force onto polycube edges (chords, then
//! flat triangles), then widen thin corner fans. `start` (optional) is refined alongside.
void make_realizable(LabeledTetMesh& lm, int min_fan, std::vector<Vec3>* start, DeformResult& res) {
  constexpr int kMaxRounds = 12;
  bool unlock = true;
  for (int round = 0;; ++round) {
    mapping::update_charts(lm);
    const std::vector<std::array<int, 2>> chords = mapping::chord_edges(lm);
    const std::vector<int> flat = chords.empty() ? mapping::forced_flat_triangles(lm) : std::vector<int>{};
    const std::vector<mapping::LockedVertex> locked = chords.empty() && flat.empty() && unlock && round < kMaxRounds
                                                          ? mapping::locked_interior_vertices(lm)
                                                          : std::vector<mapping::LockedVertex>{};
    const std::vector<std::array<int, 2>> fans = chords.empty() && flat.empty() && locked.empty()
                                                     ? mapping::thin_fan_edges(lm, min_fan)
                                                     : std::vector<std::array<int, 2>>{};
    if (chords.empty() && flat.empty() && locked.empty() && (fans.empty() || round >= kMaxRounds)) return;
    if (!locked.empty()) {
      std::vector<char> touched(lm.mesh.cells.size(), 0);
      int split = 0;
      for (const auto& l : locked) split += mapping::split_interior_face(lm, l.face, touched, start) ? 1 : 0;
      core::logger().info("deform: {} interior link faces of vertices that see only one chart plane: {} split",
                          locked.size(), split);
      res.split_faces += split;
      unlock = split > 0;
    } else if (!fans.empty()) {
      res.split_fan_edges += mapping::split_edges(lm, fans, start);
    } else if (round >= kMaxRounds) {
      std::vector<int> where;
      for (const auto& e : chords) where.insert(where.end(), e.begin(), e.end());
      for (int f : flat) where.insert(where.end(), lm.boundary[f].begin(), lm.boundary[f].end());
      throw UnrealizableLabeling(fmt::format("deform: {} boundary edges and {} triangles stay forced onto polycube "
                                             "edges by the labeling after splitting",
                                             chords.size(), flat.size()),
                                 std::move(where));
    } else if (!chords.empty()) {
      res.split_edges += mapping::split_edges(lm, chords, start);
    } else {
      std::vector<char> touched(lm.mesh.cells.size(), 0);
      for (int f : flat) res.split_triangles += mapping::split_boundary_triangle(lm, f, touched, start) ? 1 : 0;
    }
    mapping::refresh_boundary(lm);
  }
}

//! Two distinct vertices tied to the same chart coordinates on all three axes would coincide.
void check_no_coinciding_vertices(const LabeledTetMesh& lm) {
  const std::vector<int>& group = lm.charts.vertex_group;
  const auto et = core::unique_edges(lm.mesh);
  for (const auto& e : et.edges) {
    bool same = true;
    for (int a = 0; a < 3 && same; ++a) {
      const int g = group[3 * static_cast<std::size_t>(e[0]) + a];
      same = g >= 0 && g == group[3 * static_cast<std::size_t>(e[1]) + a];
    }
    if (same)
      throw UnrealizableLabeling(fmt::format("deform: the labeling forces vertices {} and {} (an edge) onto one polycube "
                                             "point: both are corners of the same three charts",
                                             e[0], e[1]),
                                 {e[0], e[1]});
  }
}

//! Keep the first run's "before" figures and the last run's outcome.
void merge(solve::UntangleResult& into, const solve::UntangleResult& r) {
  into.untangled = r.untangled;
  into.iterations += r.iterations;
  into.newton_steps += r.newton_steps;
  into.inverted_after = r.inverted_after;
  into.min_det = r.min_det;
  into.energy = r.energy;
  into.epsilon = r.epsilon;
}

//! Edges of the tets with det J <= min_det in P (to refine around them).
std::vector<std::array<int, 2>> inverted_tet_edges(const LabeledTetMesh& lm, const std::vector<Vec3>& P, double min_det) {
  const solve::TetElements el = solve::reference_elements(lm.mesh.points, lm.mesh.cells);
  std::vector<std::array<int, 2>> edges;
  for (int t = 0; t < el.size(); ++t) {
    const auto& c = el.tets[t];
    Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
    for (int i = 0; i < 4; ++i) J += P[c[i]] * el.gradients[t].row(i);
    if (J.determinant() > min_det) continue;
    for (const auto& e : core::kTetEdges) edges.push_back({std::min(c[e[0]], c[e[1]]), std::max(c[e[0]], c[e[1]])});
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

//! Step 4: the repairs of one deformation, run round by round (a round ends with a local
//! refinement around the tets that stay inverted).
class Untangling {
 public:
  //! Outcome of a round.
  enum class Round { Valid, RetryPlacement, Stuck };

  Untangling(const DeformOptions& o, LabeledTetMesh& lm, std::vector<Vec3>& P, double ghost_h, DeformResult& res)
      : o_(o), lm_(lm), P_(P), res_(res), use_boundary_first_(o.boundary_first != BoundaryFirst::Off && ghost_h > 0) {
    map_options_.untangle = o.untangle;
    // After the flow the map is almost untangled: a large ε would undo it (ε's rule raises it
    // again where a tet is still inverted).
    if (o.first.method == mapping::FirstPolycubeMethod::PlanarityFlow)
      map_options_.untangle.initial_epsilon = o.first.flow.snap_epsilon;
    map_options_.ghost_height = ghost_h;
  }

  //! The caller's time budget ran out (DeformOptions::untangle.expired): no further step.
  [[nodiscard]] bool expired() const { return o_.untangle.expired && o_.untangle.expired(); }

  //! The boundary-first placement is tried before the untangling in the first round.
  [[nodiscard]] bool placement_first() const { return use_boundary_first_ && o_.boundary_first == BoundaryFirst::First; }

  //! One round: the boundary first when asked, the global untangling, the local repair, then
  //! the boundary first when it was not tried yet.
  Round run(int round, bool placement_first) {
    if (placement_first) {
      const Placed placed = place_boundary_first();
      if (placed != Placed::Failed) return placed == Placed::Valid ? Round::Valid : Round::RetryPlacement;
    }
    const solve::UntangleResult ur = mapping::untangle_globally(lm_, P_, map_options_);
    if (round == 0 && !placement_first) res_.untangle = ur;
    else merge(res_.untangle, ur);
    if (ur.untangled) return Round::Valid;
    if (expired()) return Round::Stuck;
    // A few tets left: repair them locally, then go back through the global optimizer (from a
    // valid state it stays valid) to spread the distortion, and take its verdict.
    const mapping::LocalRepairResult lr = mapping::repair_locally(lm_, P_, map_options_, o_.local_repair);
    res_.reopened_fans += lr.reopened_fans;
    if (lr.fixed) {
      merge(res_.untangle, mapping::untangle_globally(lm_, P_, map_options_));
      if (res_.untangle.untangled) return Round::Valid;
    }
    if (use_boundary_first_ && !placement_first && !expired()) {
      const Placed placed = place_boundary_first();
      if (placed != Placed::Failed) return placed == Placed::Valid ? Round::Valid : Round::RetryPlacement;
    }
    return Round::Stuck;
  }

 private:
  enum class Placed { Valid, Retry, Failed };

  //! The boundary first (mapping/boundary_first.h). A valid placement goes through the global
  //! optimizer once more with the boundary free (from a valid state it stays valid), with a
  //! tighter tolerance; a placement that leaves a few tets inverted is refined around them and
  //! placed again in the next round.
  Placed place_boundary_first() {
    std::vector<Vec3> valid = P_;
    const core::TetMesh& mesh = lm_.mesh;
    const mapping::BoundaryFirstResult bf =
        mapping::place_boundary_first(mesh.points, mesh.cells, lm_.boundary, lm_.labels, lm_.charts.vertex_group,
                                      valid, map_options_.untangle, map_options_.ghost_height, placement_sigma_);
    // A tangle the fast schedule left was hard: the next placements of this deformation (the
    // same shape, refined) go straight to the paper's schedule instead of trying it first again.
    if (bf.volume_step.slower_schedule) placement_sigma_ = 0.0;
    core::logger().info("deform: boundary-first placement: {} chains ({} reversed); charts {} ({} facing away, {:.1f} "
                        "s); volume {} ({} inverted, {:.1f} s{}){}{}",
                        bf.chains, bf.reversed_chains, bf.chart_step.untangled ? "untangled" : "tangled", bf.charts_inverted,
                        bf.chart_step.seconds, bf.volume_step.untangled ? "untangled" : "tangled", bf.tets_inverted,
                        bf.volume_step.seconds, bf.volume_step.slower_schedule ? ", the slower ε schedule after the fast one" : "",
                        bf.valid ? "" : ": ", bf.reason);
    if (!bf.locked_triangles.empty() && unlocks_ < kMaxUnlocks && unlock(bf.locked_triangles)) {
      ++unlocks_;
      return place_boundary_first();
    }
    if (bf.valid) {
      P_ = valid;
      mapping::UntangleMapOptions relax = map_options_;
      relax.untangle.tolerance = o_.untangle.tolerance * o_.boundary_first_relax_tolerance;
      relax.untangle.max_iterations = std::min(o_.untangle.max_iterations, o_.boundary_first_relax_iterations);
      solve::UntangleResult r = mapping::untangle_globally(lm_, P_, relax);  // the boundary free again
      if (!r.untangled || mapping::failures(lm_, P_) > 0) {
        P_ = valid;  // keep the valid placement
        r.untangled = true;
        r.inverted_after = 0;
      }
      merge(res_.untangle, r);
      res_.boundary_first = true;
      return Placed::Valid;
    }
    if (!bf.placement.empty() && placements_ < o_.boundary_first_refinements) {
      ++placements_;
      P_ = bf.placement;
      return Placed::Retry;
    }
    return Placed::Failed;
  }

  //! Split the edges of the locked chart triangles that cross their chart (their ends are not
  //! on one polycube edge): each midpoint is free in the chart plane, so the 2D step can turn
  //! the triangles around. The positions P_ get the midpoints (chart coordinates stay exact).
  //! False when there is no such edge.
  bool unlock(const std::vector<int>& locked) {
    const std::vector<int>& group = lm_.charts.vertex_group;
    std::vector<std::array<int, 2>> edges;
    for (int f : locked) {
      const Tri& t = lm_.boundary[static_cast<std::size_t>(f)];
      for (int i = 0; i < 3; ++i) {
        const int u = t[i], w = t[(i + 1) % 3];
        int shared = 0;
        for (int a = 0; a < 3; ++a) {
          const int g = group[3 * static_cast<std::size_t>(u) + a];
          shared += g >= 0 && g == group[3 * static_cast<std::size_t>(w) + a];
        }
        if (shared < 2) edges.push_back({std::min(u, w), std::max(u, w)});
      }
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    const int split = edges.empty() ? 0 : mapping::split_edges(lm_, edges, &P_);
    core::logger().info("deform: {} chart triangles on polycube edges only face away: {} of their edges split",
                        locked.size(), split);
    if (split == 0) return false;
    res_.split_edges += split;
    mapping::refresh_boundary(lm_);
    mapping::update_charts(lm_);
    return true;
  }

  static constexpr int kMaxUnlocks = 2;
  const DeformOptions& o_;
  LabeledTetMesh& lm_;
  std::vector<Vec3>& P_;
  DeformResult& res_;
  mapping::UntangleMapOptions map_options_;
  bool use_boundary_first_;
  //! The placement's fast ε schedule (mapping::place_boundary_first), until it fails once.
  double placement_sigma_ = mapping::kFastPlacementSigma;
  int placements_ = 0;  // boundary-first placements retried after a refinement
  int unlocks_ = 0;     // placements retried after unlock()
};

//! Step 4 in rounds: when tets stay inverted, refine locally (split every edge of those tets)
//! and start again from the current positions.
void untangle_in_rounds(const DeformOptions& o, LabeledTetMesh& lm, std::vector<Vec3>& P, double ghost_h,
                        DeformResult& res) {
  Untangling untangling(o, lm, P, ghost_h, res);
  bool placement_first = untangling.placement_first();
  for (int round = 0;; ++round) {
    const Untangling::Round outcome = untangling.run(round, placement_first);
    if (outcome == Untangling::Round::Valid) return;
    placement_first = outcome == Untangling::Round::RetryPlacement;
    if ((!placement_first && round >= o.refine_rounds) || untangling.expired()) return;
    const int split = mapping::split_edges(lm, inverted_tet_edges(lm, P, o.untangle.min_det_target), &P);
    res.refined_edges += split;
    core::logger().debug("deform: {} tets stay inverted; refinement round {} split {} edges",
                         res.untangle.inverted_after, round + 1, split);
    if (split == 0) return;
    mapping::refresh_boundary(lm);
    mapping::update_charts(lm);
  }
}

}  // namespace

solve::UntangleOptions deform_untangle_defaults() {
  solve::UntangleOptions u;
  u.max_iterations = 150;
  u.newton_steps = 2;
  u.volume_weight = 1.0;
  u.initial_epsilon = 0.05;
  u.tolerance = 1e-4;
  u.min_det_target = 1e-6;
  u.stall_min_det_rise = 0.005;
  return u;
}

DeformResult deform_to_polycube(const core::TetMesh& input, const std::vector<Tri>& boundary,
                                const std::vector<int>& labels, const DeformOptions& o,
                                const std::vector<Vec3>* initial) {
  const core::Stopwatch clock;
  core::check_indices(input);
  LabeledTetMesh lm = mapping::label_tet_mesh(input, boundary, labels);
  if (initial && initial->size() != lm.mesh.points.size())
    throw core::InputError(fmt::format("deform: {} initial positions for {} vertices", initial->size(), lm.mesh.points.size()));
  // Starting positions: the model, or the caller's (a pre-deformed model), refined alongside.
  std::vector<Vec3> start = initial ? *initial : std::vector<Vec3>{};
  DeformResult res;
  make_realizable(lm, o.min_fan, initial ? &start : nullptr, res);
  check_no_coinciding_vertices(lm);
  const double ghost_h = mapping::ghost_height(lm.mesh.points, lm.boundary, o.ghost_height);

  // 3. The first polycube.
  mapping::FirstPolycube first =
      mapping::first_polycube(lm, initial ? start : lm.mesh.points, ghost_h, initial != nullptr, o.first);
  res.inverted_after_linear = first.inverted;
  res.flow_iterations = first.flow_iterations;
  res.flow_residual = first.flow_residual;
  std::vector<Vec3> P = std::move(first.points);
  res.seconds_linear = clock.seconds();

  // 4. Untangle, then lower the distortion, keeping the chart constraints exactly.
  const core::Stopwatch untangle_clock;
  untangle_in_rounds(o, lm, P, ghost_h, res);
  res.seconds_untangle = untangle_clock.seconds();
  res.triangle_chart = lm.charts.triangle_chart;
  res.num_charts = lm.charts.num_charts;
  res.num_chart_variables = lm.charts.num_groups;
  res.boundary = std::move(lm.boundary);
  res.labels = std::move(lm.labels);
  res.mesh = std::move(lm.mesh);
  res.polycube = std::move(P);
  return res;
}

}  // namespace polycube::construct
