#include "construct/labeling_repair.h"

#include "construct/labeling_check_detail.h"
#include "construct/labeling_detail.h"
#include "construct/polycube_estimate.h"
#include "core/errors.h"
#include "core/log.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <limits>

namespace polycube::construct {

namespace {

using detail::Energy;
using detail::SurfaceGraph;

//! A candidate move: give `label` to `triangles`.
struct Move {
  std::vector<int> triangles;
  int label = 0;
};

class Repairer {
 public:
  Repairer(const SurfaceGraph& g, const Energy& en, std::vector<int> labels)
      : g_(g), en_(en), labels_(std::move(labels)), mark_(static_cast<std::size_t>(g.num_triangles), 0),
        vmark_(static_cast<std::size_t>(g.num_vertices), 0) {
    for (const int l : labels_) ++label_count_[static_cast<std::size_t>(l)];
  }

  const std::vector<int>& labels() const { return labels_; }

  //! One accepted move, or false when no defect can be improved.
  bool step(const LabelingCheck& check) {
    const int current = detail::defect_count(check);
    for (const Defect& d : check.defects) {
      for (int ring = 0; ring <= max_ring_; ++ring) {
        std::vector<Move> moves = candidates(check, d, ring);
        drop_held(moves);
        if (moves.empty()) continue;
        int best = -1;
        int best_defects = current;
        double best_delta = std::numeric_limits<double>::infinity();
        std::vector<int> defects(moves.size());
        for (std::size_t i = 0; i < moves.size(); ++i) {
          if (drops_a_direction(moves[i])) {
            defects[i] = std::numeric_limits<int>::max();
            continue;
          }
          const double delta = energy_delta(moves[i]);
          const int k = defects[i] = evaluate(moves[i]);
          if (k < best_defects || (k == best_defects && best >= 0 && delta < best_delta)) {
            best = static_cast<int>(i);
            best_defects = k;
            best_delta = delta;
          }
        }
        // Among the moves that remove the most defects, the one whose fast polycube estimate
        // folds the least area wins (then the lowest labeling energy).
        if (best >= 0 && surface_ != nullptr) {
          std::vector<int> tied;
          for (std::size_t i = 0; i < moves.size(); ++i)
            if (defects[i] == best_defects) tied.push_back(static_cast<int>(i));
          if (tied.size() > 1) {
            double best_fold = std::numeric_limits<double>::infinity();
            for (const int i : tied) {
              const double fold = folded_area(moves[i]);
              const double delta = energy_delta(moves[i]);
              if (fold < best_fold || (fold == best_fold && delta < best_delta)) {
                best = i;
                best_fold = fold;
                best_delta = delta;
              }
            }
          }
        }
        if (best >= 0) {
          for (const int t : moves[best].triangles) {
            --label_count_[static_cast<std::size_t>(labels_[t])];
            labels_[t] = moves[best].label;
            ++label_count_[static_cast<std::size_t>(labels_[t])];
          }
          return true;
        }
      }
    }
    return false;
  }

  int max_ring_ = 6;
  const core::TriMesh* surface_ = nullptr;  //!< set: rank tied moves by the polycube estimate
  std::vector<int> held_;                   //!< RepairOptions::held

 private:
  //! Moves without the triangles held to another label; moves left with nothing to change go.
  void drop_held(std::vector<Move>& moves) const {
    if (held_.empty()) return;
    for (Move& m : moves)
      std::erase_if(m.triangles, [&](int t) { return held_[t] >= 0 && held_[t] != m.label; });
    std::erase_if(moves, [&](const Move& m) {
      return std::all_of(m.triangles.begin(), m.triangles.end(), [&](int t) { return labels_[t] == m.label; });
    });
  }

  //! Whether a move takes the last triangles of a label. Every closed polycube has a chart facing
  //! each of the six directions (the surface's extreme points along each axis), so such a move
  //! leads away from every valid labeling, however many defects it seems to remove: taken, it
  //! collapses a coarse shape into one chart with a single defect (a tetrahedron's four faces
  //! all labelled -Y), which no later move can undo.
  bool drops_a_direction(const Move& m) {
    std::array<int, kNumLabels> taken{};
    for (const int t : m.triangles)
      if (labels_[t] != m.label) ++taken[static_cast<std::size_t>(labels_[t])];
    for (std::size_t l = 0; l < taken.size(); ++l)
      if (taken[l] > 0 && taken[l] == label_count_[l]) return true;
    return false;
  }

