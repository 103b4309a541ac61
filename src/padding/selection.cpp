#include "padding/selection.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "padding/padding_topology.h"
#include "solve/milp.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace polycube::padding {

namespace {

using detail::Topology;

//! Indices of the program's variables.
struct Variables {
  std::vector<int> hex;    //!< #H: y of each hex
  std::vector<int> ghost;  //!< #F: y of the ghost of each boundary facet (-1 for interior facets)
  std::vector<int> x;      //!< #F: facet selected
  std::vector<int> z;      //!< #E: the two ghosts of a boundary edge on different sides (-1 elsewhere)
  std::vector<int> te;     //!< #E: edge turn (-1 where none is counted)
  std::vector<int> tv;     //!< #V: vertex turn (-1 where none is counted)
};

//! The two cells of facet f as variables (hex, other hex or ghost).
std::array<int, 2> facet_cells(const Topology& tp, const Variables& v, int f) {
  const auto [c0, c1] = tp.t.faces.face_cells[f];
  return {v.hex[c0], c1 >= 0 ? v.hex[c1] : v.ghost[f]};
}

//! Add a row whose columns may be -1 (a variable that does not exist: fixed at 0), left out.
void add_live_row(solve::LinearProgram& p, const std::vector<int>& cols, const std::vector<double>& coefs, double lo,
                  double hi) {
  std::vector<int> c;
  std::vector<double> k;
  for (std::size_t i = 0; i < cols.size(); ++i)
    if (cols[i] >= 0) {
      c.push_back(cols[i]);
      k.push_back(coefs[i]);
    }
  if (!c.empty()) p.add_row(std::move(c), std::move(k), lo, hi);
}

//! w ≥ |a − b| (two rows); with `exact`, also w ≤ a + b and w ≤ 2 − a − b (w = a XOR b).
//! a and b may be -1 (none: 0).
void add_xor(solve::LinearProgram& p, int w, int a, int b, bool exact) {
  add_live_row(p, {w, a, b}, {1, -1, 1}, 0, solve::kInfinity);
  add_live_row(p, {w, a, b}, {1, 1, -1}, 0, solve::kInfinity);
  if (!exact) return;
  add_live_row(p, {w, a, b}, {1, -1, -1}, -solve::kInfinity, 0);
  add_live_row(p, {w, a, b}, {1, 1, 1}, -solve::kInfinity, 2);
}

//! Opposite facet pairs around an edge (two apart in the turning order): a straight sheet
//! selects both or neither.
std::vector<std::array<int, 2>> opposite_facets(const std::vector<int>& around) {
  if (around.size() == 3) return {{around[0], around[2]}};
  if (around.size() == 4) return {{around[0], around[2]}, {around[1], around[3]}};
  return {};
}

//! The cells around edge e as program variables, in turning order (cells_around(); at a
//! boundary edge the ghosts first and last).
std::vector<int> cell_variables(const core::HexMesh& mesh, const Topology& tp, const Variables& v, int e) {
  std::vector<int> out;
  for (int c : detail::cells_around(mesh, tp, e))
    out.push_back(c < tp.num_hexes ? v.hex[c] : v.ghost[c - tp.num_hexes]);
  return out;
}

struct Model {
  solve::LinearProgram program;
  Variables v;
  std::vector<std::vector<std::array<int, 2>>> pairs;       //!< #E: opposite facet pairs of te edges
  std::vector<std::vector<std::array<int, 2>>> edge_pairs;  //!< #V: opposite te-edge pairs
};

//! Edges where HF itself turns (two of its facets around the edge, not opposite), and the
//! vertices on them: their turns are in every solution, so they are not counted.
void forced_turns(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& hard,
                  std::vector<std::uint8_t>& edge_forced, std::vector<std::uint8_t>& vertex_forced) {
  edge_forced.assign(tp.t.num_edges(), 0);
  vertex_forced.assign(mesh.points.size(), 0);
  for (int e = 0; e < tp.t.num_edges(); ++e) {
    if (!tp.t.edge_on_boundary[e]) continue;
    const auto [b1, b2] = tp.edge_boundary[e];
    if (b1 < 0 || b2 < 0 || !hard[b1] || !hard[b2]) continue;
    if (tp.t.edge_valence(e) == 2) continue;  // E2H: the two surface facets are opposite
    edge_forced[e] = 1;
    for (int w : tp.t.edges.edges[e]) vertex_forced[w] = 1;
  }
}

//! Equation 4.6: opposite edges at a vertex (no facet holds both) turn together; a vertex turn
//! tv_v ≥ |te_i − te_k| for each such pair of edges with a turn variable.
void add_vertex_turns(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& vertex_forced,
                      double lambda, Model& m) {
  solve::LinearProgram& p = m.program;
  Variables& v = m.v;
  const double w_vertex = lambda;
  v.tv.assign(mesh.points.size(), -1);
  m.edge_pairs.resize(mesh.points.size());
  for (int vert = 0; lambda > 0 && vert < mesh.num_points(); ++vert) {
    if (vertex_forced[vert] || tp.vertex_hexes[vert].size() <= 1) continue;
    std::vector<int> edges;
    for (int e : tp.vertex_edges[vert])
      if (v.te[e] >= 0) edges.push_back(e);
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = i + 1; j < edges.size(); ++j) {
        bool share = false;
        for (int f : tp.t.edge_faces[edges[i]])
          share = share || std::find(tp.t.edge_faces[edges[j]].begin(), tp.t.edge_faces[edges[j]].end(), f) !=
                               tp.t.edge_faces[edges[j]].end();
        if (!share) m.edge_pairs[vert].push_back({edges[i], edges[j]});
      }
    if (m.edge_pairs[vert].empty()) continue;
    v.tv[vert] = p.add_variable(w_vertex, 0, 1);
    for (const auto& [a, b] : m.edge_pairs[vert]) add_xor(p, v.tv[vert], v.te[a], v.te[b], false);
  }
}

