#include "simplify/corner_alignment.h"

#include "core/stopwatch.h"
#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "solve/milp.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numeric>
#include <string>

namespace polycube::simplify {

namespace {


using core::DisjointSets;

//! The state of one axis: merged classes (groups), the contracted constraint DAG and its
//! reachability, and the current coordinates.
class AxisState {
 public:
  explicit AxisState(const AxisSystem& sys) : sys_(sys), groups_(static_cast<std::size_t>(sys.num_classes())) { rebuild(); }

  //! Node (contracted group) of a class.
  [[nodiscard]] int node(int cls) const { return node_of_class_[cls]; }
  [[nodiscard]] int num_nodes() const { return num_nodes_; }

  [[nodiscard]] bool can_align(int corner_a, int corner_b) const {
    const int a = node(sys_.corner_class[corner_a]);
    const int b = node(sys_.corner_class[corner_b]);
    return a != b && !reach(r1_, a, b) && !reach(r1_, b, a);
  }

  void merge(int corner_a, int corner_b) { groups_.unite(sys_.corner_class[corner_a], sys_.corner_class[corner_b]); }

  //! Contract groups (and the zero-weight cycles they create), rebuild arcs and reachability.
  void rebuild() {
    const int nc = sys_.num_classes();
    while (true) {
      // compact node ids in class order
      std::vector<int> root_node(static_cast<std::size_t>(nc), -1);
      num_nodes_ = 0;
      node_of_class_.assign(static_cast<std::size_t>(nc), -1);
      for (int k = 0; k < nc; ++k) {
        const int r = groups_.find(k);
        if (root_node[r] < 0) root_node[r] = num_nodes_++;
        node_of_class_[k] = root_node[r];
      }
      std::map<std::pair<int, int>, int> arcs;
      for (const auto& c : sys_.constraints) {
        const int f = node_of_class_[c.from];
        const int t = node_of_class_[c.to];
        if (f == t) {
          PC_REQUIRE(c.weight == 0, "alignment merged the two ends of a strict constraint");
          continue;
        }
        auto& w = arcs[{f, t}];
        w = std::max(w, c.weight);
      }
      arcs_.clear();
      for (const auto& [ft, w] : arcs) arcs_.push_back({ft.first, ft.second, w});
      // zero-weight cycles force equality: find SCCs and merge them
      const auto comp = strongly_connected();
      bool merged_any = false;
      for (int k = 0; k < nc; ++k) {
        const int n = node_of_class_[k];
        // unite every class with the first class of its component
        if (first_class_of_comp_[comp[n]] != k) merged_any |= groups_.unite(k, first_class_of_comp_[comp[n]]);
      }
      if (!merged_any) break;
    }
    compute_reachability();
  }

  [[nodiscard]] const std::vector<AxisConstraint>& arcs() const { return arcs_; }

 private:
  //! Tarjan's SCC (iterative); also fills first_class_of_comp_.
  std::vector<int> strongly_connected() {
    const int n = num_nodes_;
    std::vector<std::vector<int>> out(static_cast<std::size_t>(n));
    for (const auto& a : arcs_) out[a.from].push_back(a.to);
    std::vector<int> index(static_cast<std::size_t>(n), -1), low(static_cast<std::size_t>(n), 0), comp(static_cast<std::size_t>(n), -1);
    std::vector<char> on_stack(static_cast<std::size_t>(n), 0);
    std::vector<int> stack;
    int counter = 0, ncomp = 0;
    for (int s0 = 0; s0 < n; ++s0) {
      if (index[s0] >= 0) continue;
      std::vector<std::pair<int, std::size_t>> call{{s0, 0}};
      index[s0] = low[s0] = counter++;
      stack.push_back(s0);
      on_stack[s0] = 1;
      while (!call.empty()) {
        auto& [v, i] = call.back();
        if (i < out[v].size()) {
          const int w = out[v][i++];
          if (index[w] < 0) {
            index[w] = low[w] = counter++;
            stack.push_back(w);
            on_stack[w] = 1;
            call.push_back({w, 0});
          } else if (on_stack[w]) {
            low[v] = std::min(low[v], index[w]);
          }
        } else {
          const int vv = v;
          call.pop_back();
          if (!call.empty()) low[call.back().first] = std::min(low[call.back().first], low[vv]);
          if (low[vv] == index[vv]) {
            while (true) {
              const int w = stack.back();
              stack.pop_back();
              on_stack[w] = 0;
              comp[w] = ncomp;
              if (w == vv) break;
            }
            ++ncomp;
          }
        }
      }
    }
    first_class_of_comp_.assign(static_cast<std::size_t>(ncomp), -1);
    for (int k = 0; k < sys_.num_classes(); ++k) {
      const int c = comp[node_of_class_[k]];
      if (first_class_of_comp_[c] < 0) first_class_of_comp_[c] = k;
    }
    return comp;
  }

