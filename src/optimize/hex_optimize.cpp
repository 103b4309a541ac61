//! Hex-mesh untangling and quality improvement with surface and feature attraction (see
//! hex_optimize.h). The energy and Newton solver are solve::untangle's.
#include "optimize/hex_optimize.h"

#include "core/elements.h"
#include "core/errors.h"
#include "core/log.h"
#include "core/progress.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "optimize/boundary_lift.h"
#include "optimize/centre_frames.h"
#include "optimize/face_attraction.h"
#include "optimize/features.h"
#include "optimize/foldover_check.h"
#include "optimize/vertex_roles.h"
#include "quality/surface_distance.h"
#include "solve/untangle.h"

#include <tbb/parallel_for.h>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace polycube::optimize {

namespace {

using core::Vec3;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

//! Mean edge length of each hex (the scale of its ideal-cube reference).
std::vector<double> hex_sizes(const core::HexMesh& m) {
  std::vector<double> h(m.cells.size());
  double total = 0;
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    double len = 0;
    for (const auto& e : core::kHexEdges)
      len += (m.points[m.cells[c][e[0]]] - m.points[m.cells[c][e[1]]]).norm();
    h[c] = len / 12.0;
    total += h[c];
  }
  const double mean = total / std::max<std::size_t>(1, h.size());
  if (!(mean > 0) || !std::isfinite(mean))
    throw core::InputError("hex mesh: every hex is degenerate");
  for (double& x : h)
    if (!(x > 1e-6 * mean)) x = mean;  // collapsed hex: use the mean size
  return h;
}

//! The 8 corner tets of every hex. The reference of a corner is the right-angled box corner
//! with the input corner's three edge lengths (an ideal cube corner for a cubic hex): J = I
//! exactly when the corner is orthogonal with its input edge lengths, so the energy raises the
//! scaled Jacobian without fighting a mesh's grading or anisotropy.
//! \param lengths #H*8 by 3 input edge lengths of each corner (zero ones replaced by the hex size)
//! \param multiplier #H weight factors
solve::TetElements corner_elements(const core::HexMesh& m,
                                   const std::vector<std::array<double, 3>>& lengths,
                                   const std::vector<double>& multiplier) {
  solve::TetElements el;
  const std::size_t n = m.cells.size() * 8;
  el.tets.reserve(n);
  el.gradients.reserve(n);
  el.weights.reserve(n);
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    const auto& h = m.cells[c];
    for (int i = 0; i < 8; ++i) {
      const auto& nb = core::kHexCornerNeighbors[i];
      const auto& l = lengths[8 * c + i];
      Eigen::Matrix<double, 4, 3> G = Eigen::Matrix<double, 4, 3>::Zero();
      for (int d = 0; d < 3; ++d) {
        G(d + 1, d) = 1.0 / l[d];
        G(0, d) = -1.0 / l[d];
      }
      el.tets.push_back({h[i], h[nb[0]], h[nb[1]], h[nb[2]]});
      el.gradients.push_back(G);
      el.weights.push_back(multiplier[c] * l[0] * l[1] * l[2] / 6.0);
    }
  }
  return el;
}

//! Per-hex factor (L / size)^uniformity of the reference lengths, with L such that
//! sum (L^u size^(1-u))^3 = sum size^3 (the total reference volume stays the input's).
std::vector<double> reference_scale(const std::vector<double>& size, double uniformity) {
  std::vector<double> scale(size.size(), 1.0);
  if (uniformity > 0) {
    double volume = 0, blended = 0;
    for (double h : size) {
      volume += h * h * h;
      blended += std::pow(h, 3.0 * (1.0 - uniformity));
    }
    const double L = std::pow(volume / blended, 1.0 / (3.0 * uniformity));
    for (std::size_t c = 0; c < size.size(); ++c) scale[c] = std::pow(L / size[c], uniformity);
  }
  return scale;
}

//! Reference edge lengths of every hex corner (8 per hex, in kHexCornerNeighbors order): the
//! input's, times the hex's reference scale.
std::vector<std::array<double, 3>> corner_lengths(const core::HexMesh& m,
                                                  const std::vector<double>& size,
                                                  const std::vector<double>& scale) {
  std::vector<std::array<double, 3>> out(m.cells.size() * 8);
  for (std::size_t c = 0; c < m.cells.size(); ++c)
    for (int i = 0; i < 8; ++i)
      for (int d = 0; d < 3; ++d) {
        const double l =
            (m.points[m.cells[c][core::kHexCornerNeighbors[i][d]]] - m.points[m.cells[c][i]])
                .norm();
        out[8 * c + i][d] =
            scale[c] * (l > 0.05 * size[c] ? l : size[c]);  // collapsed edge: the hex size
      }
  return out;
}

//! Corner and centre Jacobians of a hex that are not positive (the centre as Verdict's).
int inverted_jacobians(const core::HexMesh& m, const core::Hex& h) {
  int n = !(centre_value(m, h) > 0);
  for (int i = 0; i < 8; ++i) {
    const auto& nb = core::kHexCornerNeighbors[i];
    const Vec3& p = m.points[h[i]];
    n +=
        !((m.points[h[nb[0]]] - p).dot((m.points[h[nb[1]]] - p).cross(m.points[h[nb[2]]] - p)) > 0);
  }
  return n;
}

int inverted_jacobians(const core::HexMesh& m) {
  int n = 0;
  for (const auto& h : m.cells) n += inverted_jacobians(m, h);
  return n;
}

quality::ScaledJacobianSummary summary(const core::HexMesh& m, bool keep_values) {
  quality::ScaledJacobianOptions o;
  o.keep_values = keep_values;
  return quality::scaled_jacobian(m, o);
}

//! The optimization problem: reduction (corners fixed), attractions, re-projection.
struct Problem {
  const TargetSurface* target = nullptr;
  VertexRoles roles;
  solve::LinearReduction reduction;
  std::vector<solve::Attraction> attractions;
  std::vector<double>
      stiffness;  //!< per attraction: weight factor, raised where the vertex drifted
  std::vector<double>
      vertex_weight;  //!< #V attraction weight of a boundary vertex before stiffening
  std::vector<std::array<int, 4>> quads;  //!< the boundary quads (outward)