  //! Area fraction the fast polycube estimate folds after a move (labels restored afterwards).
  double folded_area(const Move& m) {
    saved_.clear();
    for (const int t : m.triangles) {
      saved_.push_back(labels_[t]);
      labels_[t] = m.label;
    }
    const double f = estimate_polycube(*surface_, labels_).flipped_area;
    for (std::size_t i = 0; i < m.triangles.size(); ++i) labels_[m.triangles[i]] = saved_[i];
    return f;
  }

  //! Defect count after applying a move (labels restored afterwards).
  int evaluate(const Move& m) {
    saved_.clear();
    for (const int t : m.triangles) {
      saved_.push_back(labels_[t]);
      labels_[t] = m.label;
    }
    const int k = detail::defect_count(detail::check_labeling(g_, labels_, false));
    for (std::size_t i = 0; i < m.triangles.size(); ++i) labels_[m.triangles[i]] = saved_[i];
    return k;
  }

  //! Energy change of a move (data + Potts terms of the touched triangles).
  double energy_delta(const Move& m) {
    ++stamp_;
    for (const int t : m.triangles) mark_[t] = stamp_;
    double d = 0.0;
    for (const int t : m.triangles) {
      d += en_.data[t][m.label] - en_.data[t][labels_[t]];
      for (const int e : g_.triangle_edges[t]) {
        const int u = g_.other(e, t);
        const int lu_old = labels_[u];
        const int lu_new = mark_[u] == stamp_ ? m.label : labels_[u];
        // Edges inside the move are counted from both sides: halve them.
        const double f = mark_[u] == stamp_ ? 0.5 : 1.0;
        d += f * en_.edge_weight[e] * ((m.label != lu_new) - (labels_[t] != lu_old));
      }
    }
    return d;
  }

  //! Triangles within `ring` vertex rings of a set of vertices (ring 0 = their incident triangles).
  std::vector<int> ring_of_vertices(std::vector<int> verts, int ring) {
    ++stamp_;
    std::vector<int> tris;
    for (const int v : verts) vmark_[v] = stamp_;
    for (int r = 0; r <= ring; ++r) {
      std::vector<int> next;
      for (const int v : verts)
        for (const int t : g_.vertex_triangles[v]) {
          if (mark_[t] == stamp_) continue;
          mark_[t] = stamp_;
          tris.push_back(t);
          for (const int w : g_.triangles_vertices(t))
            if (vmark_[w] != stamp_) {
              vmark_[w] = stamp_;
              next.push_back(w);
            }
        }
      verts.swap(next);
    }
    std::sort(tris.begin(), tris.end());
    return tris;
  }

  std::vector<int> chart_triangles(const LabelingCheck& check, int c) const {
    std::vector<int> tris;
    for (int t = 0; t < g_.num_triangles; ++t)
      if (check.layout.triangle_chart[t] == c) tris.push_back(t);
    return tris;
  }

  std::vector<int> chart_vertices(const std::vector<int>& tris) {
    ++stamp_;
    std::vector<int> verts;
    for (const int t : tris)
      for (const int v : g_.triangles_vertices(t))
        if (vmark_[v] != stamp_) {
          vmark_[v] = stamp_;
          verts.push_back(v);
        }
    return verts;
  }

  //! Vertices on the boundary between charts a and b.
  std::vector<int> shared_boundary_vertices(const LabelingCheck& check, int a, int b) {
    std::vector<int> verts;
    const auto& tc = check.layout.triangle_chart;
    for (std::size_t e = 0; e < g_.edges.size(); ++e) {
      const int c0 = tc[g_.edge_triangles[e][0]];
      const int c1 = tc[g_.edge_triangles[e][1]];
      if ((c0 == a && c1 == b) || (c0 == b && c1 == a)) {
        verts.push_back(g_.edges[e][0]);
        verts.push_back(g_.edges[e][1]);
      }
    }
    std::sort(verts.begin(), verts.end());
    verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
    return verts;
  }