Model build_model(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& hard,
                  const SelectionOptions& o) {
  Model m;
  solve::LinearProgram& p = m.program;
  Variables& v = m.v;
  const int nf = tp.t.num_faces(), ne = tp.t.num_edges();
  const double hexes = static_cast<double>(mesh.num_cells());
  const double w_facet = std::pow(hexes, -2.0 / 3.0);
  const double w_edge = o.lambda * std::pow(hexes, -1.0 / 3.0);

  v.hex.resize(mesh.cells.size());
  for (auto& y : v.hex) y = p.add_variable(0, 0, 1, true);
  v.ghost.assign(nf, -1);
  for (int f = 0; f < nf; ++f)
    if (tp.t.faces.is_boundary(f)) v.ghost[f] = p.add_variable(0, 0, 1, true);
  for (int f = 0; f < nf; ++f)
    if (hard[f]) {  // equation 4.2: the hex inside, its ghost outside
      p.lower[v.hex[tp.t.faces.face_cells[f][0]]] = 1;
      p.upper[v.ghost[f]] = 0;
    }
  v.x.resize(nf);
  for (int f = 0; f < nf; ++f) v.x[f] = p.add_variable(hard[f] ? 0.0 : w_facet, 0, 1);

  std::vector<std::uint8_t> edge_forced, vertex_forced;
  forced_turns(mesh, tp, hard, edge_forced, vertex_forced);
  std::vector<std::uint8_t> exact(nf, 0);  // facets in a rule or turn row need x = XOR exactly
  v.z.assign(ne, -1);
  v.te.assign(ne, -1);
  m.pairs.resize(ne);
  for (int e = 0; e < ne; ++e) {
    const std::vector<int> around = detail::facets_around(mesh, tp, e);
    const bool boundary = tp.t.edge_on_boundary[e] != 0;
    const int valence = tp.t.edge_valence(e);
    if (boundary) {
      const auto [b1, b2] = tp.edge_boundary[e];
      if (valence >= 3) {
        add_live_row(p, {v.ghost[b1], v.ghost[b2]}, {1, -1}, 0, 0);  // E3H: an even count
      } else if (v.ghost[b1] >= 0 || v.ghost[b2] >= 0) {
        v.z[e] = p.add_variable(0, 0, 1);
        add_xor(p, v.z[e], v.ghost[b1], v.ghost[b2], false);
      }
      if (valence == 2 && around.size() == 3) {  // E2H: not one surface facet alone
        const int g = around[1];
        add_live_row(p, {v.x[b1], v.z[e], v.x[g], v.x[b2]}, {1, 1, -1, -1}, -solve::kInfinity, 1);
        add_live_row(p, {v.x[b2], v.z[e], v.x[g], v.x[b1]}, {1, 1, -1, -1}, -solve::kInfinity, 1);
        for (int f : around) exact[f] = 1;
      }
    }
    // Sheets do not cross: at most two separations around an edge (selection.h).
    const int separations = static_cast<int>(tp.t.edge_faces[e].size()) + (v.z[e] >= 0 ? 1 : 0);
    if (separations > 2) {
      std::vector<int> cols;
      for (int f : tp.t.edge_faces[e]) cols.push_back(v.x[f]);
      cols.push_back(v.z[e]);
      add_live_row(p, cols, std::vector<double>(cols.size(), 1.0), -solve::kInfinity, 2);
    }
    if (o.lambda <= 0 || valence == 1 || edge_forced[e]) continue;
    m.pairs[e] = opposite_facets(around);
    std::erase_if(m.pairs[e], [&](const std::array<int, 2>& q) { return v.x[q[0]] < 0 && v.x[q[1]] < 0; });
    if (m.pairs[e].empty()) continue;
    v.te[e] = p.add_variable(w_edge, 0, 1);
    for (const auto& [a, b] : m.pairs[e]) {  // equation 4.5
      add_xor(p, v.te[e], v.x[a], v.x[b], false);
      exact[a] = exact[b] = 1;
    }
  }
  for (int f = 0; f < nf; ++f) {
    if (v.x[f] < 0) continue;
    const auto [a, b] = facet_cells(tp, v, f);
    add_xor(p, v.x[f], a, b, exact[f] != 0);
  }

  add_vertex_turns(mesh, tp, vertex_forced, o.lambda, m);
  return m;
}