  //! Move every attraction target to the closest point of its surface or feature lines.
  //! Put every attracted vertex exactly on its target, except where that would invert a
  //! corner that was not inverted before or bring a hex's scaled Jacobian below `floor`
  //! (the vertices of such hexes keep their position).
  void snap(core::HexMesh& mesh, double floor) const {
    std::vector<solve::Attraction> attr = attractions;
    project(solve::flatten(mesh.points), attr);
    const std::vector<Vec3> old = mesh.points;
    std::vector<int> bad_before(mesh.cells.size());
    for (std::size_t c = 0; c < mesh.cells.size(); ++c)
      bad_before[c] = inverted_jacobians(mesh, mesh.cells[c]);
    std::vector<char> moved(mesh.points.size(), 0);
    for (const auto& a : attr) {
      mesh.points[a.vertex] = a.target;
      moved[a.vertex] = 1;
    }
    // Revert the moves around hexes that got worse, until none does (each pass reverts some).
    for (int pass = 0; pass < 20; ++pass) {
      bool changed = false;
      for (std::size_t c = 0; c < mesh.cells.size(); ++c) {
        const auto& h = mesh.cells[c];
        if (inverted_jacobians(mesh, h) <= bad_before[c]) {
          std::array<Vec3, 8> p;
          bool touched = false;
          for (int i = 0; i < 8; ++i) {
            p[i] = mesh.points[h[i]];
            touched = touched || moved[h[i]];
          }
          if (!touched || bad_before[c] > 0 || quality::hex_scaled_jacobian(p).value >= floor)
            continue;
        }
        for (int v : mesh.cells[c])
          if (moved[v]) {
            mesh.points[v] = old[v];
            moved[v] = 0;
            changed = true;
          }
      }
      if (!changed) break;
    }
  }

  //! Attraction weights: surface_weight * (reference volume around v) / h_v², times each
  //! attraction's stiffness (1 unless the vertex drifted off the target, see below).
  void set_weights(const core::HexMesh& mesh, const std::vector<double>& size,
                   double surface_weight) {
    std::vector<double> volume(mesh.points.size(), 0.0);
    for (std::size_t c = 0; c < mesh.cells.size(); ++c)
      for (int v : mesh.cells[c]) volume[v] += size[c] * size[c] * size[c];
    stiffness.resize(attractions.size(), 1.0);
    vertex_weight.assign(mesh.points.size(), 0.0);
    for (std::size_t v = 0; v < mesh.points.size(); ++v) {
      const double h = roles.edge_length[v] > 0 ? roles.edge_length[v] : 1.0;
      vertex_weight[v] = surface_weight * volume[v] / (h * h);
    }
    for (std::size_t k = 0; k < attractions.size(); ++k)
      attractions[k].weight = stiffness[k] * vertex_weight[attractions[k].vertex];
  }

  //! Distance of every attracted vertex to its target (the closest point now).
  [[nodiscard]] std::vector<double> drift_distances(const core::HexMesh& mesh) const {
    std::vector<solve::Attraction> attr = attractions;
    project(solve::flatten(mesh.points), attr);
    std::vector<double> d(attr.size());
    for (std::size_t k = 0; k < attr.size(); ++k)
      d[k] = (mesh.points[attr[k].vertex] - attr[k].target).norm();
    return d;
  }

  //! Area-weighted normals (not unit) of the boundary quads and, summed, of their vertices (#V),
  //! at the points `point(v)` gives.
  template <class Point>
  void boundary_normals(const Point& point, std::vector<Vec3>& quad_normal, std::vector<Vec3>& vertex_normal) const {
    quad_normal.assign(quads.size(), Vec3::Zero());
    vertex_normal.assign(roles.role.size(), Vec3::Zero());
    for (std::size_t f = 0; f < quads.size(); ++f) {
      const auto& q = quads[f];
      quad_normal[f] = (point(q[2]) - point(q[0])).cross(point(q[3]) - point(q[1]));
      for (int v : q) vertex_normal[v] += quad_normal[f];
    }
  }

  //! Where boundary vertex v at p belongs on the target: the closest point of the feature lines
  //! (feature vertices) or of the surface triangles facing `normal`'s way (the others).
  [[nodiscard]] Vec3 vertex_target(int v, const Vec3& p, const Vec3& normal) const {
    if (roles.role[v] == VertexRole::Feature) return target->closest_feature_point(p);
    return target->closest_point_facing(p, normal, roles.edge_length[v]).first;
  }

  //! Move every attraction target to the closest point of the feature lines (feature vertices)
  //! or of the surface triangles facing the way the hex boundary faces there (the others): see
  //! TargetSurface::closest_point_facing. Attractions beyond the mesh's vertices are the centres
  //! of `quads` from point `centre_base` on (face_attraction.h).
  void project(const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr, int centre_base = -1) const {
    const auto point = [&x](int v) -> Vec3 { return x.segment<3>(3 * static_cast<Eigen::Index>(v)); };
    std::vector<Vec3> quad_normal, vertex_normal;
    boundary_normals(point, quad_normal, vertex_normal);
    tbb::parallel_for(std::size_t{0}, attr.size(), [&](std::size_t k) {
      const Vec3 p = point(attr[k].vertex);
      const auto v = static_cast<std::size_t>(attr[k].vertex);
      if (v < roles.role.size()) {
        attr[k].target = vertex_target(attr[k].vertex, p, vertex_normal[v]);
        return;
      }
      const auto& q = quads[v - static_cast<std::size_t>(centre_base)];
      double h = 0;
      for (int c : q) h += 0.25 * roles.edge_length[c];
      attr[k].target = target->closest_point_facing(p, quad_normal[v - static_cast<std::size_t>(centre_base)], h).first;
    });
  }
};