  [[nodiscard]] bool reach(const std::vector<std::uint64_t>& r, int i, int j) const {
    return ((r[static_cast<std::size_t>(i) * words_ + j / 64] >> (j % 64)) & 1U) != 0;
  }

  //! r0: reachable; r1: reachable through a strict arc. The contracted graph is a DAG.
  void compute_reachability() {
    const int n = num_nodes_;
    words_ = (static_cast<std::size_t>(n) + 63) / 64;
    r0_.assign(static_cast<std::size_t>(n) * words_, 0);
    r1_.assign(r0_.size(), 0);
    std::vector<std::vector<std::pair<int, int>>> out(static_cast<std::size_t>(n));
    std::vector<int> indeg(static_cast<std::size_t>(n), 0);
    for (const auto& a : arcs_) {
      out[a.from].push_back({a.to, a.weight});
      ++indeg[a.to];
    }
    std::vector<int> topo;
    for (int v = 0; v < n; ++v)
      if (indeg[v] == 0) topo.push_back(v);
    for (std::size_t i = 0; i < topo.size(); ++i)
      for (const auto& [w, wt] : out[topo[i]])
        if (--indeg[w] == 0) topo.push_back(w);
    PC_REQUIRE(static_cast<int>(topo.size()) == n, "contracted constraint graph has a cycle");
    for (auto it = topo.rbegin(); it != topo.rend(); ++it) {
      const int v = *it;
      auto* d0 = &r0_[static_cast<std::size_t>(v) * words_];
      auto* d1 = &r1_[static_cast<std::size_t>(v) * words_];
      for (const auto& [w, wt] : out[v]) {
        const auto* s0 = &r0_[static_cast<std::size_t>(w) * words_];
        const auto* s1 = &r1_[static_cast<std::size_t>(w) * words_];
        d0[w / 64] |= std::uint64_t{1} << (w % 64);
        for (std::size_t q = 0; q < words_; ++q) d0[q] |= s0[q];
        if (wt > 0) {
          d1[w / 64] |= std::uint64_t{1} << (w % 64);
          for (std::size_t q = 0; q < words_; ++q) d1[q] |= s0[q];
        } else {
          for (std::size_t q = 0; q < words_; ++q) d1[q] |= s1[q];
        }
      }
    }
  }