//! Turn indicators of a selection, as the rows define them (the largest difference of a pair).
void turns_of(const Model& m, const std::vector<double>& x_of_facet, std::vector<double>& te, std::vector<double>& tv) {
  te.assign(m.v.te.size(), 0.0);
  tv.assign(m.v.tv.size(), 0.0);
  for (std::size_t e = 0; e < te.size(); ++e)
    for (const auto& [a, b] : m.pairs[e]) te[e] = std::max(te[e], std::abs(x_of_facet[a] - x_of_facet[b]));
  for (std::size_t w = 0; w < tv.size(); ++w)
    for (const auto& [a, b] : m.edge_pairs[w]) tv[w] = std::max(tv[w], std::abs(te[a] - te[b]));
}

//! The program's point of a cut: y of every hex and ghost given (`inside`, by variable), x, z
//! and the turn indicators as the rows define them.
std::vector<double> cut_solution(const Model& m, const Topology& tp, const std::vector<double>& inside) {
  const Variables& v = m.v;
  std::vector<double> s(static_cast<std::size_t>(m.program.num_variables()), 0.0);
  for (int y : v.hex) s[y] = inside[y];
  for (int y : v.ghost)
    if (y >= 0) s[y] = inside[y];
  const auto y = [&](int var) { return var >= 0 ? s[var] : 0.0; };
  std::vector<double> x(v.x.size(), 0.0);
  for (int f = 0; f < tp.t.num_faces(); ++f) {
    const auto [a, b] = facet_cells(tp, v, f);
    x[f] = y(a) != y(b) ? 1.0 : 0.0;
    s[v.x[f]] = x[f];
  }
  for (int e = 0; e < tp.t.num_edges(); ++e)
    if (v.z[e] >= 0) {
      const auto [b1, b2] = tp.edge_boundary[e];
      s[v.z[e]] = y(b1 >= 0 ? v.ghost[b1] : -1) != y(b2 >= 0 ? v.ghost[b2] : -1) ? 1.0 : 0.0;
    }
  std::vector<double> te, tv;
  turns_of(m, x, te, tv);
  for (std::size_t e = 0; e < te.size(); ++e)
    if (v.te[e] >= 0) s[v.te[e]] = te[e];
  for (std::size_t w = 0; w < tv.size(); ++w)
    if (v.tv[w] >= 0) s[v.tv[w]] = tv[w];
  return s;
}