Problem make_problem(core::HexMesh& mesh, const TargetSurface& target,
                     const std::vector<double>& size, const OptimizeOptions& o) {
  Problem pb;
  pb.target = &target;
  pb.roles = classify_vertices(mesh, target, o.feature_angle, o.feature_distance);
  pb.quads = boundary_quads(mesh);
  const int nv = mesh.num_points();
  // Corners take their target positions now and stay there.
  for (int v = 0; v < nv; ++v)
    if (pb.roles.role[v] == VertexRole::Corner)
      mesh.points[v] = target.corner_position(pb.roles.corner[v]);
  std::vector<int> var(3 * static_cast<std::size_t>(nv), -1);
  int nvar = 0;
  for (int v = 0; v < nv; ++v)
    if (pb.roles.role[v] != VertexRole::Corner)
      for (int d = 0; d < 3; ++d) var[3 * v + d] = nvar++;
  pb.reduction = solve::index_reduction(var, nvar, solve::flatten(mesh.points));
  for (int v = 0; v < nv; ++v) {
    const VertexRole r = pb.roles.role[v];
    if (r == VertexRole::Surface || r == VertexRole::Feature)
      pb.attractions.push_back({v, mesh.points[v], 0.0});
  }
  pb.set_weights(mesh, size, o.surface_weight);
  pb.project(solve::flatten(mesh.points), pb.attractions);
  return pb;
}

