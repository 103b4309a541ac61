//! The polish of the worst hexes (see polish.h).
#include "optimize/polish.h"

#include "core/elements.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "quality/scaled_jacobian.h"

#include <algorithm>
#include <array>
#include <limits>

namespace polycube::optimize {

namespace {

//! Scaled Jacobian of hex h (degenerate: kInvalidScaledJacobian).
double hex_sj(const core::HexMesh& mesh, int h) {
  std::array<core::Vec3, 8> p;
  for (int k = 0; k < 8; ++k) p[k] = mesh.points[mesh.cells[h][k]];
  return quality::hex_scaled_jacobian(p).value;
}

//! The minimum and the sum of the scaled Jacobians of `hexes`.
struct Around {
  double min = std::numeric_limits<double>::infinity();
  double sum = 0;
};

Around around(const core::HexMesh& mesh, const std::vector<int>& hexes) {
  Around a;
  for (int h : hexes) {
    const double s = hex_sj(mesh, h);
    a.min = std::min(a.min, s);
    a.sum += s;
  }
  return a;
}

//! Mean length of the hex edges at vertex v (each edge of each hex around it).
double mean_edge(const core::HexMesh& mesh, int v, const std::vector<int>& hexes) {
  double total = 0;
  int count = 0;
  for (int h : hexes)
    for (int c = 0; c < 8; ++c) {
      if (mesh.cells[h][c] != v) continue;
      for (int n : core::kHexCornerNeighbors[c]) {
        total += (mesh.points[mesh.cells[h][n]] - mesh.points[v]).norm();
        ++count;
      }
    }
  return count > 0 ? total / count : 0.0;
}

//! Pattern search at vertex v (see polish.h); true when it moved. `project`: null for an
//! interior vertex, else what puts a boundary vertex's trial position back on the target.
bool polish_vertex(core::HexMesh& mesh, int v, const std::vector<int>& hexes, const PolishOptions& o,
                   const BoundaryProjector* project) {
  constexpr int kMaxEvaluations = 200;  // a vertex's search ends well before; a bound on its cost
  const Around start = around(mesh, hexes);
  const double edge = mean_edge(mesh, v, hexes);
  const core::Vec3 from = mesh.points[v];
  double best = start.min;
  double step = o.first_step * edge;
  int evaluations = 0;
  while (step > o.last_step * edge && evaluations < kMaxEvaluations) {
    bool improved = false;
    for (int d = 0; d < 6 && !improved; ++d) {
      core::Vec3 delta = core::Vec3::Zero();
      delta[d / 2] = d % 2 == 0 ? step : -step;
      const core::Vec3 here = mesh.points[v];
      core::Vec3 trial = here + delta;
      if (project != nullptr && !(*project)(v, trial)) return false;
      if (trial == here) continue;
      mesh.points[v] = trial;
      const Around a = around(mesh, hexes);
      ++evaluations;
      if (a.min > best + 1e-12 && a.sum >= start.sum) {
        best = a.min;
        improved = true;
      } else {
        mesh.points[v] = here;
      }
    }
    if (!improved) step *= 0.5;
  }
  return mesh.points[v] != from;
}

}  // namespace

PolishResult polish_worst_hexes(core::HexMesh& mesh, const std::vector<char>& fixed, const PolishOptions& o,
                                const BoundaryProjector& boundary) {
  const core::Stopwatch clock;
  PolishResult r;
  const int nh = mesh.num_cells();
  std::vector<double> sj(static_cast<std::size_t>(nh));
  for (int h = 0; h < nh; ++h) sj[h] = hex_sj(mesh, h);
  r.min_before = r.min_after = nh > 0 ? *std::min_element(sj.begin(), sj.end()) : 0.0;
  if (nh == 0 || r.min_before <= 0) return r;

  std::vector<char> held(mesh.points.size(), 0);
  std::vector<char> on_boundary(mesh.points.size(), 0);
  for (int v : core::boundary(mesh).vertex_map) on_boundary[v] = 1;
  if (!boundary) held = on_boundary;
  for (std::size_t v = 0; v < fixed.size() && v < held.size(); ++v) held[v] = held[v] || fixed[v];
  std::vector<std::vector<int>> hexes_of(mesh.points.size());
  for (int h = 0; h < nh; ++h)
    for (int v : mesh.cells[h]) hexes_of[v].push_back(h);

  double lowest = r.min_before;
  for (int sweep = 0; sweep < o.max_sweeps; ++sweep) {
    std::vector<int> candidates;
    for (int h = 0; h < nh; ++h)
      if (sj[h] < lowest + o.band)
        for (int v : mesh.cells[h])
          if (!held[v]) candidates.push_back(v);
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    ++r.sweeps;
    for (int v : candidates) {
      if (!polish_vertex(mesh, v, hexes_of[v], o, on_boundary[v] ? &boundary : nullptr)) continue;
      ++r.moved;
      for (int h : hexes_of[v]) sj[h] = hex_sj(mesh, h);
    }
    const double now = *std::min_element(sj.begin(), sj.end());
    if (now <= lowest + 1e-9) break;
    lowest = now;
  }
  r.min_after = *std::min_element(sj.begin(), sj.end());
  r.seconds = clock.seconds();
  return r;
}

}  // namespace polycube::optimize
