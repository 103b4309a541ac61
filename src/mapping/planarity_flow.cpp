//! Foldover-free planarity flow (see planarity_flow.h).
#include "mapping/planarity_flow.h"

#include "core/errors.h"
#include "core/log.h"
#include "core/stopwatch.h"
#include "mapping/ghost_tets.h"
#include "solve/untangle.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace polycube::mapping {

namespace {

using core::Vec3;

//! Volume and mean edge length around each vertex (model): the attraction scale V_v / h_v².
struct VertexScales {
  std::vector<double> volume, length;
};

VertexScales vertex_scales(const core::TetMesh& mesh) {
  const int nv = mesh.num_points();
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
  return {std::move(vol), std::move(len)};
}

//! The soft attractions of the flow: one per chart vertex (along its charts' axes), then one
//! per ghost apex (along its label's axis), with their base weights V_v / h_v²; retarget()
//! moves every target onto the current planes.
class Attractions {
 public:
  Attractions(const std::vector<int>& vertex_group, int num_groups, const std::vector<core::Tri>& boundary,
              double ghost_height, VertexScales scales)
      : group_(vertex_group), boundary_(boundary), h_(ghost_height), scales_(std::move(scales)),
        plane_(static_cast<std::size_t>(num_groups)) {}

  //! Attractions of the chart vertices (call first).
  void add_vertices(int nv, std::vector<solve::Attraction>& attr) {
    base_of_.assign(static_cast<std::size_t>(nv), 0.0);
    for (int v = 0; v < nv; ++v) {
      Vec3 mask = Vec3::Zero();
      for (int d = 0; d < 3; ++d) mask[d] = group_[3 * static_cast<std::size_t>(v) + d] >= 0 ? 1.0 : 0.0;
      if (mask.isZero()) continue;
      solve::Attraction a;
      a.vertex = v;
      a.axis_weights = mask;
      attr.push_back(a);
      base_.push_back(scales_.volume[v] / (scales_.length[v] * scales_.length[v]));
      base_of_[v] = base_.back();
    }
    vertex_attractions_ = attr.size();
  }

  //! Attraction of the apex (vertex `apex`) of the ghost tet of boundary triangle f.
  void add_ghost(int f, int label, int apex, std::vector<solve::Attraction>& attr) {
    const core::Tri& t = boundary_[f];
    const int a = label / 2;
    solve::Attraction g;
    g.vertex = apex;
    g.axis_weights = Vec3::Unit(a);
    attr.push_back(g);
    base_.push_back((base_of_[t[0]] + base_of_[t[1]] + base_of_[t[2]]) / 3.0);
    ghost_.push_back({f, a, label % 2 == 0 ? 1.0 : -1.0});
  }

  //! Plane of every group = mean coordinate of its entries; targets and weights follow.
  void retarget(const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr, double weight) {
    std::fill(plane_.begin(), plane_.end(), 0.0);
    std::vector<double> n(plane_.size(), 0.0);
    for (std::size_t i = 0; i < group_.size(); ++i)
      if (group_[i] >= 0) {
        plane_[group_[i]] += x[static_cast<Eigen::Index>(i)];
        n[group_[i]] += 1.0;
      }
    for (std::size_t g = 0; g < plane_.size(); ++g) plane_[g] = n[g] > 0 ? plane_[g] / n[g] : 0.0;
    residual_ = 0.0;
    for (std::size_t k = 0; k < attr.size(); ++k) {
      if (k >= vertex_attractions_) {  // ghost apex: h above its triangle's plane along the label
        const Ghost& gh = ghost_[k - vertex_attractions_];
        const int g = group_[3 * static_cast<std::size_t>(boundary_[gh.tri][0]) + gh.axis];
        attr[k].target = x.segment<3>(3 * attr[k].vertex);
        attr[k].target[gh.axis] = plane_[g] + gh.sign * h_;
        attr[k].weight = weight * base_[k];
        continue;
      }
      const int v = attr[k].vertex;
      for (int d = 0; d < 3; ++d) {
        const int g = group_[3 * static_cast<std::size_t>(v) + d];
        attr[k].target[d] = g >= 0 ? plane_[g] : x[3 * v + d];
        if (g >= 0) residual_ = std::max(residual_, std::abs(x[3 * v + d] - plane_[g]) / scales_.length[v]);
      }
      attr[k].weight = weight * base_[k];
    }
  }

  //! Max distance of a chart vertex to its plane / local edge length, at the last retarget().
  [[nodiscard]] double residual() const { return residual_; }