//! y of the reduction (an index reduction: each variable is one coordinate, coefficient 1) for
//! the current points.
Eigen::VectorXd variables_of(const Problem& pb, const core::HexMesh& mesh) {
  const auto& B = pb.reduction.B;
  Eigen::VectorXd y(pb.reduction.num_variables());
  for (int r = 0; r < B.rows(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(B, r); it; ++it)
      y[it.col()] = mesh.points[r / 3][r % 3];
  return y;
}

//! What every optimization of the mesh shares: the problem and the references of the corners
//! and centres.
struct Optimization {
  core::HexMesh& mesh;
  const core::TriMesh& target_mesh;
  Problem& pb;
  const std::vector<double>& size;  //!< #H input mean edge length of each hex
  const std::vector<std::array<double, 3>>&
      lengths;  //!< #H*8 by 3 reference edge lengths of the corners
  const std::vector<std::array<double, 3>>&
      centre;  //!< #H by 3 reference lengths of the centre tets
  //! #H weight factors of the hexes: 1 while untangling, raised on the worst hexes by the
  //! quality rounds (the retries keep the last round's).
  std::vector<double> multiplier;
  const OptimizeOptions& o;
  //! The Newton system's pattern, shared by the runs on the same elements (solve/untangle.h).
  std::shared_ptr<solve::PatternCache> pattern = solve::make_pattern_cache();
  //! Only a region of the mesh moves (local_problem): the elements that cannot move are dropped.
  bool local = false;

  [[nodiscard]] solve::TetElements elements() const {
    return corner_elements(mesh, lengths, multiplier);
  }
  //! The last boundary distance measured, with the points it was measured for.
  quality::RememberedDistance distances{};

  //! The boundary's Hausdorff distance to the target, relative to its bounding-box diagonal.
  [[nodiscard]] double hausdorff() { return distances.measure(mesh, target_mesh).relative; }
};

//! Drop the elements none of whose points moves with the reduction's variables: constants of the
//! energy, and a local untangling's cost is then that of its region only.
void drop_fixed_elements(const solve::LinearReduction& reduction, solve::TetElements& el) {
  const auto moves = [&](int p) {
    for (int d = 0; d < 3; ++d)
      if (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator(reduction.B, 3 * p + d)) return true;
    return false;
  };
  solve::TetElements kept;
  for (int t = 0; t < el.size(); ++t) {
    if (std::none_of(el.tets[t].begin(), el.tets[t].end(), moves)) continue;
    kept.tets.push_back(el.tets[t]);
    kept.gradients.push_back(el.gradients[t]);
    kept.weights.push_back(el.weights[t]);
  }
  el = std::move(kept);
}

//! Optimize the mesh's points from their current positions. With o.boundary_barrier > 0 the
//! boundary quad corners are lifted (boundary_lift.h): all of them while untangling, only those
//! facing the target's side now during quality rounds (so the barrier never turns an
//! optimization into an untangling).
solve::UntangleResult run(const Optimization& w, solve::UntangleOptions uo, bool untangling,
                          double face_weight) {
  const Problem& pb = w.pb;
  const OptimizeOptions& o = w.o;
  core::HexMesh& mesh = w.mesh;
  solve::TetElements el = w.elements();
  solve::LinearReduction reduction = pb.reduction;
  if (o.boundary_barrier > 0) {
    const BoundaryLift lift =
        lift_boundary(mesh, *pb.target, pb.roles.edge_length, o.boundary_barrier, !untangling);
    append(el, lift.elements);
    reduction = with_apexes(reduction, lift);
  }
  uo.attractions = pb.attractions;
  int centre_base = -1;
  if (face_weight > 0) {
    const std::vector<std::array<int, 4>>& quads = pb.quads;
    const int base = reduction.num_points();
    centre_base = base;
    reduction = with_quad_centres(reduction, quads);
    std::vector<solve::Attraction> centres(quads.size());
    for (std::size_t k = 0; k < quads.size(); ++k) {
      centres[k].vertex = base + static_cast<int>(k);
      double weight = 0;
      for (int v : quads[k]) weight += 0.25 * pb.vertex_weight[v];
      centres[k].weight = face_weight * weight;
    }
    pb.project(reduction.apply(variables_of(pb, mesh)), centres, base);
    uo.attractions.insert(uo.attractions.end(), centres.begin(), centres.end());
  }
  // Last, so that the apexes and quad centres keep the point numbers their elements use.
  reduction = with_centre_tets(reduction, mesh, w.centre, w.multiplier, o.centre_weight, el);
  if (pb.reduction.num_variables() > o.cholesky_max_variables) {
    uo.linear_solver = solve::NewtonSolver::ConjugateGradient;
    uo.cg_iterations = o.cg_iterations;
  }
  if (w.local) drop_fixed_elements(reduction, el);
  uo.pattern_cache = w.pattern;
  uo.on_iteration = [&pb, centre_base](int, const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr) {
    pb.project(x, attr, centre_base);
    return true;
  };
  Eigen::VectorXd y = variables_of(pb, mesh);
  const solve::UntangleResult r = solve::untangle(el, reduction, y, uo);
  std::vector<Vec3> points = solve::unflatten(reduction.apply(y));
  points.resize(mesh.points.size());  // drop the derived points
  mesh.points = std::move(points);
  return r;
}

void add(PhaseReport& p, const solve::UntangleResult& r) {
  p.iterations += r.iterations;
  p.newton_steps += r.newton_steps;
}

// --- the steps of optimize_hex_mesh -----------------------------------------------------------

void check_input(const core::HexMesh& mesh, const OptimizeOptions& o) {
  if (mesh.cells.empty()) throw core::InputError("hex mesh: no hexahedra");
  if (!(o.surface_weight >= 0) || o.untangle_iterations < 0 ||
      !(o.untangle_min_sigma > 0 && o.untangle_min_sigma < 1) || o.quality_rounds < 0 || o.quality_patience < 0 ||
      o.quality_iterations < 1 || !(o.volume_weight > 0) ||
      !(o.feature_angle > 0 && o.feature_angle < 180) || !(o.feature_distance > 0) ||
      !(o.drift_diagonal > 0) || !(o.hausdorff_bound > 0) || o.drift_retries < 0 ||
      !(o.size_uniformity >= 0 && o.size_uniformity <= 1) || !(o.face_attraction >= 0) ||
      !(o.fit_retry >= 0) || !(o.fit_first_margin >= 0) || !(o.centre_weight >= 0))
    throw core::InputError("optimize: option out of range");
  core::check_indices(mesh);
  for (const Vec3& p : mesh.points)
    if (!p.allFinite()) throw core::InputError("hex mesh: non-finite coordinate");
}

//! The vertices of the hexes within `rings` rings of the hexes with an inverted corner or
//! centre (a ring: every hex sharing a vertex with the last).
std::vector<char> near_inverted(const core::HexMesh& m, int rings) {
  std::vector<char> in(m.points.size(), 0);
  for (const core::Hex& h : m.cells)
    if (inverted_jacobians(m, h) > 0)
      for (int v : h) in[v] = 1;
  for (int ring = 0; ring < rings; ++ring) {
    const std::vector<char> last = in;
    for (const core::Hex& h : m.cells)
      if (std::any_of(h.begin(), h.end(), [&](int v) { return last[v] != 0; }))
        for (int v : h) in[v] = 1;
  }
  return in;
}

//! The problem with only the vertices in `free` (corners excepted) as variables, the others
//! fixed where they are, and their attractions dropped.
Problem local_problem(const Problem& pb, const core::HexMesh& m, const std::vector<char>& free) {
  Problem local = pb;
  std::vector<int> var(3 * m.points.size(), -1);
  int n = 0;
  for (int v = 0; v < m.num_points(); ++v)
    if (free[v] && pb.roles.role[v] != VertexRole::Corner)
      for (int d = 0; d < 3; ++d) var[3 * v + d] = n++;
  local.reduction = solve::index_reduction(var, n, solve::flatten(m.points));
  local.attractions.clear();
  local.stiffness.clear();
  for (std::size_t k = 0; k < pb.attractions.size(); ++k)
    if (free[pb.attractions[k].vertex]) {
      local.attractions.push_back(pb.attractions[k]);
      local.stiffness.push_back(pb.stiffness[k]);
    }
  return local;
}

//! The untangling's options (phase 1).
solve::UntangleOptions untangle_options(const OptimizeOptions& o) {
  solve::UntangleOptions uo;
  uo.max_iterations = o.untangle_iterations;
  uo.newton_steps = 2;
  uo.volume_weight = o.volume_weight;
  uo.initial_epsilon = 1.0;
  uo.stop_when_untangled = true;
  uo.stall_iterations = 30;
  uo.min_sigma = o.untangle_min_sigma;
  return uo;
}

//! Phase 1's local try (OptimizeOptions::local_untangle_rings): true when it left nothing
//! inverted.
bool untangle_locally(const Optimization& w, PhaseReport& report) {
  const std::vector<char> free = near_inverted(w.mesh, w.o.local_untangle_rings);
  Problem local = local_problem(w.pb, w.mesh, free);
  Optimization lw{w.mesh, w.target_mesh, local, w.size, w.lengths, w.centre, w.multiplier, w.o};
  lw.local = true;
  const solve::UntangleResult r = run(lw, untangle_options(w.o), true, w.o.face_attraction);
  add(report, r);
  const int left = inverted_jacobians(w.mesh);
  core::logger().info(
      "optimize: local untangling ({} of {} vertices free) {} iterations, {} -> {} inverted elements{}",
      std::count(free.begin(), free.end(), 1), w.mesh.num_points(), r.iterations, r.inverted_before,
      r.inverted_after, left > 0 ? "; now the whole mesh" : "");
  return left == 0;
}

//! Phase 1: untangle (corners fixed at the target may have folded elements too).
void untangle_phase(const Optimization& w, PhaseReport& report) {
  if (inverted_jacobians(w.mesh) > 0 && w.o.untangle_iterations > 0) {
    if (w.o.local_untangle_rings > 0 && untangle_locally(w, report)) return;
    const solve::UntangleResult r = run(w, untangle_options(w.o), true, w.o.face_attraction);
    add(report, r);
    core::logger().info(
        "optimize: untangling {} iterations, {} -> {} inverted elements (corners, centres, "
        "boundary lifts)",
        r.iterations, r.inverted_before, r.inverted_after);
  }
}

//! Options of a quality optimization (barrier kept: valid meshes start with a tiny ε; the
//! initial ε only matters while tangled).
solve::UntangleOptions quality_options(const OptimizeOptions& o, int iterations) {
  solve::UntangleOptions uo;
  uo.max_iterations = iterations;
  uo.newton_steps = 1;
  uo.volume_weight = o.volume_weight;
  uo.initial_epsilon = 1.0;
  uo.tolerance = 1e-4;
  uo.stall_iterations = 0;
  return uo;
}

//! Where the quality phase starts.
struct Start {
  std::vector<Vec3> points;
  int inverted = 0;      //!< corner and centre Jacobians <= 0
  double average = 0.0;  //!< a round may not lower the average scaled Jacobian below this
  //! The start is valid and its boundary does not cross itself: no state whose boundary crosses
  //! itself is kept (crosses_where_start_does_not).
  bool uncrossed = false;
};

bool boundary_crosses(const core::HexMesh& mesh) {
  return check_foldover(mesh, {1}).boundary_self_intersections > 0;
}

//! Whether the mesh's boundary crosses itself where the valid start's does not. Such a state would
//! fail the fold-over check at the end, and every later round starts from the kept state: keeping
//! it threw the whole optimization away (`run` optimized again from scratch with another
//! schedule), where the last state kept before it was valid.
bool crosses_where_start_does_not(const core::HexMesh& mesh, const Start& start) {
  return start.uncrossed && boundary_crosses(mesh);
}

//! The best state of the quality phase so far.
struct Best {
  quality::ScaledJacobianSummary summary;  //!< with the per-hex values
  int inverted = 0;                        //!< corner and centre Jacobians <= 0
  std::vector<Vec3> points;
};

Best best_of(const core::HexMesh& mesh) {
  return {summary(mesh, true), inverted_jacobians(mesh), mesh.points};
}

//! Heavier weights on the worst hexes (those within 0.1 of the minimum, at least 1%), so that
//! the next round raises the minimum.
void weigh_worst_hexes(const quality::ScaledJacobianSummary& best,
                       std::vector<double>& multiplier) {
  std::vector<double> sorted = best.values;
  const std::size_t k = std::min(sorted.size() - 1, sorted.size() / 100);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(k), sorted.end());
  const double tau = std::max(sorted[k], best.min + 0.1);
  for (std::size_t c = 0; c < multiplier.size(); ++c)
    if (best.values[c] < tau) multiplier[c] *= 4.0;
}