//! The cut that pads every surface facet: every hex inside, every ghost outside.
std::vector<double> surface_start(const Model& m, const Topology& tp) {
  std::vector<double> inside(static_cast<std::size_t>(m.program.num_variables()), 0.0);
  for (int y : m.v.hex) inside[y] = 1.0;
  return cut_solution(m, tp, inside);
}

//! The cut that pads the hexes of HF as a pillow of their own: those hexes inside, the ghosts
//! of HF outside, every other ghost on its hex's side (its facet not padded), then, until every
//! rule holds, a ghost outside where its facet would stop a padded patch on a flat face or
//! where a concave edge's two ghosts differ, and a hex inside where two sheets would cross at
//! an edge. Each fix pads one more facet or hex, so it ends. Where turns cost little, this
//! layer, one hex deep, costs the walls around HF's patches instead of the rest of the
//! surface. Empty when the rules still fail (they do not on a hex mesh of a solid).
std::vector<double> pillow_start(const Model& m, const core::HexMesh& mesh, const Topology& tp,
                                 const std::vector<std::uint8_t>& hard) {
  const Variables& v = m.v;
  std::vector<double> inside(static_cast<std::size_t>(m.program.num_variables()), 0.0);
  std::vector<char> ghost_out(static_cast<std::size_t>(m.program.num_variables()), 0);
  for (int f = 0; f < tp.t.num_faces(); ++f)
    if (hard[f]) {
      inside[v.hex[tp.t.faces.face_cells[f][0]]] = 1.0;
      ghost_out[v.ghost[f]] = 1;
    }
  std::vector<std::vector<int>> cycles(static_cast<std::size_t>(tp.t.num_edges()));
  for (int e = 0; e < tp.t.num_edges(); ++e)
    if (tp.t.edge_valence(e) != 1) cycles[e] = cell_variables(mesh, tp, v, e);
  for (bool changed = true; changed;) {
    changed = false;
    for (int f = 0; f < tp.t.num_faces(); ++f)
      if (v.ghost[f] >= 0)
        inside[v.ghost[f]] = ghost_out[v.ghost[f]] ? 0.0 : inside[v.hex[tp.t.faces.face_cells[f][0]]];
    const auto pad_ghosts = [&](int a, int b) {
      changed = changed || !ghost_out[a] || !ghost_out[b];
      ghost_out[a] = ghost_out[b] = 1;
    };
    for (int e = 0; e < tp.t.num_edges(); ++e) {
      const std::vector<int>& c = cycles[e];
      if (c.empty()) continue;
      const bool boundary = tp.t.edge_on_boundary[e] != 0;
      const auto in = [&](int k) { return inside[c[k]] > 0.5; };
      if (boundary && c.size() == 4 && in(1) && in(2) && in(0) != in(3)) pad_ghosts(c[0], c[3]);
      if (boundary && c.size() == 5 && in(0) != in(4)) pad_ghosts(c[0], c[4]);
      // The closed cycle of four cells: an E3H edge's two ghosts are one cell (c4 left out).
      const std::size_t cells = boundary && c.size() == 5 ? 4 : c.size();
      if (cells != 4 || in(0) == in(1) || in(1) == in(2) || in(2) == in(3)) continue;
      // Two sheets crossing: take in the first hex of the outside pair.
      const int last_hex = boundary && c.size() == 4 ? 2 : 3;  // E2H: c3 is a ghost
      for (int k = boundary ? 1 : 0; k <= last_hex; ++k)
        if (!in(k)) {
          inside[c[k]] = 1.0;
          changed = true;
          break;
        }
    }
  }
  std::vector<double> s = cut_solution(m, tp, inside);
  return m.program.satisfied_by(s) ? s : std::vector<double>{};
}

