//! The whole construction chain (see construct.h).
#include "construct/construct.h"

#include "construct/labeling_check.h"
#include "construct/polycube_estimate.h"
#include "construct/turning_points.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/topology.h"
#include "quality/distortion.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>

namespace polycube::construct {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::string defects_text(const LabelingCheck& check, std::size_t max_listed = 5) {
  std::string s;
  for (std::size_t i = 0; i < check.defects.size() && i < max_listed; ++i)
    s += (i ? "; " : "") + check.defects[i].reason;
  if (check.defects.size() > max_listed) s += fmt::format("; and {} more", check.defects.size() - max_listed);
  return s;
}

//! Add `amount` to the data cost of the current label of every triangle within `rings` vertex
//! rings of the marked surface vertices. Returns the number of triangles penalized.
int penalize_around(const core::TriMesh& s, const std::vector<std::vector<int>>& vertex_tris,
                    const std::vector<int>& labels, std::vector<char> marked, int rings, double amount,
                    std::vector<std::array<double, 6>>& penalty) {
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<char> next = marked;
    for (std::size_t v = 0; v < marked.size(); ++v)
      if (marked[v])
        for (int f : vertex_tris[v])
          for (int w : s.cells[f]) next[w] = 1;
    marked.swap(next);
  }
  if (penalty.empty()) penalty.assign(s.cells.size(), {0, 0, 0, 0, 0, 0});
  int count = 0;
  for (std::size_t f = 0; f < s.cells.size(); ++f) {
    const auto& c = s.cells[f];
    if (!marked[c[0]] && !marked[c[1]] && !marked[c[2]]) continue;
    penalty[f][labels[f]] += amount;
    ++count;
  }
  return count;
}

//! A valid labeling steered by the fast polycube estimate: graph cut + repair, then while the
//! estimate folds some triangles, penalize their labels and label again (estimate_rounds
//! times at most). The valid labeling whose estimate folds the least area wins.
struct SteeredLabeling {
  RepairResult repair;
  PolycubeEstimate estimate;
  bool valid = false;
  int rounds = 0;
};

SteeredLabeling steered_labeling(const core::TriMesh& s, const std::vector<std::vector<int>>& vertex_tris,
                                 const std::vector<core::Vec3>& shape, LabelingOptions& lopt, const ConstructOptions& o,
                                 ConstructTimes& seconds) {
  auto& log = core::logger();
  SteeredLabeling best;
  for (int round = 0; round <= o.estimate_rounds; ++round) {
    auto t = Clock::now();
    const LabelingResult lab = graph_cut_labeling(s, lopt);
    seconds.label += since(t);
    t = Clock::now();
    RepairOptions ropt = o.repair;
    ropt.energy = lopt;
    RepairResult rep = repair_labeling(s, lab.labels, ropt);
    if (!rep.valid()) {
      seconds.repair += since(t);
      if (!best.valid) best.repair = std::move(rep);
      break;
    }
    if (o.unfold_moves > 0) {
      UnfoldResult un = unfold_labeling(s, rep.labels, o.unfold_moves);
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
    PolycubeEstimate est = estimate_polycube(s, rep.labels);
    seconds.repair += since(t);
    log.info("construct: labeling round {}: {} charts, the polycube estimate folds {} triangles ({:.3g}% of the area)",
             round, rep.check.layout.num_charts(), est.flipped.size(), 100.0 * est.flipped_area);
    const bool fewer = !best.valid || est.flipped_area < best.estimate.flipped_area;
    const bool done = est.flipped.empty();
    std::vector<char> marked(s.points.size(), 0);
    for (int f : est.flipped)
      for (int v : s.cells[f]) marked[v] = 1;
    const std::vector<int> labels = rep.labels;
    if (fewer) {
      best.repair = std::move(rep);
      best.estimate = std::move(est);
      best.valid = true;
      best.rounds = round;
    }
    if (done || round == o.estimate_rounds) break;
    penalize_around(s, vertex_tris, labels, std::move(marked), o.relabel_ring, o.relabel_penalty, lopt.penalty);
  }
  return best;
}

}  // namespace