//! The quality rounds from the best points (multipliers from 1), keeping the best state.
//! One step of `progress` per round, when given.
void quality_rounds(Optimization& w, const Start& start, double face_weight, Best& best,
                    OptimizeResult& res, core::ProgressTask* progress, std::vector<Best>* earlier = nullptr) {
  std::fill(w.multiplier.begin(), w.multiplier.end(), 1.0);
  // How many rounds in a row were neither kept nor higher in mSJ than the round before them. A
  // round not kept but higher may lead to one that is (the worst hexes weigh more each round).
  // Round 0 never counts: it has no round before it, only the start, and no heavier weights
  // yet (a graded grid's round 0 falls below the start and the next rounds climb to a kept one:
  // HexOptimize.SizeUniformityEvensOutAGradedMesh).
  int stalled = 0;
  double previous_min = best.summary.min;
  for (int round = 0; round < w.o.quality_rounds; ++round) {
    if (w.o.quality_patience > 0 && stalled >= w.o.quality_patience) {
      core::logger().info("optimize: quality rounds stop: {} rounds in a row neither kept nor higher", stalled);
      if (progress)
        for (int rest = round; rest < w.o.quality_rounds; ++rest) progress->step();
      break;
    }
    ++res.rounds_run;
    if (round > 0) weigh_worst_hexes(best.summary, w.multiplier);
    const solve::UntangleOptions uo = quality_options(w.o, w.o.quality_iterations);
    w.mesh.points = best.points;
    const solve::UntangleResult r = run(w, uo, false, face_weight);
    add(res.quality, r);
    const quality::ScaledJacobianSummary s = summary(w.mesh, true);
    const int inv = inverted_jacobians(w.mesh);
    bool better =
        inv < best.inverted || (inv == best.inverted && inv > 0 && s.min > best.summary.min) ||
        (inv == 0 && best.inverted == 0 && s.min > best.summary.min && s.average >= start.average);
    const bool crosses = better && inv == 0 && crosses_where_start_does_not(w.mesh, start);
    better = better && !crosses;
    core::logger().info(
        "optimize: quality round {}: {} iterations, mSJ {:.4f} aSJ {:.4f} inverted Jacobians {}{}",
        round, r.iterations, s.min, s.average, inv,
        crosses ? " (not kept: its boundary crosses itself)" : better ? "" : " (not kept)");
    if (better) {
      if (earlier) earlier->push_back(best);
      best.summary = s;
      best.inverted = inv;
      best.points = w.mesh.points;
      ++res.rounds_accepted;
    }
    stalled = better || round == 0 || s.min > previous_min ? 0 : stalled + 1;
    previous_min = s.min;
    if (progress) progress->step();
  }
  w.mesh.points = best.points;
}