//! Cells (hex and ghost variables) next to each other: across a facet, or two ghosts at a
//! boundary edge.
std::vector<std::vector<int>> cell_neighbours(const Model& m, const Topology& tp) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(m.program.num_variables()));
  const auto link = [&](int a, int b) {
    if (a < 0 || b < 0) return;
    out[a].push_back(b);
    out[b].push_back(a);
  };
  for (int f = 0; f < tp.t.num_faces(); ++f) {
    const auto [a, b] = facet_cells(tp, m.v, f);
    link(a, b);
  }
  for (int e = 0; e < tp.t.num_edges(); ++e)
    if (tp.t.edge_on_boundary[e]) {
      const auto [b1, b2] = tp.edge_boundary[e];
      if (b1 >= 0 && b2 >= 0) link(m.v.ghost[b1], m.v.ghost[b2]);
    }
  return out;
}

//! Which variables stay fixed when only the cells within `rings` steps of `seeds` are free: a
//! cell outside, and every x, z and turn indicator whose rows read fixed cells only (their values
//! follow from the cut, cut_solution()).
std::vector<char> fixed_outside(const Model& m, const Topology& tp, const std::vector<std::vector<int>>& neighbours,
                                std::vector<int> seeds, int rings) {
  const Variables& v = m.v;
  std::vector<char> fixed(static_cast<std::size_t>(m.program.num_variables()), 1);
  std::vector<int> front = std::move(seeds);
  for (int y : front) fixed[y] = 0;
  for (int ring = 0; ring < rings; ++ring) {
    std::vector<int> next;
    for (int c : front)
      for (int d : neighbours[c])
        if (fixed[d]) {
          fixed[d] = 0;
          next.push_back(d);
        }
    front = std::move(next);
  }
  const auto is_fixed = [&](int var) { return var < 0 || fixed[var] != 0; };
  for (int f = 0; f < tp.t.num_faces(); ++f) {
    const auto [a, b] = facet_cells(tp, v, f);
    fixed[v.x[f]] = is_fixed(a) && is_fixed(b) ? 1 : 0;
  }
  for (int e = 0; e < tp.t.num_edges(); ++e) {
    if (v.z[e] >= 0) {
      const auto [b1, b2] = tp.edge_boundary[e];
      fixed[v.z[e]] = is_fixed(b1 >= 0 ? v.ghost[b1] : -1) && is_fixed(b2 >= 0 ? v.ghost[b2] : -1) ? 1 : 0;
    }
    if (v.te[e] < 0) continue;
    bool all = true;
    for (const auto& [a, b] : m.pairs[e]) all = all && is_fixed(v.x[a]) && is_fixed(v.x[b]);
    fixed[v.te[e]] = all ? 1 : 0;
  }
  for (std::size_t w = 0; w < v.tv.size(); ++w) {
    if (v.tv[w] < 0) continue;
    bool all = true;
    for (const auto& [a, b] : m.edge_pairs[w]) all = all && is_fixed(v.te[a]) && is_fixed(v.te[b]);
    fixed[v.tv[w]] = all ? 1 : 0;
  }
  return fixed;
}

