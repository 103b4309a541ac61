//! Foldover-free planarity flow (see planarity_flow.h).
#include "construct/planarity_flow.h"

#include "core/errors.h"
#include "core/log.h"
#include "solve/untangle.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace polycube::construct {

PlanarityFlowResult planarity_flow(const core::TetMesh& mesh, const std::vector<core::Vec3>& start,
                                   const std::vector<int>& vertex_group, int num_groups,
                                   const std::vector<core::Tri>& boundary, const std::vector<int>& labels,
                                   double ghost_height, const PlanarityFlowOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const int nv = mesh.num_points();
  if (start.size() != mesh.points.size() || vertex_group.size() != 3 * static_cast<std::size_t>(nv))
    throw core::InputError(fmt::format("planarity flow: {} start positions and {} group entries for {} vertices",
                                       start.size(), vertex_group.size(), nv));
  for (int g : vertex_group)
    if (g >= num_groups) throw core::InputError("planarity flow: chart group out of range");
  if (labels.size() != boundary.size())
    throw core::InputError(fmt::format("planarity flow: {} labels for {} boundary triangles", labels.size(), boundary.size()));
  const int nb = ghost_height > 0 ? static_cast<int>(boundary.size()) : 0;

  // Volume and mean edge length around each vertex (model): the attraction scale V_v / h_v².
  std::vector<double> vol(static_cast<std::size_t>(nv), 0.0), len(static_cast<std::size_t>(nv), 0.0),
      cnt(static_cast<std::size_t>(nv), 0.0);
  const auto& X = mesh.points;
  for (const auto& c : mesh.cells) {
    const double v = std::abs((X[c[1]] - X[c[0]]).dot((X[c[2]] - X[c[0]]).cross(X[c[3]] - X[c[0]]))) / 24.0;
    for (int i = 0; i < 4; ++i) {
      vol[c[i]] += v;
      for (int j = 0; j < 4; ++j)
        if (j != i) {
          len[c[i]] += (X[c[i]] - X[c[j]]).norm();
          cnt[c[i]] += 1.0;
        }
    }
  }
  for (int v = 0; v < nv; ++v) len[v] = cnt[v] > 0 ? len[v] / cnt[v] : 1.0;

  solve::UntangleOptions uo;
  uo.max_iterations = o.iterations;
  uo.newton_steps = o.newton_steps;
  uo.volume_weight = o.volume_weight;
  uo.initial_epsilon = o.initial_epsilon;
  uo.tolerance = 0.0;  // the targets move: the hook decides when to stop
  std::vector<double> base;  // V_v / h_v² of each attraction
  std::vector<double> base_of(static_cast<std::size_t>(nv), 0.0);
  struct Ghost {
    int tri, axis;
    double sign;
  };
  std::vector<Ghost> ghost;  // attractions after the vertices' ones: one per ghost apex
  for (int v = 0; v < nv; ++v) {
    core::Vec3 mask = core::Vec3::Zero();
    for (int d = 0; d < 3; ++d) mask[d] = vertex_group[3 * static_cast<std::size_t>(v) + d] >= 0 ? 1.0 : 0.0;
    if (mask.isZero()) continue;
    solve::Attraction a;
    a.vertex = v;
    a.axis_weights = mask;
    uo.attractions.push_back(a);
    base.push_back(vol[v] / (len[v] * len[v]));
    base_of[v] = base.back();
  }
  const std::size_t n_vertex_attr = uo.attractions.size();
  // Plane of every group = mean coordinate of its entries; targets and weights follow.
  std::vector<double> plane(static_cast<std::size_t>(num_groups));
  double residual = 0.0;
  auto retarget = [&](const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr, double weight) {
    std::fill(plane.begin(), plane.end(), 0.0);
    std::vector<double> n(static_cast<std::size_t>(num_groups), 0.0);
    for (std::size_t i = 0; i < vertex_group.size(); ++i)
      if (vertex_group[i] >= 0) {
        plane[vertex_group[i]] += x[static_cast<Eigen::Index>(i)];
        n[vertex_group[i]] += 1.0;
      }
    for (int g = 0; g < num_groups; ++g) plane[g] = n[g] > 0 ? plane[g] / n[g] : 0.0;
    residual = 0.0;
    for (std::size_t k = 0; k < attr.size(); ++k) {
      if (k >= n_vertex_attr) {  // ghost apex: h above its triangle's plane along the label
        const Ghost& gh = ghost[k - n_vertex_attr];
        const int g = vertex_group[3 * static_cast<std::size_t>(boundary[gh.tri][0]) + gh.axis];
        attr[k].target = x.segment<3>(3 * attr[k].vertex);
        attr[k].target[gh.axis] = plane[g] + gh.sign * ghost_height;
        attr[k].weight = weight * base[k];
        continue;
      }
      const int v = attr[k].vertex;
      for (int d = 0; d < 3; ++d) {
        const int g = vertex_group[3 * static_cast<std::size_t>(v) + d];
        attr[k].target[d] = g >= 0 ? plane[g] : x[3 * v + d];
        if (g >= 0) residual = std::max(residual, std::abs(x[3 * v + d] - plane[g]) / len[v]);
      }
      attr[k].weight = weight * base[k];
    }
  };
  Eigen::VectorXd y = solve::flatten(start);
  PlanarityFlowResult res;
  uo.on_iteration = [&](int outer, const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr) {
    const double w = std::min(o.max_weight, o.initial_weight * std::pow(o.growth, outer + 1));
    retarget(x, attr, w);
    res.iterations = outer + 1;
    core::logger().debug("planarity flow: iteration {}: plane residual {:.3g} edge lengths, weight {:.3g}", outer,
                         residual, w);
    return residual > o.tolerance;
  };
  // Ghost tets: reference = model triangle + apex at h along its normal; start = the start's
  // triangle + apex at h along the label (positive exactly when the triangle faces its label).
  std::vector<core::Vec3> ref = mesh.points;
  std::vector<core::Tet> tets = mesh.cells;
  y.conservativeResize(3 * static_cast<Eigen::Index>(nv + nb));
  for (int f = 0; f < nb; ++f) {
    const core::Tri& t = boundary[f];
    for (int v : t)
      if (v < 0 || v >= nv) throw core::InputError("planarity flow: boundary vertex out of range");
    if (labels[f] < 0 || labels[f] > 5) throw core::InputError("planarity flow: label out of range");
    const core::Vec3 c = (X[t[0]] + X[t[1]] + X[t[2]]) / 3.0;
    ref.push_back(c + ghost_height * (X[t[1]] - X[t[0]]).cross(X[t[2]] - X[t[0]]).normalized());
    tets.push_back({t[0], t[1], t[2], nv + f});
    const int a = labels[f] / 2;
    const double sign = labels[f] % 2 == 0 ? 1.0 : -1.0;
    core::Vec3 apex = (start[t[0]] + start[t[1]] + start[t[2]]) / 3.0;
    apex[a] += sign * ghost_height;
    y.segment<3>(3 * (nv + f)) = apex;
    solve::Attraction g;
    g.vertex = nv + f;
    g.axis_weights = core::Vec3::Unit(a);
    uo.attractions.push_back(g);
    base.push_back((base_of[t[0]] + base_of[t[1]] + base_of[t[2]]) / 3.0);
    ghost.push_back({f, a, sign});
  }
  retarget(y, uo.attractions, o.initial_weight);
  const solve::TetElements el = solve::reference_elements(ref, tets);
  const solve::UntangleResult ur = solve::untangle(el, solve::identity_reduction(nv + nb), y, uo);
  res.points = solve::unflatten(y.head(3 * static_cast<Eigen::Index>(nv)));
  std::vector<solve::Attraction> dummy = uo.attractions;
  retarget(y, dummy, 0.0);
  res.residual = residual;
  res.inverted = ur.inverted_after;
  res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

}  // namespace polycube::construct