 private:
  struct Ghost {
    int tri, axis;
    double sign;
  };
  const std::vector<int>& group_;
  const std::vector<core::Tri>& boundary_;
  double h_;
  VertexScales scales_;
  std::vector<double> plane_;
  std::vector<double> base_;     // V_v / h_v² of each attraction
  std::vector<double> base_of_;  // ... of each vertex
  std::vector<Ghost> ghost_;     // attractions after the vertices' ones: one per ghost apex
  std::size_t vertex_attractions_ = 0;
  double residual_ = 0.0;
};

void check_inputs(const core::TetMesh& mesh, const std::vector<Vec3>& start, const std::vector<int>& vertex_group,
                  int num_groups, const std::vector<core::Tri>& boundary, const std::vector<int>& labels) {
  const int nv = mesh.num_points();
  if (start.size() != mesh.points.size() || vertex_group.size() != 3 * static_cast<std::size_t>(nv))
    throw core::InputError(fmt::format("planarity flow: {} start positions and {} group entries for {} vertices",
                                       start.size(), vertex_group.size(), nv));
  for (int g : vertex_group)
    if (g >= num_groups) throw core::InputError("planarity flow: chart group out of range");
  if (labels.size() != boundary.size())
    throw core::InputError(fmt::format("planarity flow: {} labels for {} boundary triangles", labels.size(), boundary.size()));
  for (std::size_t f = 0; f < boundary.size(); ++f) {
    for (int v : boundary[f])
      if (v < 0 || v >= nv) throw core::InputError("planarity flow: boundary vertex out of range");
    if (labels[f] < 0 || labels[f] > 5) throw core::InputError("planarity flow: label out of range");
  }
}

}  // namespace

PlanarityFlowResult planarity_flow(const core::TetMesh& mesh, const std::vector<core::Vec3>& start,
                                   const std::vector<int>& vertex_group, int num_groups,
                                   const std::vector<core::Tri>& boundary, const std::vector<int>& labels,
                                   double ghost_height, const PlanarityFlowOptions& o) {
  const core::Stopwatch clock;
  check_inputs(mesh, start, vertex_group, num_groups, boundary, labels);
  const int nv = mesh.num_points();
  const int nb = ghost_height > 0 ? static_cast<int>(boundary.size()) : 0;
  solve::UntangleOptions uo;
  uo.max_iterations = o.iterations;
  uo.newton_steps = o.newton_steps;
  uo.volume_weight = o.volume_weight;
  uo.initial_epsilon = o.initial_epsilon;
  uo.tolerance = 0.0;  // the targets move: the hook decides when to stop
  Attractions attractions(vertex_group, num_groups, boundary, ghost_height, vertex_scales(mesh));
  attractions.add_vertices(nv, uo.attractions);
  PlanarityFlowResult res;
  uo.on_iteration = [&](int outer, const Eigen::VectorXd& x, std::vector<solve::Attraction>& attr) {
    const double w = std::min(o.max_weight, o.initial_weight * std::pow(o.growth, outer + 1));
    attractions.retarget(x, attr, w);
    res.iterations = outer + 1;
    core::logger().debug("planarity flow: iteration {}: plane residual {:.3g} edge lengths, weight {:.3g}", outer,
                         attractions.residual(), w);
    return attractions.residual() > o.tolerance;
  };
  // Ghost tets (ghost_tets.h): the start's triangle + apex at h along the label from the
  // triangle's centroid (the charts are not planar yet), attracted to h above the chart plane.
  const std::vector<core::Tri> ghost_tris(boundary.begin(), boundary.begin() + nb);
  const std::vector<int> ghost_labels(labels.begin(), labels.begin() + nb);
  const GhostTets ghosts = ghost_tets(mesh.points, ghost_tris, ghost_labels, ghost_height, nv);
  std::vector<core::Vec3> ref = mesh.points;
  std::vector<core::Tet> tets = mesh.cells;
  ref.insert(ref.end(), ghosts.reference.begin(), ghosts.reference.end());
  tets.insert(tets.end(), ghosts.tets.begin(), ghosts.tets.end());
  Eigen::VectorXd y = solve::flatten(start);
  y.conservativeResize(3 * static_cast<Eigen::Index>(nv + nb));
  for (int f = 0; f < nb; ++f) {
    y.segment<3>(3 * (nv + f)) = ghost_apex(start, boundary[f], labels[f], ghost_height, GhostBase::Centroid, ApexLift::FromBase);
    attractions.add_ghost(f, labels[f], nv + f, uo.attractions);
  }
  attractions.retarget(y, uo.attractions, o.initial_weight);
  const solve::TetElements el = solve::reference_elements(ref, tets);
  const solve::UntangleResult ur = solve::untangle(el, solve::identity_reduction(nv + nb), y, uo);
  res.points = solve::unflatten(y.head(3 * static_cast<Eigen::Index>(nv)));
  std::vector<solve::Attraction> final_targets = uo.attractions;
  attractions.retarget(y, final_targets, 0.0);
  res.residual = attractions.residual();
  res.inverted = ur.inverted_after;
  res.seconds = clock.seconds();
  return res;
}

}  // namespace polycube::mapping
