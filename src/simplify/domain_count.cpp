#include "simplify/domain_count.h"

#include "core/topology.h"
#include "quality/domains.h"

#include <algorithm>

namespace polycube::simplify {

core::HexMesh plane_grid(const CornerSystem& sys, const structure::PolycubeStructure& s,
                         const std::array<std::vector<double>, 3>& values) {
  std::array<std::vector<double>, 3> g;
  for (int a = 0; a < 3; ++a) {
    g[a] = values[a];
    std::sort(g[a].begin(), g[a].end());
    g[a].erase(std::unique(g[a].begin(), g[a].end()), g[a].end());
  }
  const int nx = static_cast<int>(g[0].size()), ny = static_cast<int>(g[1].size()), nz = static_cast<int>(g[2].size());
  core::HexMesh mesh;
  if (nx < 2 || ny < 2 || nz < 2) return mesh;
  // x-chart rectangles at their coordinates
  struct Rect {
    double x, y0, y1, z0, z1;
  };
  std::vector<Rect> rects;
  (void)s;
  for (int r : sys.x_rectangles)
    if (const auto& b = sys.boxes[r]; true)
      rects.push_back({values[0][b.lo[0]], values[1][b.lo[1]], values[1][b.hi[1]], values[2][b.lo[2]], values[2][b.hi[2]]});
  std::vector<char> inside(static_cast<std::size_t>((nx - 1) * (ny - 1) * (nz - 1)), 0);
  auto cid = [&](int i, int j, int k) { return (static_cast<std::size_t>(k) * (ny - 1) + j) * (nx - 1) + i; };
  std::vector<double> xs;
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j) {
      const double yc = 0.5 * (g[1][j] + g[1][j + 1]), zc = 0.5 * (g[2][k] + g[2][k + 1]);
      xs.clear();
      for (const Rect& r : rects)
        if (r.y0 <= yc && yc < r.y1 && r.z0 <= zc && zc < r.z1) xs.push_back(r.x);
      std::sort(xs.begin(), xs.end());
      for (int i = 0; i + 1 < nx; ++i) {
        const double xc = 0.5 * (g[0][i] + g[0][i + 1]);
        const auto beyond = xs.end() - std::upper_bound(xs.begin(), xs.end(), xc);
        inside[cid(i, j, k)] = (beyond % 2) == 1;
      }
    }
  std::vector<int> vid(static_cast<std::size_t>(nx * ny * nz), -1);
  auto vindex = [&](int i, int j, int k) {
    int& v = vid[(static_cast<std::size_t>(k) * ny + j) * nx + i];
    if (v < 0) {
      v = static_cast<int>(mesh.points.size());
      mesh.points.emplace_back(g[0][i], g[1][j], g[2][k]);
    }
    return v;
  };
  for (int k = 0; k + 1 < nz; ++k)
    for (int j = 0; j + 1 < ny; ++j)
      for (int i = 0; i + 1 < nx; ++i)
        if (inside[cid(i, j, k)])
          mesh.cells.push_back({vindex(i, j, k), vindex(i + 1, j, k), vindex(i + 1, j + 1, k), vindex(i, j + 1, k),
                                vindex(i, j, k + 1), vindex(i + 1, j, k + 1), vindex(i + 1, j + 1, k + 1),
                                vindex(i, j + 1, k + 1)});
  return mesh;
}

DomainCount count_domains(const CornerSystem& sys, const structure::PolycubeStructure& s,
                          const std::array<std::vector<double>, 3>& values) {
  DomainCount dc;
  const core::HexMesh hex = plane_grid(sys, s, values);
  dc.hexes = hex.num_cells();
  if (dc.hexes == 0) return dc;
  quality::DomainOptions o;
  o.keep_labels = false;
  dc.hex_domains = quality::hex_domains(hex, o).domains;
  const core::HexBoundary b = core::boundary(hex);
  dc.quads = b.surface.num_cells();
  dc.quad_domains = quality::quad_domains(b.surface, o).domains;
  return dc;
}

}  // namespace polycube::simplify