ConstructResult construct_from_prepared(const core::TetMesh& input, const ConstructOptions& o) {
  auto& log = core::logger();
  const auto t0 = Clock::now();
  ConstructResult res;

  // Axis alignment: the labeling and the deformation work on the rotated model (the polycube's
  // axes are the rotated frame); the map's model positions are the input's.
  core::TetMesh mesh = input;
  if (o.align_axes) {
    res.axis_rotation = best_axis_rotation(core::boundary(input).surface);
    log.debug("construct: axis alignment: L1 energy of the normals {:.4f}, best rotation {:.4f}", res.axis_rotation.energy_before, res.axis_rotation.energy_best);
    if (!res.axis_rotation.rotation.isIdentity()) {
      for (core::Vec3& p : mesh.points) p = res.axis_rotation.rotation * p;
      log.info("construct: model rotated to the axes (normals' L1 energy {:.4f} -> {:.4f})",
               res.axis_rotation.energy_before, res.axis_rotation.energy_after);
    }
  }

  // Labeling, repair, deformation; when the map cannot be untangled, revisit the labeling with
  // other compactness weights (each attempt is a different valid labeling).
  const core::TetBoundary bnd = core::boundary(mesh);
  std::vector<core::Tri> tris(bnd.surface.cells.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const auto& s = bnd.surface.cells[f];
    tris[f] = {bnd.vertex_map[s[0]], bnd.vertex_map[s[1]], bnd.vertex_map[s[2]]};
  }
  // Attempts: the compactness schedule (1, then the retry factors); within each, relabelling
  // rounds that penalize the labels of the triangles around what could not be untangled.
  std::vector<double> factors{1.0};
  for (double f : o.retry_compactness_factors) factors.push_back(f);
  const int nv0 = mesh.num_points();
  std::vector<int> surface_of(static_cast<std::size_t>(nv0), -1);  // volume vertex -> surface vertex
  for (std::size_t i = 0; i < bnd.vertex_map.size(); ++i) surface_of[bnd.vertex_map[i]] = static_cast<int>(i);
  std::vector<std::vector<int>> vertex_tris(bnd.surface.points.size());
  for (std::size_t f = 0; f < bnd.surface.cells.size(); ++f)
    for (int v : bnd.surface.cells[f]) vertex_tris[v].push_back(static_cast<int>(f));
  DeformResult def;
  bool have_def = false;
  int def_failures = 0;  // inverted tets + wrong-facing triangles of the kept attempt
  std::string failures;
  bool done = false;
  int attempts = 0;
  // Passes: the options as given; then, when every attempt failed and no pre-deformation was
  // asked for, the same schedule again on a labeling of the pre-deformed normals with local
  // unfolding against the fast estimate (cup certifies only so). The shapes that certify in
  // the first pass get exactly the first pass's map.
  const int passes = o.predeform.iterations == 0 && o.predeform_retry > 0 ? 2 : 1;
  PredeformResult pre;
  bool timed_out = false;
  for (int pass = 0; pass < passes && !done && !timed_out && attempts < o.max_attempts; ++pass) {
    ConstructOptions po = o;
    if (pass == 1) {
      po.predeform.iterations = o.predeform_retry;
      po.unfold_moves = std::max(o.unfold_moves, o.predeform_retry_unfold_moves);
      log.info("construct: every attempt failed; again with a pre-deformation of {} iterations", o.predeform_retry);
    }
    // Pre-deformation: the fidelity term of the labeling reads the normals of the pre-deformed
    // surface (the compactness term keeps the model's, so chart boundaries stay smooth).
    std::vector<core::Vec3> data_normals;
    if (po.predeform.iterations > 0) {
      pre = predeform(mesh, tris, po.predeform);
      data_normals = triangle_normals(pre.points, tris);
      res.seconds.predeform += pre.seconds;
      log.info("construct: pre-deformation, {} iterations: misalignment {:.4f} -> {:.4f} ({} tets inverted), {:.2f} s",
               pre.iterations, pre.misalignment_before, pre.misalignment_after, pre.inverted, pre.seconds);
    }
    const std::vector<core::Vec3>* start = po.predeform.iterations > 0 ? &pre.points : nullptr;
    // The surface the chart boundaries are straightened on: the pre-deformed one when there is.
    std::vector<core::Vec3> shape = bnd.surface.points;
    if (start)
      for (std::size_t i = 0; i < shape.size(); ++i) shape[i] = pre.points[bnd.vertex_map[i]];
    for (std::size_t fi = 0; fi < factors.size() && !done && attempts < o.max_attempts; ++fi) {
      LabelingOptions lopt = o.labeling;
      lopt.compactness *= factors[fi];
      if (!data_normals.empty()) lopt.data_normals = data_normals;
      lopt.penalty.clear();
      for (int round = 0; round <= o.relabel_rounds && !done && attempts < o.max_attempts; ++round) {
        if (attempts > 0 && o.time_limit > 0 && since(t0) > o.time_limit) {
          failures += fmt::format("{}time limit of {:g} s reached after {} attempt(s)", failures.empty() ? "" : "; ",
                                  o.time_limit, attempts);
          fi = factors.size();
          timed_out = true;
          break;
        }
        ++attempts;
        const SteeredLabeling sl = steered_labeling(bnd.surface, vertex_tris, shape, lopt, po, res.seconds);
        const RepairResult& rep = sl.repair;
        res.repair_moves = rep.moves;
        const std::string what = fmt::format("{}compactness {:.3g}{}", pass == 1 ? "pre-deformed, " : "", lopt.compactness,
                                             round > 0 ? fmt::format(" relabel {}", round) : std::string());
        if (!sl.valid) {
          failures += fmt::format("{}{}: no valid labeling ({} defect(s): {})", failures.empty() ? "" : "; ", what,
                                  rep.check.defects.size(), defects_text(rep.check, 2));
          break;  // penalties only make it harder: go to the next compactness
        }
        log.info("construct: attempt {} ({}): labeling valid ({} charts, estimate folds {} triangles)", attempts, what,
                 rep.check.layout.num_charts(), sl.estimate.flipped.size());
        // Where the attempt failed (volume vertices of the original mesh); empty on success.
        std::vector<char> bad(bnd.surface.points.size(), 0);
        auto mark = [&](int v) {
          if (v >= 0 && v < nv0 && surface_of[v] >= 0) bad[surface_of[v]] = 1;
        };
        DeformResult cur;
        int cur_failures = 0;
        try {
          cur = deform_to_polycube(mesh, tris, rep.labels, o.deform, start);
        } catch (const UnrealizableLabeling& e) {
          failures += fmt::format("{}{}: {}", failures.empty() ? "" : "; ", what, e.what());
          log.info("construct: attempt {}: {}", attempts, e.what());
          for (int v : e.vertices()) mark(v);
        }
        const bool deformed = !cur.polycube.empty();
        if (deformed) {
          res.seconds.deform += cur.seconds_linear;
          res.seconds.untangle += cur.seconds_untangle;
          log.info("construct: deformation {:.2f} s ({} inverted after the linear step), untangling {:.2f} s "
                   "({} iterations, {} Newton steps, min det {:.3g}, {} inverted)",
                   cur.seconds_linear, cur.inverted_after_linear, cur.seconds_untangle, cur.untangle.iterations,
                   cur.untangle.newton_steps, cur.untangle.min_det, cur.untangle.inverted_after);
          // The tets and the boundary triangles that face away from their label in polycube
          // space (with every tet positive, such a triangle means the surface folds over itself).
          const auto& P = cur.polycube;
          int inverted = 0, wrong_facing = 0;
          for (const auto& c : cur.mesh.cells) {
            const double det = (P[c[1]] - P[c[0]]).dot((P[c[2]] - P[c[0]]).cross(P[c[3]] - P[c[0]]));
            if (det > 0) continue;
            ++inverted;
            for (int v : c) mark(v);
          }
          for (std::size_t f = 0; f < cur.boundary.size(); ++f) {
            const auto& b = cur.boundary[f];
            if (faces_label(P, b, cur.labels[f])) continue;
            ++wrong_facing;
            for (int v : b) mark(v);
          }
          cur_failures = inverted + wrong_facing + (cur.untangle.untangled ? 0 : 1);
          done = cur.untangle.untangled && wrong_facing == 0;
          if (!done)
            failures += fmt::format("{}{}: {} tets stay inverted, {} boundary triangles face away from their label",
                                    failures.empty() ? "" : "; ", what, cur.untangle.inverted_after, wrong_facing);
        }
        if (!done) {
          const int n = penalize_around(bnd.surface, vertex_tris, rep.labels, std::move(bad), o.relabel_ring,
                                        o.relabel_penalty, lopt.penalty);
          log.info("construct: relabelling: penalized the labels of {} triangles", n);
        }
        if (!deformed) continue;
        // Keep the attempt with the fewest inverted tets.
        if (!have_def || done || cur_failures < def_failures) {
          def = std::move(cur);
          def_failures = cur_failures;
          have_def = true;
        }
      }
    }
  }
  if (!have_def)
    throw core::SolverError("no valid polycube labeling reached: " + failures);
  if (!done) log.warn("construct: every attempt left inverted tets ({})", failures);
  res.split_triangles = def.split_triangles;
  res.split_edges = def.split_edges;
  res.refined_edges = def.refined_edges;
  res.boundary_first = def.boundary_first;
  res.inverted_after_linear = def.inverted_after_linear;
  res.untangle = def.untangle;
  res.predeform = std::move(pre);
  res.predeform.points.clear();

  // Certification.
  const auto t = Clock::now();
  res.map.tets = def.mesh.cells;
  res.map.model = def.mesh.points;
  if (!res.axis_rotation.rotation.isIdentity()) {
    const Eigen::Matrix3d back = res.axis_rotation.rotation.transpose();
    for (std::size_t v = 0; v < res.map.model.size(); ++v)
      res.map.model[v] = v < input.points.size() ? input.points[v] : core::Vec3(back * res.map.model[v]);
  }
  res.map.polycube = def.polycube;
  res.certificate = certify_polycube_map(res.map, def.boundary, def.labels, o.certify);
  if (!res.certificate.certified())
    throw NotCertified("polycube map not certified: " + res.certificate.reason() +
                           (failures.empty() ? std::string() : " (attempts: " + failures + ")"),
                       res.map, def.boundary, def.labels);

  // Boundary in core::boundary() order (the order of the written Triangles blocks).
  const core::TetBoundary fb = core::boundary(def.mesh);
  std::vector<std::pair<std::array<int, 3>, int>> keys(def.boundary.size());
  for (std::size_t i = 0; i < def.boundary.size(); ++i) {
    std::array<int, 3> k{def.boundary[i][0], def.boundary[i][1], def.boundary[i][2]};
    std::sort(k.begin(), k.end());
    keys[i] = {k, def.labels[i]};
  }
  std::sort(keys.begin(), keys.end());
  core::TriMesh surface;
  surface.points = def.mesh.points;  // the rotated frame, where the labels are axes
  for (const auto& s : fb.surface.cells) {
    const core::Tri tri{fb.vertex_map[s[0]], fb.vertex_map[s[1]], fb.vertex_map[s[2]]};
    std::array<int, 3> k{tri[0], tri[1], tri[2]};
    std::sort(k.begin(), k.end());
    const auto it = std::lower_bound(keys.begin(), keys.end(), std::make_pair(k, -1));
    PC_REQUIRE(it != keys.end() && it->first == k, "construct: certified boundary lost a triangle");
    res.boundary.push_back(tri);
    res.labels.push_back(it->second);
    surface.cells.push_back(tri);
  }
  const LabelingCheck check = check_labeling(surface, res.labels);
  res.charts = check.layout.num_charts();
  res.corners = static_cast<int>(check.layout.corners.size());
  res.boundaries = check.layout.num_boundaries;
  res.fidelity = labeling_fidelity(surface, res.labels);
  quality::DistortionOptions dopt;
  dopt.normalize_volume = true;
  dopt.keep_per_tet = false;
  const quality::MapDistortion dist = quality::map_distortion(def.mesh, def.polycube, dopt);
  res.isometric_average = dist.isometric.average;
  res.isometric_max = dist.isometric.max;
  res.conformal_average = dist.conformal.average;
  res.conformal_max = dist.conformal.max;
  res.seconds.certify = since(t);
  res.seconds.total = since(t0);
  return res;
}