//! Drift retries. The heavier weights of the worst hexes may have pulled some of their boundary
//! vertices off the target, where the snap cannot put them back without lowering the minimum
//! (e.g. a vertex of the worst hex at a concave polycube corner on a curved part of the surface,
//! a fraction of an edge length off). When that takes the boundary beyond the Hausdorff bound,
//! stiffen the attraction of the drifted vertices only and optimize again from the state before
//! the rounds: the surface is a constraint, the minimum scaled Jacobian the objective. A retry is
//! kept only when it lowers the Hausdorff distance. Returns the Hausdorff distance of the result
//! (0 when not measured).
double drift_retries(Optimization& w, const Start& start, Best& best, OptimizeResult& res) {
  const OptimizeOptions& o = w.o;
  core::HexMesh& mesh = w.mesh;
  const double diagonal = core::bounding_box(w.target_mesh.points).extent().norm();
  best.points = mesh.points;
  double best_hausdorff = o.drift_retries > 0 && res.inverted_before == 0 ? w.hausdorff() : 0.0;
  for (int retry = 0; retry < o.drift_retries && res.inverted_before == 0; ++retry) {
    if (best_hausdorff <= o.hausdorff_bound) break;
    const std::vector<double> drift = w.pb.drift_distances(mesh);
    std::vector<std::size_t> off;
    for (std::size_t k = 0; k < drift.size(); ++k)
      if (drift[k] > o.drift_diagonal * diagonal) off.push_back(k);
    if (off.empty()) break;
    for (std::size_t k : off) w.pb.stiffness[k] *= 16.0;
    w.pb.set_weights(mesh, w.size, o.surface_weight);
    mesh.points = start.points;
    const solve::UntangleOptions uo =
        quality_options(o, o.quality_iterations * std::max(1, o.quality_rounds));
    const solve::UntangleResult r = run(w, uo, false, o.face_attraction);
    add(res.quality, r);
    if (inverted_jacobians(mesh) > 0 || crosses_where_start_does_not(mesh, start)) {  // never trade validity for the surface
      mesh.points = best.points;
      break;
    }
    const quality::ScaledJacobianSummary s = summary(mesh, true);
    if (o.face_attraction <= 0) w.pb.snap(mesh, s.min);
    const double h = w.hausdorff();
    if (!(h < best_hausdorff)) {
      core::logger().info(
          "optimize: stiffer attraction on {} drifted vertices did not lower the Hausdorff "
          "distance "
          "({:.3f} %); not kept",
          off.size(), 100 * h);
      mesh.points = best.points;
      break;
    }
    core::logger().info(
        "optimize: Hausdorff {:.3f} % above the bound; {} drifted boundary vertices stiffened: "
        "{:.3f} %, mSJ {:.4f}",
        100 * best_hausdorff, off.size(), 100 * h, s.min);
    best.summary = s;
    best_hausdorff = h;
    best.points = mesh.points;
    ++res.drift_retries;
  }
  return best_hausdorff;
}

//! The boundary's Hausdorff distance with every attracted vertex at its closest target point: a
//! lower bound, in practice, of what the rounds' final snap reaches, since the rounds slide the
//! vertices along the surface but do not shorten the quads' chords. Beyond the bound, the
//! distance is in the chords (quads too long for the curvature, or straddling a sharp edge the
//! hex mesh has no edge for), which only the fit with the quad centres attracted removes.
double snapped_hausdorff(const Optimization& w) {
  core::HexMesh snapped = w.mesh;
  std::vector<solve::Attraction> attr = w.pb.attractions;
  w.pb.project(solve::flatten(snapped.points), attr);
  for (const auto& a : attr) snapped.points[a.vertex] = a.target;
  return quality::hausdorff_distance(snapped, w.target_mesh).relative;
}

//! When the rounds should attract the quad centres from the start, the Hausdorff distance of the
//! start's boundary put on the target (else 0): the fit retry would run anyway (a valid start
//! beyond the bound by the margin), and the plain rounds before it would be thrown away.
double fit_from_start(const Optimization& w, const Start& start) {
  const OptimizeOptions& o = w.o;
  if (!(o.fit_retry > 0 && o.face_attraction <= 0 && o.fit_first_margin > 0 && start.inverted == 0)) return 0;
  const double h = snapped_hausdorff(w);
  const bool fit = h > o.fit_first_margin * o.hausdorff_bound;
  core::logger().info("optimize: boundary on the target: Hausdorff {:.3f} %{}", 100 * h,
                      fit ? "; the rounds attract the quad centres from the start" : "");
  return fit ? h : 0;
}

//! Fit retry: still beyond the bound with the boundary vertices on the target, the distance is
//! the chords of quads too long for the surface's curvature or straddling a sharp edge the hex
//! mesh has no edge for. Run the rounds again from their start with the quad centres attracted
//! too (face_attraction.h): the boundary then fits the surface instead of interpolating it.
//! Kept only when it lowers the Hausdorff distance (best_hausdorff, 0 when not measured yet).
void fit_retry(Optimization& w, const Start& start, double best_hausdorff, Best& best,
               OptimizeResult& res) {
  const OptimizeOptions& o = w.o;
  core::HexMesh& mesh = w.mesh;
  if (!(o.fit_retry > 0 && o.face_attraction <= 0 && start.inverted == 0 &&
        inverted_jacobians(mesh) == 0))
    return;
  if (best_hausdorff <= 0) best_hausdorff = w.hausdorff();
  if (best_hausdorff <= o.hausdorff_bound) return;
  const Best kept{best.summary, best.inverted, mesh.points};
  mesh.points = start.points;
  best = best_of(mesh);
  quality_rounds(w, start, o.fit_retry, best, res, nullptr);
  const double h = w.hausdorff();
  if (best.inverted == 0 && h < best_hausdorff) {
    core::logger().info(
        "optimize: Hausdorff {:.3f} % above the bound; quad centres attracted too: {:.3f} %, "
        "mSJ {:.4f}",
        100 * best_hausdorff, 100 * h, best.summary.min);
    res.fit_retry = true;
  } else {
    core::logger().info(
        "optimize: attracting the quad centres did not lower the Hausdorff distance ({:.3f} %); "
        "not kept",
        100 * h);
    mesh.points = kept.points;
    best = kept;
  }
}

//! When the best round's boundary, put on the target, is beyond the Hausdorff bound: the last
//! round kept before it whose boundary is within the bound, put on the target the same way (the
//! rounds are kept in rising mSJ, so its mSJ is the highest within the bound they reached;
//! `earlier`: the best state before each kept round, in order). The heavier weights of a later
//! round can pull the worst hexes' boundary vertices off the target farther than the snap can put
//! back; the retries that follow (drift, fit) start over from the rounds' start and keep their own
//! result, which can be lower in mSJ than that round (prefer_within_bound).
std::optional<Best> last_round_within_bound(Optimization& w, const std::vector<Best>& earlier) {
  if (w.o.hausdorff_bound <= 0 || earlier.size() < 2 || w.hausdorff() <= w.o.hausdorff_bound) return std::nullopt;
  const std::vector<Vec3> last = w.mesh.points;
  std::optional<Best> found;
  // earlier[0] is the state before the first kept round (the rounds' start): not a round's.
  for (auto it = earlier.rbegin(); it + 1 != earlier.rend() && it->inverted == 0; ++it) {
    w.mesh.points = it->points;
    w.pb.snap(w.mesh, it->summary.min);
    if (w.hausdorff() > w.o.hausdorff_bound) continue;
    found = Best{summary(w.mesh, true), 0, w.mesh.points};
    break;
  }
  w.mesh.points = last;
  return found;
}