//! Rings of cells around the fractional ones that repair_rounding() frees in turn.
constexpr std::array<int, 3> kRepairRings{2, 4, 8};
//! Share of the time limit the repair may take; branch and cut gets the rest.
constexpr double kRepairShare = 0.25;
//! Largest neighbourhood worth a program of its own, as a share of the whole program's
//! variables: CBC finds no point in time in a neighbourhood of a tenth of the whole either.
constexpr double kRepairLargest = 0.05;
//! Branch-and-cut nodes of each neighbourhood's program: a node limit rather than the time left
//! decides when it stops, so the repair's point does not depend on the machine (the time left
//! only caps it).
constexpr int kRepairNodes = 500;
//! Largest program branch and cut searches under a time limit. On the padding problems of
//! 20,000-hex meshes (about 190,000 variables) with a fractional relaxation, CBC's root node
//! outlasts a minute, and without strong branching it processes a few nodes in minutes, never
//! improving on the start; on 2,000-hex meshes (about 21,000 variables) it does not close the gap
//! within a minute either (bench/RESULTS.md). The best start is then the answer, the same on
//! any machine.
constexpr int kBranchAndCutLargest = 20000;
//! A relaxation's value this far from 0 and 1 is fractional.
constexpr double kFractional = 1e-6;

bool fractional(double y) { return y > kFractional && y < 1 - kFractional; }

//! The relaxation made integral: its cut rounded at 1/2, which keeps HF and the concave edges
//! but may break E2H and no-crossing rows where the relaxation was fractional. The cells within
//! a few rings of the fractional ones are then set anew by solving the program over them alone,
//! the rest fixed to the rounding: 2, 4 and 8 rings, while the point found does not yet cost
//! what the relaxation does, the neighbourhood stays small (kRepairLargest) and the repair's
//! share of `seconds` is left. The padding problem's relaxation is often integral but at a few
//! ghosts, whose facets it pads by half; then the neighbourhood is a few hundred cells. Empty
//! when no neighbourhood gives a feasible point.
std::vector<double> repair_rounding(const Model& m, const Topology& tp, const std::vector<double>& relaxation,
                                    double seconds) {
  const core::Stopwatch clock;
  std::vector<double> inside(relaxation.size(), 0.0);
  for (int y : m.v.hex) inside[y] = relaxation[y] >= 0.5 ? 1.0 : 0.0;
  for (int y : m.v.ghost)
    if (y >= 0) inside[y] = relaxation[y] >= 0.5 ? 1.0 : 0.0;
  const std::vector<double> rounded = cut_solution(m, tp, inside);
  if (m.program.satisfied_by(rounded)) return rounded;
  std::vector<int> seeds;
  for (int y : m.v.hex)
    if (fractional(relaxation[y])) seeds.push_back(y);
  for (int y : m.v.ghost)
    if (y >= 0 && fractional(relaxation[y])) seeds.push_back(y);
  const double bound = m.program.objective(relaxation);
  const double budget = seconds > 0 ? kRepairShare * seconds : 0.0;
  const std::vector<std::vector<int>> neighbours = cell_neighbours(m, tp);
  std::vector<double> best;
  for (int rings : kRepairRings) {
    const double left = budget - clock.seconds();
    if (seconds > 0 && left <= 0) break;
    const solve::RestrictedProgram sub =
        solve::restrict_program(m.program, fixed_outside(m, tp, neighbours, seeds, rings), rounded);
    if (sub.program.num_variables() > kRepairLargest * m.program.num_variables()) break;
    if (!sub.consistent) continue;
    solve::MilpOptions o;
    o.node_limit = kRepairNodes;   // the same point on a fast or a loaded machine
    o.cuts_and_heuristics = true;  // a small program
    o.time_limit = seconds > 0 ? left : 0.0;
    const solve::MilpResult r = solve::solve_program(sub.program, o);
    core::logger().debug("selection: {} fractional cells, {} rings: {} variables, {} rows, {} ({:.6f} against {:.6f})",
                         seeds.size(), rings, sub.program.num_variables(), sub.program.num_rows(),
                         solve::status_name(r.status), r.x.empty() ? 0.0 : r.objective + sub.constant, bound);
    if (r.x.empty()) continue;
    std::vector<double> full = sub.expand(rounded, r.x);
    if (!m.program.satisfied_by(full)) continue;
    if (best.empty() || m.program.objective(full) < m.program.objective(best)) best = std::move(full);
    if (solve::meets_bound(m.program.objective(best), bound)) break;
  }
  return best;
}

}  // namespace

