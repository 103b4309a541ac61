#include "construct/labeling.h"

#include "construct/labeling_detail.h"
#include "construct/surface_graph.h"
#include "core/errors.h"
#include "core/log.h"
#include "solve/max_flow.h"

#include <cmath>
#include <Eigen/Geometry>

namespace polycube::construct {

namespace {

using detail::Energy;
using detail::SurfaceGraph;

//! Triangles with n·axis at most this never switch to that axis's label in an expansion move.
constexpr double kCandidateDot = -0.2;

}  // namespace

int smooth_chart_boundaries(const core::TriMesh& surface, std::vector<int>& labels, int max_rounds) {
  PC_REQUIRE(labels.size() == surface.cells.size(), "smooth_chart_boundaries: one label per triangle");
  const SurfaceGraph g = detail::build_surface_graph(surface);
  int changes = 0;
  for (int round = 0; round < max_rounds; ++round) {
    int changed = 0;
    for (int t = 0; t < g.num_triangles; ++t) {
      std::array<int, 3> nl{};
      for (int k = 0; k < 3; ++k) nl[k] = labels[g.other(g.triangle_edges[t][k], t)];
      for (int k = 0; k < 3; ++k) {
        const int l = nl[k];
        if (l == labels[t]) continue;
        const int same = (nl[0] == l) + (nl[1] == l) + (nl[2] == l);
        if (same >= 2) {
          labels[t] = l;
          ++changed;
          break;
        }
      }
    }
    changes += changed;
    if (changed == 0) break;
  }
  return changes;
}

LabelingResult graph_cut_labeling(const core::TriMesh& surface, const LabelingOptions& opt) {
  const SurfaceGraph g = detail::build_surface_graph(surface);
  const Energy en = detail::make_energy(g, opt);
  LabelingResult r;
  r.compactness = opt.compactness;
  // Start from the best axis per triangle.
  r.labels.resize(static_cast<std::size_t>(g.num_triangles));
  for (int t = 0; t < g.num_triangles; ++t) {
    int best = 0;
    for (int l = 1; l < kNumLabels; ++l)
      if (en.data[t][l] < en.data[t][best]) best = l;
    r.labels[t] = best;
  }
  double energy = en.total(g, r.labels);
  const double tol = 1e-9 * std::max(1.0, std::abs(energy));
  if (opt.compactness > 0.0) {
    for (r.cycles = 0; r.cycles < opt.max_cycles;) {
      ++r.cycles;
      bool improved = false;
      for (int alpha = 0; alpha < kNumLabels; ++alpha) {
        // Binary problem: x_t = 0 keeps the label, x_t = 1 (sink side) switches to alpha.
        // Only triangles not facing away from alpha take part (the others keep their label:
        // switching them could only raise the energy a lot); this halves the graph.
        std::vector<int> node(static_cast<std::size_t>(g.num_triangles), -1);
        std::vector<int> tri;
        const core::Vec3 dir = label_direction(alpha);
        for (int t = 0; t < g.num_triangles; ++t)
          if (r.labels[t] != alpha && (opt.data_normals.empty() ? g.normals[t] : opt.data_normals[t]).dot(dir) > kCandidateDot) {
            node[t] = static_cast<int>(tri.size());
            tri.push_back(t);
          }
        if (tri.empty()) continue;
        solve::FlowNetwork net(static_cast<int>(tri.size()));
        for (std::size_t i = 0; i < tri.size(); ++i) {
          const int t = tri[i];
          net.add_unary(static_cast<int>(i), en.data[t][r.labels[t]], en.data[t][alpha]);
        }
        for (std::size_t e = 0; e < g.edges.size(); ++e) {
          const int p = g.edge_triangles[e][0];
          const int q = g.edge_triangles[e][1];
          const int np = node[p];
          const int nq = node[q];
          if (np < 0 && nq < 0) continue;
          const int fp = r.labels[p];
          const int fq = r.labels[q];
          const double w = en.edge_weight[e];
          if (np < 0 || nq < 0) {
            // One side is fixed at its label f: a unary term on the other side.
            const int f = np < 0 ? fp : fq;
            const int fv = np < 0 ? fq : fp;
            net.add_unary(np < 0 ? nq : np, f != fv ? w : 0.0, f != alpha ? w : 0.0);
            continue;
          }
          // Potts: E(0,0)=w[fp!=fq], E(0,1)=w[fp!=a], E(1,0)=w[a!=fq], E(1,1)=0.
          const double a00 = fp != fq ? w : 0.0;
          const double b01 = fp != alpha ? w : 0.0;
          const double c10 = fq != alpha ? w : 0.0;
          // E = A + (C-A) x_p + (D-C) x_q + (B+C-A-D)(1-x_p) x_q
          net.add_unary(np, 0.0, c10 - a00);
          net.add_unary(nq, 0.0, -c10);
          const double pq = b01 + c10 - a00;
          if (pq > 0.0) net.add_edge(np, nq, pq, 0.0);
        }
        const auto cut = solve::max_flow(net);
        std::vector<int> next = r.labels;
        for (std::size_t i = 0; i < tri.size(); ++i)
          if (cut.on_sink[i]) next[tri[i]] = alpha;
        const double e_next = en.total(g, next);
        if (e_next < energy - tol) {
          energy = e_next;
          r.labels.swap(next);
          ++r.moves;
          improved = true;
        }
      }
      if (!improved) break;
    }
  }
  if (opt.smoothing_rounds > 0) {
    const int changed = smooth_chart_boundaries(surface, r.labels, opt.smoothing_rounds);
    if (changed > 0) energy = en.total(g, r.labels);
    core::logger().debug("labeling: boundary smoothing changed {} triangles", changed);
  }
  r.energy = energy / std::max(1, g.num_triangles);
  core::logger().debug("labeling: energy {:.6g} after {} cycles, {} moves", r.energy, r.cycles, r.moves);
  return r;
}

double labeling_fidelity(const core::TriMesh& surface, const std::vector<int>& labels) {
  PC_REQUIRE(labels.size() == surface.cells.size(), "labeling_fidelity: one label per triangle");
  double sum = 0.0;
  double area = 0.0;
  for (std::size_t t = 0; t < surface.cells.size(); ++t) {
    const auto& c = surface.cells[t];
    const core::Vec3 n =
        (surface.points[c[1]] - surface.points[c[0]]).cross(surface.points[c[2]] - surface.points[c[0]]);
    const double a = 0.5 * n.norm();
    if (a <= 0.0) continue;
    PC_REQUIRE(labels[t] >= 0 && labels[t] < kNumLabels, "labeling_fidelity: label out of range");
    sum += a * (1.0 - (n / (2.0 * a)).dot(label_direction(labels[t])));
    area += a;
  }
  return area > 0.0 ? sum / area : 0.0;
}

namespace detail {

//! Energy terms precomputed once.
Energy make_energy(const SurfaceGraph& g, const LabelingOptions& opt) {
  Energy en;
  const double mean_area = g.total_area / std::max(1, g.num_triangles);
  double mean_len = 0.0;
  for (double l : g.edge_lengths) mean_len += l;
  mean_len /= std::max<std::size_t>(1, g.edge_lengths.size());
  en.data.resize(static_cast<std::size_t>(g.num_triangles));
  PC_REQUIRE(opt.penalty.empty() || static_cast<int>(opt.penalty.size()) == g.num_triangles,
             "labeling: penalty needs one entry per triangle");
  PC_REQUIRE(opt.data_normals.empty() || static_cast<int>(opt.data_normals.size()) == g.num_triangles,
             "labeling: data_normals needs one entry per triangle");
  for (int t = 0; t < g.num_triangles; ++t) {
    const double w = mean_area > 0.0 ? g.areas[t] / mean_area : 1.0;
    for (int l = 0; l < kNumLabels; ++l) {
      const core::Vec3& n = opt.data_normals.empty() ? g.normals[t] : opt.data_normals[t];
      en.data[t][l] = w * (1.0 - n.dot(label_direction(l)));
      if (!opt.penalty.empty()) en.data[t][l] += w * opt.penalty[t][l];
    }
  }
  en.edge_weight.resize(g.edges.size());
  const double s2 = 2.0 * opt.sigma * opt.sigma;
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const auto& tt = g.edge_triangles[e];
    const double d = 1.0 - g.normals[tt[0]].dot(g.normals[tt[1]]);
    const double len = mean_len > 0.0 ? g.edge_lengths[e] / mean_len : 1.0;
    en.edge_weight[e] = opt.compactness * len * (s2 > 0.0 ? std::exp(-d * d / s2) : 0.0);
  }
  return en;
}


}  // namespace detail

}  // namespace polycube::construct