ConstructResult construct_polycube(const core::TriMesh& surface, const ConstructOptions& o) {
  const auto t0 = Clock::now();
  TetrahedralizeResult tr = tetrahedralize(surface, o.tetrahedralize);
  if (o.tetrahedralize.max_volume == 0.0 && o.min_tets > 0 && tr.mesh.num_cells() < o.min_tets) {
    // Too coarse an interior leaves too little room to open a polycube corner where the
    // model's surface is nearly flat (3holes: stuck tets at 7188 tets, certified at ~13500):
    // bound the tet volume so that the volume alone asks for about min_tets tets.
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
  const double t_tet = since(t0);
  ConstructResult res = construct_from_prepared(tr.mesh, o);
  res.tetgen_tets = tr.tetgen_tets;
  res.refine = tr.refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

ConstructResult construct_polycube(core::TetMesh mesh, const ConstructOptions& o) {
  const auto t0 = Clock::now();
  prepare_tet_mesh(mesh);
  const RefineStats refine = refine_boundary(mesh);
  const double t_tet = since(t0);
  ConstructResult res = construct_from_prepared(mesh, o);
  res.refine = refine;
  res.seconds.tetrahedralize = t_tet;
  res.seconds.total += t_tet;
  return res;
}

}  // namespace polycube::construct