//! The result of the retries, or the round within the bound when that is higher in mSJ or the
//! retries' result is beyond the bound (or not valid).
void prefer_within_bound(Optimization& w, const std::optional<Best>& within, Best& best) {
  if (!within) return;
  const double h = w.hausdorff();
  const quality::ScaledJacobianSummary now = summary(w.mesh, true);
  const bool take = inverted_jacobians(w.mesh) > 0 || h > w.o.hausdorff_bound || within->summary.min > now.min;
  core::logger().info("optimize: an earlier round within the bound: mSJ {:.4f}; the retries' result: mSJ {:.4f} at "
                      "{:.3f} %{}",
                      within->summary.min, now.min, 100 * h, take ? ": the earlier round kept" : "");
  if (!take) return;
  best = *within;
  w.mesh.points = within->points;
}

//! The quality rounds as they are asked for, then the final snap and the drift retries. Returns
//! the Hausdorff distance of the result (0 when not measured).
double plain_rounds(Optimization& w, const Start& start, Best& best, OptimizeResult& res,
                    core::ProgressTask* progress, std::optional<Best>& within) {
  std::vector<Best> earlier;
  quality_rounds(w, start, w.o.face_attraction, best, res, progress, &earlier);
  // Finally put the boundary exactly on the target where that keeps every hex at or above the
  // minimum reached (and inverts nothing); not when the boundary fits the surface by its quad
  // centres too (the vertices are then meant to be off it by a fraction of the chord).
  if (w.o.face_attraction <= 0) {
    w.pb.snap(w.mesh, best.summary.min);
    within = last_round_within_bound(w, earlier);
  }
  // Then the retries, when the boundary is beyond the Hausdorff bound.
  return drift_retries(w, start, best, res);
}

//! The rounds with the quad centres attracted, from the start: what the fit retry runs, without
//! the plain rounds before it. `snapped` is the start's distance with its boundary on the target,
//! which the plain rounds end at or above (their snap puts the vertices back on the target, and
//! they do not shorten the chords). So a valid fit within the bound or closer than that is what
//! the fit retry would have kept. Otherwise the plain rounds and their retries run too, and the
//! fit is kept as the fit retry would keep it: valid, and closer than a plain result beyond the
//! bound (or the plain result invalid).
void fitted_rounds(Optimization& w, const Start& start, double snapped, Best& best, OptimizeResult& res,
                   core::ProgressTask& progress) {
  quality_rounds(w, start, w.o.fit_retry, best, res, &progress);
  const double h = w.hausdorff();
  if (best.inverted == 0 && (h <= w.o.hausdorff_bound || h < snapped)) {
    core::logger().info("optimize: quad centres attracted: Hausdorff {:.3f} %, mSJ {:.4f}", 100 * h,
                        best.summary.min);
    res.fit_retry = true;
    return;
  }
  const Best fit{best.summary, best.inverted, w.mesh.points};
  w.mesh.points = start.points;
  best = best_of(w.mesh);
  std::optional<Best> within;
  double plain = plain_rounds(w, start, best, res, nullptr, within);
  if (plain <= 0) plain = w.hausdorff();
  if (fit.inverted == 0 && (best.inverted > 0 || (plain > w.o.hausdorff_bound && h < plain))) {
    core::logger().info("optimize: quad centres attracted: Hausdorff {:.3f} % (without: {:.3f} %), mSJ {:.4f}",
                        100 * h, 100 * plain, fit.summary.min);
    w.mesh.points = fit.points;
    best = fit;
    res.fit_retry = true;
  } else {
    core::logger().info(
        "optimize: attracting the quad centres did not lower the Hausdorff distance ({:.3f} % against {:.3f} %); "
        "not kept",
        100 * h, 100 * plain);
  }
  prefer_within_bound(w, within, best);
}

//! Phase 2: the quality rounds from the untangled mesh, keeping the best state, then the retries.
void quality_phase(Optimization& w, OptimizeResult& res, core::ProgressTask& progress) {
  const OptimizeOptions& o = w.o;
  core::HexMesh& mesh = w.mesh;
  Best best = best_of(mesh);
  // Keep the average: exactly when the input was valid; after untangling, within a small slack
  // (the untangled state's average is not a quality the user asked to keep).
  const Start start{mesh.points, best.inverted,
                    best.summary.average - (res.untangle.iterations > 0 ? o.average_slack : 0.0),
                    best.inverted == 0 && !boundary_crosses(mesh)};
  if (const double snapped = fit_from_start(w, start); snapped > 0) {
    fitted_rounds(w, start, snapped, best, res, progress);
  } else {
    std::optional<Best> within;
    const double hausdorff = plain_rounds(w, start, best, res, &progress, within);
    fit_retry(w, start, hausdorff, best, res);
    prefer_within_bound(w, within, best);
  }
}

void log_polish(const PolishResult& p) {
  core::logger().info("optimize: polish of the worst hexes: mSJ {:.4f} -> {:.4f} ({} moves, {} sweeps, {:.2f} s)",
                      p.min_before, p.min_after, p.moved, p.sweeps, p.seconds);
}

//! Whether the mesh's boundary crosses itself (untangled: every hex positive), logged.
bool untangled_boundary_crosses(const core::HexMesh& mesh) {
  const FoldoverReport check = check_foldover(mesh);
  if (check.boundary_self_intersections == 0) return false;
  core::logger().info("optimize: the untangled boundary crosses itself ({} pairs of triangles); no quality rounds",
                      check.boundary_self_intersections);
  return true;
}