  const AxisSystem& sys_;
  DisjointSets groups_;
  int num_nodes_ = 0;
  std::vector<int> node_of_class_;
  std::vector<int> first_class_of_comp_;
  std::vector<AxisConstraint> arcs_;
  std::size_t words_ = 0;
  std::vector<std::uint64_t> r0_, r1_;
};

//! Solve one axis exactly: returns the integer coordinate of every node.
std::vector<int> solve_axis(const AxisSystem& sys, const AxisState& st, const std::vector<CornerPair>& pairs,
                            double lambda, std::string& solver_name) {
  const int n = st.num_nodes();
  solve::LinearProgram lp;
  for (int v = 0; v < n; ++v) lp.add_variable(0.0);
  // shape: per node, weights of |X − b| on integers b (L1 to s·x interpolated at integers)
  std::vector<std::map<long long, double>> w(static_cast<std::size_t>(n));
  for (int k = 0; k < sys.num_classes(); ++k) {
    const double t = sys.coordinate[k];
    const double cnt = sys.class_size[k];
    const double fl = std::floor(t);
    const double phi = t - fl;
    auto& m = w[st.node(k)];
    constexpr double kSnap = 1e-9;
    if (phi <= kSnap) {
      m[static_cast<long long>(fl)] += cnt;
    } else if (phi >= 1.0 - kSnap) {
      m[static_cast<long long>(fl) + 1] += cnt;
    } else {
      m[static_cast<long long>(fl)] += cnt * (1.0 - phi);
      m[static_cast<long long>(fl) + 1] += cnt * phi;
    }
  }
  for (int v = 0; v < n; ++v)
    for (const auto& [b, wt] : w[v]) {
      const double bd = static_cast<double>(b);
      const int tp = lp.add_variable(lambda * wt, 0.0);  // tp ≥ X − b
      lp.add_row({tp, v}, {1.0, -1.0}, -bd);
      const int tm = lp.add_variable(lambda * wt, 0.0);  // tm ≥ b − X
      lp.add_row({tm, v}, {1.0, 1.0}, bd);
    }
  // alignment: |X_a − X_b| per pair
  for (const auto& p : pairs) {
    const int a = st.node(sys.corner_class[p.a]);
    const int b = st.node(sys.corner_class[p.b]);
    if (a == b) continue;
    const int t1 = lp.add_variable(1.0, 0.0);
    lp.add_row({t1, a, b}, {1.0, -1.0, 1.0}, 0.0);
    const int t2 = lp.add_variable(1.0, 0.0);
    lp.add_row({t2, a, b}, {1.0, 1.0, -1.0}, 0.0);
  }
  // structure: X_to − X_from ≥ weight
  for (const auto& c : st.arcs()) lp.add_row({c.to, c.from}, {1.0, -1.0}, static_cast<double>(c.weight));

  const auto res = solve::solve_program(lp);
  solver_name = res.solver + " (LP, totally unimodular: integral vertex optimum)";
  if (res.status != solve::MilpStatus::Optimal)
    throw core::SolverError(std::string("corner alignment LP along ") + "xyz"[sys.axis] + ": " +
                            solve::status_name(res.status));
  std::vector<int> x(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    const double r = std::round(res.x[v]);
    if (std::abs(res.x[v] - r) > 1e-5)
      throw core::SolverError("corner alignment LP returned a fractional coordinate " + std::to_string(res.x[v]));
    x[v] = static_cast<int>(r);
  }
  for (const auto& c : st.arcs())
    if (x[c.to] - x[c.from] < c.weight)
      throw core::SolverError("corner alignment LP solution violates a structural constraint after rounding");
  return x;
}

double shape_energy(const CornerSystem& sys, const std::array<std::vector<double>, 3>& class_pos, double* max_disp) {
  double e = 0.0, m = 0.0;
  for (int a = 0; a < 3; ++a) {
    const auto& ax = sys.axes[a];
    for (int k = 0; k < ax.num_classes(); ++k) {
      const double d = std::abs(class_pos[a][k] - ax.coordinate[k]);
      e += d * ax.class_size[k];
      m = std::max(m, d);
    }
  }
  if (max_disp) *max_disp = m;
  return e;
}

int distinct(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return static_cast<int>(std::unique(v.begin(), v.end()) - v.begin());
}

}  // namespace

double auto_scale(const structure::PolycubeStructure& s, double resolution) {
  if (s.corners.empty()) throw core::GeometryError("polycube structure has no corner");
  core::Vec3 lo = s.corners.front().position, hi = lo;
  for (const auto& c : s.corners) {
    lo = lo.cwiseMin(c.position);
    hi = hi.cwiseMax(c.position);
  }
  const double side = (hi - lo).maxCoeff();
  if (!(side > 0.0)) throw core::GeometryError("polycube has zero extent");
  return resolution / side;
}

AlignResult align_corners(const structure::PolycubeStructure& s, const AlignOptions& opt) {
  if (opt.scale < 0.0 || !std::isfinite(opt.scale)) throw core::InputError("simplify: scale must be >= 0 (0 = automatic)");
  if (!(opt.lambda_min >= 0.0)) throw core::InputError("simplify: lambda-min must be >= 0");
  if (!opt.frozen_corners.empty() && opt.frozen_corners.size() != s.corners.size())
    throw core::InputError("simplify: one frozen flag per corner expected");
  AlignResult res;
  const core::Stopwatch t_sys;
  res.scale = opt.scale > 0.0 ? opt.scale : auto_scale(s, opt.auto_resolution);
  res.system = build_corner_system(s, res.scale, opt.system);
  res.seconds_system = t_sys.seconds();
  const CornerSystem& sys = res.system;
  const int nc = static_cast<int>(s.corners.size());
  for (int a = 0; a < 3; ++a) res.planes_before[a] = distinct(sys.axes[a].coordinate);

  std::array<std::vector<double>, 3> original;
  for (int a = 0; a < 3; ++a) original[a] = sys.axes[a].coordinate;
  std::vector<AxisState> states;
  states.reserve(3);
  for (int a = 0; a < 3; ++a) states.emplace_back(sys.axes[a]);

  // current class coordinates and corner positions
  std::array<std::vector<double>, 3> class_pos = original;
  auto corner_positions = [&]() {
    std::vector<core::Vec3> p(static_cast<std::size_t>(nc));
    for (int c = 0; c < nc; ++c)
      for (int a = 0; a < 3; ++a) p[c][a] = class_pos[a][sys.axes[a].corner_class[c]];
    return p;
  };

  // pairing rule 3: midpoint of the original positions outside the input polycube (cached)
  std::map<std::pair<int, int>, bool> exterior_cache;
  IsExterior exterior;
  if (opt.exterior_rule)
    exterior = [&](int a, int b) {
      auto [it, fresh] = exterior_cache.try_emplace({a, b}, false);
      if (fresh) {
        core::Vec3 m;
        for (int k = 0; k < 3; ++k)
          m[k] = 0.5 * (original[k][sys.axes[k].corner_class[a]] + original[k][sys.axes[k].corner_class[b]]);
        it->second = !inside_polycube(sys, s, original, m);
      }
      return it->second;
    };
  const CanAlign can_align = [&](int axis, int a, int b) { return states[axis].can_align(a, b); };

  double lambda = 1.0;
  res.stop_reason = "max_iterations";
  for (int it = 0; it < opt.max_iterations; ++it) {
    if (lambda < opt.lambda_min) {
      res.stop_reason = "lambda_min";
      break;
    }
    const core::Stopwatch t_it;
    AlignIteration rec;
    rec.lambda = lambda;
    const core::Stopwatch t_pair;
    const auto pos = corner_positions();
    auto pairs = pair_corners(s, pos, can_align, exterior, &rec.pairing);
    if (!opt.frozen_corners.empty())
      std::erase_if(pairs, [&](const CornerPair& p) { return opt.frozen_corners[p.a] || opt.frozen_corners[p.b]; });
    res.seconds_pairing += t_pair.seconds();
    rec.candidates = static_cast<int>(pairs.size());
    if (pairs.empty()) {
      res.converged = true;
      res.stop_reason = "converged";
      rec.seconds = t_it.seconds();
      rec.aligned_total = static_cast<int>(res.aligned.size());
      for (int a = 0; a < 3; ++a) rec.planes[a] = distinct(class_pos[a]);
      rec.shape_energy = shape_energy(sys, class_pos, nullptr);
      res.iterations.push_back(rec);
      break;
    }
    const core::Stopwatch t_solve;
    for (int a = 0; a < 3; ++a) {
      std::vector<CornerPair> pa;
      for (const auto& p : pairs)
        if (p.axis == a) pa.push_back(p);
      if (pa.empty()) continue;
      const auto x = solve_axis(sys.axes[a], states[a], pa, lambda, res.solver);
      ++res.lp_solves;
      for (int k = 0; k < sys.axes[a].num_classes(); ++k) class_pos[a][k] = x[states[a].node(k)];
      for (const auto& p : pa)
        if (x[states[a].node(sys.axes[a].corner_class[p.a])] == x[states[a].node(sys.axes[a].corner_class[p.b])]) {
          states[a].merge(p.a, p.b);
          res.aligned.push_back({p.a, p.b, a, it});
          ++rec.aligned;
        }
      states[a].rebuild();
    }
    res.seconds_solve += t_solve.seconds();
    rec.aligned_total = static_cast<int>(res.aligned.size());
    for (int a = 0; a < 3; ++a) rec.planes[a] = distinct(class_pos[a]);
    rec.shape_energy = shape_energy(sys, class_pos, nullptr);
    rec.seconds = t_it.seconds();
    res.iterations.push_back(rec);
    lambda *= 0.5;
  }

  // finalization: E_shape only under all alignments (thesis §3.5)
  const core::Stopwatch t_fin;
  for (int a = 0; a < 3; ++a) {
    const auto x = solve_axis(sys.axes[a], states[a], {}, 1.0, res.solver);
    ++res.lp_solves;
    res.class_value[a].resize(static_cast<std::size_t>(sys.axes[a].num_classes()));
    for (int k = 0; k < sys.axes[a].num_classes(); ++k) {
      res.class_value[a][k] = x[states[a].node(k)];
      class_pos[a][k] = res.class_value[a][k];
    }
    res.planes_after[a] = distinct(class_pos[a]);
  }
  res.seconds_finalize = t_fin.seconds();
  res.corners = corner_positions();
  res.shape_energy = shape_energy(sys, class_pos, &res.max_displacement);
  return res;
}

}  // namespace polycube::simplify