  void add_all_labels(std::vector<Move>& out, const std::vector<int>& tris, int skip = -1) {
    for (int l = 0; l < kNumLabels; ++l) {
      if (l == skip) continue;
      // Skip moves that change nothing.
      if (std::all_of(tris.begin(), tris.end(), [&](int t) { return labels_[t] == l; })) continue;
      out.push_back({tris, l});
    }
  }

  std::vector<Move> candidates(const LabelingCheck& check, const Defect& d, int ring) {
    std::vector<Move> out;
    const auto& L = check.layout;
    switch (d.kind) {
      case DefectKind::TooFewNeighbors: {
        const int c = d.charts[0];
        const std::vector<int> tris = chart_triangles(check, c);
        if (ring == 0) {
          add_all_labels(out, tris, L.chart_label[c]);
        } else {
          // Grow the chart's region by rings, relabel it as a whole.
          add_all_labels(out, ring_of_vertices(chart_vertices(tris), ring - 1));
        }
        break;
      }
      case DefectKind::OppositeNeighbors: {
        const int a = d.charts[0];
        const int b = d.charts[1];
        const std::vector<int> verts = shared_boundary_vertices(check, a, b);
        const std::vector<int> strip = ring_of_vertices(verts, ring);
        const int axis = label_axis(L.chart_label[a]);
        for (int l = 0; l < kNumLabels; ++l)
          if (label_axis(l) != axis) out.push_back({strip, l});
        if (ring == 0) {
          // Relabel the smaller chart as a whole.
          const int small = L.chart_triangles[a] <= L.chart_triangles[b] ? a : b;
          add_all_labels(out, chart_triangles(check, small), L.chart_label[small]);
        }
        break;
      }
      case DefectKind::InvalidCorner: {
        const std::vector<int> region = ring_of_vertices({d.vertex}, ring);
        add_all_labels(out, region);
        // Sectors: the part of one chart inside the region takes another chart's label.
        for (const int c : d.charts) {
          std::vector<int> sector;
          for (const int t : region)
            if (L.triangle_chart[t] == c) sector.push_back(t);
          for (const int c2 : d.charts)
            if (c2 != c && L.chart_label[c2] != L.chart_label[c]) out.push_back({sector, L.chart_label[c2]});
        }
        break;
      }
    }
    return out;
  }