Selection select_facets_to_pad(const core::HexMesh& mesh, const std::vector<std::uint8_t>& hard,
                               const SelectionOptions& options) {
  const core::Stopwatch clock;
  const Topology tp = detail::build_topology(mesh);
  if (static_cast<int>(hard.size()) != tp.t.num_faces())
    throw core::InputError(fmt::format("hard set has {} flags for a mesh of {} facets", hard.size(), tp.t.num_faces()));
  for (int f = 0; f < tp.t.num_faces(); ++f)
    if (hard[f] && !tp.t.faces.is_boundary(f))
      throw core::InputError(fmt::format("hard set: facet {} is not on the boundary", f));
  if (!(options.lambda >= 0) || !(options.time_limit >= 0))
    throw core::InputError(fmt::format("selection: lambda and the time limit must be >= 0 (got {}, {})", options.lambda,
                                       options.time_limit));
  if (std::none_of(hard.begin(), hard.end(), [](std::uint8_t h) { return h != 0; })) {
    // Nothing must be padded: the empty set is valid and costs 0, the least any set costs.
    Selection none;
    none.facets.assign(tp.t.num_faces(), 0);
    none.optimal = true;
    none.solver = "none (the empty set)";
    none.seconds = clock.seconds();
    return none;
  }
  const Model m = build_model(mesh, tp, hard, options);
  solve::MilpOptions mo;
  mo.time_limit = options.time_limit;
  mo.start = surface_start(m, tp);
  const core::Stopwatch pillow_clock;
  if (std::vector<double> pillow = pillow_start(m, mesh, tp, hard); !pillow.empty()) {
    core::logger().debug("selection: starts cost {:.6f} (every surface facet) and {:.6f} (HF's hexes as a pillow, "
                         "{:.2f} s)",
                         m.program.objective(mo.start), m.program.objective(pillow), pillow_clock.seconds());
    if (m.program.objective(pillow) < m.program.objective(mo.start)) mo.start = std::move(pillow);
  }
  // Without a search every program counts as too large to search.
  mo.branch_and_cut_max_variables = options.search ? kBranchAndCutLargest : 1;
  const core::Stopwatch solve_clock;
  mo.round = [&](const std::vector<double>& relaxation) {
    const double left = options.time_limit > 0 ? std::max(options.time_limit - solve_clock.seconds(), 1e-3) : 0.0;
    return repair_rounding(m, tp, relaxation, left);
  };
  const solve::MilpResult r = solve::solve_program(m.program, mo);
  if (r.x.empty())
    throw core::SolverError(fmt::format("selective padding: CBC found no solution ({})", solve::status_name(r.status)));

  Selection s;
  s.facets.assign(tp.t.num_faces(), 0);
  std::vector<double> x(tp.t.num_faces(), 0.0);
  for (int f = 0; f < tp.t.num_faces(); ++f) {
    const auto [a, b] = facet_cells(tp, m.v, f);
    const auto y = [&](int var) { return var >= 0 ? std::lround(r.x[var]) : 0L; };
    const bool cut = y(a) != y(b);
    s.facets[f] = cut ? 1 : 0;
    x[f] = cut ? 1.0 : 0.0;
  }
  std::vector<double> te, tv;
  turns_of(m, x, te, tv);
  for (std::size_t e = 0; e < te.size(); ++e) s.edge_turns += (m.v.te[e] >= 0 && te[e] > 0.5) ? 1 : 0;
  for (std::size_t w = 0; w < tv.size(); ++w) s.vertex_turns += (m.v.tv[w] >= 0 && tv[w] > 0.5) ? 1 : 0;
  s.selected = static_cast<int>(std::count(s.facets.begin(), s.facets.end(), 1));
  s.objective = r.objective;
  s.optimal = r.status == solve::MilpStatus::Optimal;
  s.gap = s.optimal || r.objective == 0 ? 0.0 : std::max(0.0, (r.objective - r.bound) / std::abs(r.objective));
  s.solver = r.solver;
  s.variables = m.program.num_variables();
  s.rows = m.program.num_rows();
  s.seconds = clock.seconds();
  return s;
}

}  // namespace polycube::padding