//! Phase 3 (polish.h): the worst hexes' interior vertices, then their boundary vertices along
//! the target (surface vertices on the surface, feature vertices on the feature lines, corners
//! fixed). The boundary's moves are kept only when they raise the mesh's mSJ, the boundary does
//! not cross itself and stays within the Hausdorff bound (or no farther than before): the
//! surface is a constraint, as in the rounds. Skipped after a fit (quad centres attracted),
//! whose vertices are meant to leave the target. res.distance is the result's distance when it
//! was known before.
void polish_phase(Optimization& w, OptimizeResult& res) {
  res.polish = polish_worst_hexes(w.mesh);
  const PolishResult inner = res.polish;
  if (w.o.face_attraction > 0 || res.fit_retry) return log_polish(res.polish);
  const Problem& pb = w.pb;
  std::vector<Vec3> quad_normal, normal;
  pb.boundary_normals([&](int v) { return w.mesh.points[v]; }, quad_normal, normal);
  const BoundaryProjector onto_target = [&](int v, Vec3& p) {
    const VertexRole role = pb.roles.role[v];
    if (role != VertexRole::Surface && role != VertexRole::Feature) return false;  // corners stay
    p = pb.vertex_target(v, p, normal[v]);
    return true;
  };
  core::HexMesh trial = w.mesh;
  const PolishResult outer = polish_worst_hexes(trial, {}, {}, onto_target);
  res.polish.sweeps += outer.sweeps;
  res.polish.seconds += outer.seconds;
  // Boundary moves that leave the mesh's minimum where it was change the surface for nothing.
  if (outer.moved == 0 || outer.min_after <= inner.min_after + 1e-9) return log_polish(res.polish);
  const core::Stopwatch clock;
  const double before = res.distance ? res.distance->relative : w.hausdorff();  // the boundary as before the polish
  const quality::SurfaceDistance after = quality::hausdorff_distance(trial, w.target_mesh);
  const int crossings = check_foldover(trial).boundary_self_intersections;
  res.polish.seconds += clock.seconds();
  if (crossings > 0 || (after.relative > w.o.hausdorff_bound && after.relative > before)) {
    core::logger().info("optimize: the polish's boundary moves are not kept (Hausdorff {:.3f} % -> {:.3f} %, {} "
                        "boundary crossings)",
                        100 * before, 100 * after.relative, crossings);
    return log_polish(res.polish);
  }
  w.mesh = std::move(trial);
  w.distances.remember(w.mesh, after);
  res.distance = after;
  res.polish.moved += outer.moved;
  res.polish.min_after = outer.min_after;
  log_polish(res.polish);
  core::logger().info("optimize: polish: interior mSJ {:.4f}, with the boundary {:.4f}; Hausdorff {:.3f} % -> {:.3f} %",
                      inner.min_after, outer.min_after, 100 * before, 100 * after.relative);
}

}  // namespace

OptimizeResult optimize_hex_mesh(core::HexMesh& mesh, const core::TriMesh& target_mesh,
                                 const OptimizeOptions& o) {
  const auto t0 = Clock::now();
  check_input(mesh, o);
  // Progress: the untangling, each quality round, then the retries (when they run).
  core::ProgressTask progress("optimize", 2 + o.quality_rounds);

  OptimizeResult res;
  res.before = summary(mesh, false);
  res.inverted_before = inverted_jacobians(mesh);

  // Setup: target, features, roles, reduction, attractions.
  SurfaceFeatures features;
  if (o.features) features = detect_features(target_mesh, o.feature_angle);
  const TargetSurface target(target_mesh, std::move(features));
  res.target_feature_edges = static_cast<int>(target.features().edges.size());
  res.target_corners = static_cast<int>(target.features().corners.size());
  const std::vector<double> size = hex_sizes(mesh);
  const std::vector<double> scale = reference_scale(size, o.size_uniformity);
  const std::vector<std::array<double, 3>> lengths = corner_lengths(mesh, size, scale);
  const std::vector<std::array<double, 3>> centre = centre_lengths(mesh, size, scale);
  Problem pb = make_problem(mesh, target, size, o);
  res.boundary_vertices = pb.roles.surface + pb.roles.feature;
  res.feature_vertices = pb.roles.feature;
  res.corner_vertices = pb.roles.corners;
  Optimization w{
      mesh, target_mesh, pb, size, lengths, centre, std::vector<double>(mesh.cells.size(), 1.0), o};
  res.setup.seconds = seconds_since(t0);
  core::logger().info(
      "optimize: {} hexes, {} surface, {} feature, {} corner vertices; target {} sharp edges, {} "
      "corners",
      mesh.num_cells(), pb.roles.surface, pb.roles.feature, pb.roles.corners,
      res.target_feature_edges, res.target_corners);

  // Phase 1: untangle.
  const auto t1 = Clock::now();
  untangle_phase(w, res.untangle);
  res.untangle.seconds = seconds_since(t1);
  progress.step();

  // Phase 2: quality rounds, keeping the best state (unless the caller would throw them away).
  const auto t2 = Clock::now();
  res.stopped_crossing =
      o.stop_when_untangled_crosses && inverted_jacobians(mesh) == 0 && untangled_boundary_crosses(mesh);
  if (!res.stopped_crossing) quality_phase(w, res, progress);
  res.quality.seconds = seconds_since(t2);

  if (const quality::SurfaceDistance* d = w.distances.find(mesh)) res.distance = *d;
  // Phase 3: the polish (it updates res.distance when it moves the boundary).
  if (o.polish && !res.stopped_crossing && inverted_jacobians(mesh) == 0) polish_phase(w, res);
  res.after = summary(mesh, false);
  res.inverted_after = inverted_jacobians(mesh);
  res.untangled = res.inverted_after == 0;
  res.seconds = seconds_since(t0);
  progress.step();
  progress.finish();
  return res;
}

}  // namespace polycube::optimize