  const SurfaceGraph& g_;
  const Energy& en_;
  std::vector<int> labels_;
  std::vector<int> mark_;
  std::vector<int> vmark_;
  int stamp_ = 0;
  std::vector<int> saved_;
  std::array<int, kNumLabels> label_count_{};  //!< triangles per label
};

}  // namespace

CutAndRepair cut_and_repair(const core::TriMesh& surface, const LabelingOptions& labeling, RepairOptions repair) {
  CutAndRepair out;
  out.cut = graph_cut_labeling(surface, labeling);
  repair.energy = labeling;
  out.repair = repair_labeling(surface, out.cut.labels, repair);
  if (out.repair.valid() && out.repair.moves > 0 && labeling.compactness > 0.0) {
    LabelingOptions looser = labeling;
    looser.compactness = kLooserCut * labeling.compactness;
    LabelingResult cut = graph_cut_labeling(surface, looser);
    if (check_labeling(surface, cut.labels).valid()) {
      core::logger().info(
          "labeling: the cut at compactness {:.3g} is valid as it is; the one at {:.3g} needed {} repair move(s)",
          looser.compactness, labeling.compactness, out.repair.moves);
      repair.energy = looser;
      out.repair = repair_labeling(surface, cut.labels, repair);
      out.cut = std::move(cut);
    }
  }
  if (out.repair.valid()) out.repair = relabel_backward_charts(surface, std::move(out.repair), repair);
  return out;
}

RepairResult repair_labeling(const core::TriMesh& surface, const std::vector<int>& labels,
                             const RepairOptions& options) {
  RepairResult r;
  // Validates sizes and ranges.
  const LabelingCheck first = check_labeling(surface, labels);
  r.initial_defects = detail::defect_count(first);
  const SurfaceGraph g = detail::build_surface_graph(surface);
  const Energy en = detail::make_energy(g, options.energy);
  Repairer rep(g, en, labels);
  rep.max_ring_ = std::max(0, options.max_ring);
  if (options.score_by_estimate) rep.surface_ = &surface;
  PC_REQUIRE(options.held.empty() || options.held.size() == labels.size(), "repair_labeling: one held label per triangle");
  rep.held_ = options.held;
  LabelingCheck check = first;
  while (!check.valid() && r.moves < options.max_moves) {
    if (!rep.step(check)) break;
    ++r.moves;
    check = detail::check_labeling(g, rep.labels(), false);
  }
  r.labels = rep.labels();
  r.check = detail::check_labeling(g, r.labels, true);
  core::logger().info("repair: {} defect(s) -> {} after {} move(s)", r.initial_defects,
                      r.check.defects.size(), r.moves);
  return r;
}

namespace {

//! Area-weighted normal of every chart of `layout` (normals: the labeling's, or empty: the surface's).
std::vector<core::Vec3> chart_normals(const core::TriMesh& surface, const ChartLayout& layout,
                                      const std::vector<core::Vec3>& normals) {
  std::vector<core::Vec3> out(static_cast<std::size_t>(layout.num_charts()), core::Vec3::Zero());
  for (std::size_t t = 0; t < surface.cells.size(); ++t) {
    const auto& tri = surface.cells[t];
    const core::Vec3 area_normal =
        0.5 * (surface.points[tri[1]] - surface.points[tri[0]]).cross(surface.points[tri[2]] - surface.points[tri[0]]);
    out[layout.triangle_chart[t]] += normals.empty() ? area_normal : area_normal.norm() * normals[t];
  }
  return out;
}

}  // namespace

std::vector<int> backward_charts(const core::TriMesh& surface, const ChartLayout& layout,
                                 const std::vector<core::Vec3>& normals) {
  PC_REQUIRE(layout.triangle_chart.size() == surface.cells.size() &&
                 (normals.empty() || normals.size() == surface.cells.size()),
             "backward_charts: one chart and normal per triangle");
  const std::vector<core::Vec3> n = chart_normals(surface, layout, normals);
  std::vector<int> out;
  for (int c = 0; c < layout.num_charts(); ++c)
    if (!(n[c].dot(label_direction(layout.chart_label[c])) > 0.0)) out.push_back(c);
  return out;
}

RepairResult relabel_backward_charts(const core::TriMesh& surface, RepairResult rep, const RepairOptions& options) {
  const std::vector<core::Vec3>& normals = options.energy.data_normals;
  std::vector<int> backward = backward_charts(surface, rep.check.layout, normals);
  const std::size_t before = backward.size();
  // One chart at a time, largest first: its labels in the order it faces them (those it faces
  // at all); the first whose repaired labeling is valid with fewer backward charts is kept.
  bool moved = true;
  while (!backward.empty() && moved) {
    moved = false;
    const ChartLayout& L = rep.check.layout;
    const std::vector<core::Vec3> n = chart_normals(surface, L, normals);
    std::stable_sort(backward.begin(), backward.end(),
                     [&](int a, int b) { return L.chart_area[a] > L.chart_area[b]; });
    for (const int c : backward) {
      core::logger().debug("repair: chart {} ({}, {} triangles) faces away: normal sum ({:.4g} {:.4g} {:.4g})", c,
                           label_name(L.chart_label[c]), L.chart_triangles[c], n[c][0], n[c][1], n[c][2]);
      std::vector<int> order;
      for (int l = 0; l < kNumLabels; ++l)
        if (n[c].dot(label_direction(l)) > 0.0) order.push_back(l);
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return n[c].dot(label_direction(a)) > n[c].dot(label_direction(b));
      });
      for (const int l : order) {
        std::vector<int> labels = rep.labels;
        for (std::size_t t = 0; t < labels.size(); ++t)
          if (L.triangle_chart[t] == c) labels[t] = l;
        RepairResult next = repair_labeling(surface, labels, options);
        if (!next.valid()) continue;
        std::vector<int> left = backward_charts(surface, next.check.layout, normals);
        if (left.size() >= backward.size()) continue;
        next.moves += rep.moves;
        next.initial_defects = rep.initial_defects;
        rep = std::move(next);
        backward = std::move(left);
        moved = true;
        break;
      }
      if (moved) break;  // the layout changed: start again from the charts that still face away
    }
  }
  if (before > 0)
    core::logger().info("repair: {} chart(s) faced away from their label: {} left after relabelling", before,
                        backward.size());
  return rep;
}

}  // namespace polycube::construct
