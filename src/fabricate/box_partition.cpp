//! Box partition of a polycube (see box_partition.h).
#include "fabricate/box_partition.h"

#include "core/disjoint_sets.h"
#include "core/errors.h"
#include "mesh/arrangement.h"
#include "mesh/tet_locator.h"
#include "structure/structure.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace polycube::fabricate {

namespace {

using Cell = std::array<int, 3>;

//! More grid cells than this: not a polycube a person would cut into parts.
constexpr long long kMaxCells = 10'000'000;

//! The 4 cells around the grid edge of direction d whose segment index is q[d] and whose
//! plane indices on the two other axes are q[(d+1)%3], q[(d+2)%3]; in order (−,−), (+,−), (+,+),
//! (−,+).
std::array<Cell, 4> edge_cells(int d, const Cell& q) {
  const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
  std::array<Cell, 4> c{q, q, q, q};
  const int o1[4] = {-1, 0, 0, -1}, o2[4] = {-1, -1, 0, 0};
  for (int i = 0; i < 4; ++i) {
    c[i][e1] += o1[i];
    c[i][e2] += o2[i];
  }
  return c;
}

//! How the polycube's boundary runs along a grid edge.
enum class EdgeKind { Plain, Concave, NonManifold };

EdgeKind edge_kind(const OccupancyGrid& g, int d, const Cell& q) {
  const auto c = edge_cells(d, q);
  std::array<bool, 4> in{};
  int n = 0;
  for (int i = 0; i < 4; ++i) n += (in[i] = g.in(c[i])) ? 1 : 0;
  if (n == 3) return EdgeKind::Concave;
  if (n == 2 && in[0] == in[2]) return EdgeKind::NonManifold;
  return EdgeKind::Plain;
}

double cell_volume(const OccupancyGrid& g, const Box& b) {
  double v = 1.0;
  for (int a = 0; a < 3; ++a) v *= g.planes[a][b.hi[a]] - g.planes[a][b.lo[a]];
  return v;
}

//! Refuse polycubes with cells touching along an edge only; count concave edges.
int scan_edges(const OccupancyGrid& g) {
  int concave = 0;
  for (int d = 0; d < 3; ++d) {
    const int e1 = (d + 1) % 3, e2 = (d + 2) % 3;
    Cell q{};
    for (q[d] = 0; q[d] < g.cells(d); ++q[d])
      for (q[e1] = 0; q[e1] <= g.cells(e1); ++q[e1])
        for (q[e2] = 0; q[e2] <= g.cells(e2); ++q[e2]) {
          const EdgeKind k = edge_kind(g, d, q);
          if (k == EdgeKind::NonManifold) {
            Cell p = q;
            throw core::InputError(fmt::format(
                "box partition: the polycube is not a manifold solid: two of its cells touch along "
                "an edge only "
                "(axis {} at polycube ({:.6g}, {:.6g}, {:.6g})); the sweep cannot cut it",
                "xyz"[d], g.planes[0][std::min(p[0], g.cells(0))],
                g.planes[1][std::min(p[1], g.cells(1))], g.planes[2][std::min(p[2], g.cells(2))]));
          }
          concave += k == EdgeKind::Concave ? 1 : 0;
        }
  }
  return concave;
}

//! Per grid face across axis a between cells c (below) and c + e_a: whether it is a cut. The
//! regions of interior faces of each plane that touch a concave edge of that plane.
std::vector<std::vector<std::uint8_t>> cut_faces(const OccupancyGrid& g, int& regions) {
  std::vector<std::vector<std::uint8_t>> cut(3);
  regions = 0;
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    const int nb = g.cells(b), nc = g.cells(c);
    cut[a].assign(g.inside.size(), 0);  // indexed by the cell below the face
    for (int p = 1; p < g.cells(a); ++p) {
      auto face = [&](int u, int v) { return u + nb * v; };
      auto below = [&](int u, int v) {
        Cell x{};
        x[a] = p - 1;
        x[b] = u;
        x[c] = v;
        return x;
      };
      auto interior = [&](int u, int v) {
        Cell x = below(u, v);
        if (!g.in(x)) return false;
        ++x[a];
        return g.in(x);
      };
      core::DisjointSets uf(static_cast<std::size_t>(nb * nc));
      for (int v = 0; v < nc; ++v)
        for (int u = 0; u < nb; ++u) {
          if (!interior(u, v)) continue;
          if (u + 1 < nb && interior(u + 1, v)) uf.unite(face(u, v), face(u + 1, v));
          if (v + 1 < nc && interior(u, v + 1)) uf.unite(face(u, v), face(u, v + 1));
        }
      std::vector<std::uint8_t> touched(static_cast<std::size_t>(nb * nc), 0);
      for (int v = 0; v < nc; ++v)
        for (int u = 0; u < nb; ++u) {
          if (!interior(u, v)) continue;
          // The face's four edges: along b at c-planes v, v+1; along c at b-planes u, u+1.
          bool concave = false;
          for (int s = 0; s < 2 && !concave; ++s) {
            Cell q{};
            q[a] = p;
            q[b] = u;
            q[c] = v + s;
            concave = edge_kind(g, b, q) == EdgeKind::Concave;
            q[b] = u + s;
            q[c] = v;
            concave = concave || edge_kind(g, c, q) == EdgeKind::Concave;
          }
          if (concave) touched[uf.find(face(u, v))] = 1;
        }
      for (int v = 0; v < nc; ++v)
        for (int u = 0; u < nb; ++u) {
          if (!interior(u, v)) continue;
          const int r = uf.find(face(u, v));
          if (touched[r]) cut[a][g.index(below(u, v))] = 1;
          regions += (touched[r] && r == face(u, v)) ? 1 : 0;
        }
    }
  }
  return cut;
}

//! Boxes from a cell labelling: each label's cells must fill its bounding range exactly.
std::vector<Box> boxes_of(const OccupancyGrid& g, const std::vector<int>& label, int count) {
  std::vector<Box> boxes(static_cast<std::size_t>(count));
  std::vector<long long> cells(static_cast<std::size_t>(count), 0);
  for (auto& b : boxes) {
    b.lo = {g.cells(0), g.cells(1), g.cells(2)};
    b.hi = {0, 0, 0};
  }
  for (int k = 0; k < g.cells(2); ++k)
    for (int j = 0; j < g.cells(1); ++j)
      for (int i = 0; i < g.cells(0); ++i) {
        const int l = label[g.index(i, j, k)];
        if (l < 0) continue;
        Box& b = boxes[l];
        const Cell x{i, j, k};
        for (int a = 0; a < 3; ++a) {
          b.lo[a] = std::min(b.lo[a], x[a]);
          b.hi[a] = std::max(b.hi[a], x[a] + 1);
        }
        ++cells[l];
      }
  for (int l = 0; l < count; ++l)
    if (cells[l] != boxes[l].cells()) {
      const Box& b = boxes[l];
      throw core::InputError(
          fmt::format("box partition: the sweep left a region that is not a box (cells [{}, {}) x "
                      "[{}, {}) x [{}, {}) hold {} of "
                      "its {}); the polycube may intersect itself",
                      b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2], cells[l], b.cells()));
    }
  return boxes;
}

//! Call fn(a, x, y) for every grid face across axis a between two inside cells x and y = x + e_a.
template <class Fn>
void for_each_interior_face(const OccupancyGrid& g, Fn fn) {
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < g.cells(2); ++k)
      for (int j = 0; j < g.cells(1); ++j)
        for (int i = 0; i < g.cells(0); ++i) {
          const Cell x{i, j, k};
          Cell y = x;
          ++y[a];
          if (g.in(x) && g.in(y)) fn(a, x, y);
        }
}

//! The union of two boxes when it is a box.
bool union_box(const Box& x, const Box& y, Box& out) {
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    if (x.lo[b] != y.lo[b] || x.hi[b] != y.hi[b] || x.lo[c] != y.lo[c] || x.hi[c] != y.hi[c])
      continue;
    if (x.hi[a] != y.lo[a] && y.hi[a] != x.lo[a]) continue;
    out = x;
    out.lo[a] = std::min(x.lo[a], y.lo[a]);
    out.hi[a] = std::max(x.hi[a], y.hi[a]);
    return true;
  }
  return false;
}

}  // namespace

bool OccupancyGrid::in(std::array<int, 3> c) const {
  for (int a = 0; a < 3; ++a)
    if (c[a] < 0 || c[a] >= cells(a)) return false;
  return inside[index(c)] != 0;
}

double grid_diagonal(const OccupancyGrid& g) {
  double sq = 0.0;
  for (const auto& pl : g.planes)
    if (!pl.empty()) sq += (pl.back() - pl.front()) * (pl.back() - pl.front());
  return std::sqrt(sq);
}

int insert_plane(OccupancyGrid& g, int axis, double coordinate, double relative_tolerance) {
  const double tolerance = relative_tolerance * grid_diagonal(g);
  auto& pl = g.planes[axis];
  const auto it = std::lower_bound(pl.begin(), pl.end(), coordinate - tolerance);
  if (it != pl.end() && *it <= coordinate + tolerance) return static_cast<int>(it - pl.begin());
  const int k = static_cast<int>(it - pl.begin());  // the new plane's index
  const OccupancyGrid old = g;
  pl.insert(it, coordinate);
  g.inside.assign(static_cast<std::size_t>(g.cells(0)) * g.cells(1) * g.cells(2), 0);
  Cell c{};
  for (c[2] = 0; c[2] < g.cells(2); ++c[2])
    for (c[1] = 0; c[1] < g.cells(1); ++c[1])
      for (c[0] = 0; c[0] < g.cells(0); ++c[0]) {
        // Cells past the new plane were one index lower, so the two halves of the cell it
        // crosses both come from that cell; a plane beyond the grid adds a layer outside.
        Cell from = c;
        if (from[axis] >= k) --from[axis];
        g.inside[g.index(c)] = old.in(from) ? 1 : 0;
      }
  return k;
}

void split_boxes(const OccupancyGrid& g, BoxPartition& p, int axis, int plane) {
  const std::size_t n = p.boxes.size();
  for (std::size_t i = 0; i < n; ++i) {
    Box& b = p.boxes[i];
    if (!(b.lo[axis] < plane && plane < b.hi[axis])) continue;
    Box upper = b;
    upper.lo[axis] = plane;
    b.hi[axis] = plane;
    p.boxes.push_back(upper);
  }
  index_boxes(g, p);
}

core::Vec3 box_corner(const OccupancyGrid& grid, const Box& box, int i, int j, int k) {
  return {grid.planes[0][i ? box.hi[0] : box.lo[0]], grid.planes[1][j ? box.hi[1] : box.lo[1]],
          grid.planes[2][k ? box.hi[2] : box.lo[2]]};
}

void index_boxes(const OccupancyGrid& g, BoxPartition& p) {
  p.cell_box.assign(g.inside.size(), -1);
  for (std::size_t id = 0; id < p.boxes.size(); ++id) {
    const Box& b = p.boxes[id];
    for (int k = b.lo[2]; k < b.hi[2]; ++k)
      for (int j = b.lo[1]; j < b.hi[1]; ++j)
        for (int i = b.lo[0]; i < b.hi[0]; ++i) {
          int& owner = p.cell_box[g.index(i, j, k)];
          if (!g.inside[g.index(i, j, k)] || owner >= 0)
            throw core::InputError(
                fmt::format("box partition: box {} {} cell ({}, {}, {})", id,
                            owner >= 0 ? "overlaps another at" : "holds the outside", i, j, k));
          owner = static_cast<int>(id);
        }
  }
  for (std::size_t c = 0; c < g.inside.size(); ++c)
    if (g.inside[c] && p.cell_box[c] < 0)
      throw core::InputError(
          fmt::format("box partition: cell {} inside the polycube is in no box", c));
  std::map<std::tuple<int, int, int, int>, Contact> contacts;  // (a, b, axis, plane)
  for_each_interior_face(g, [&](int a, const Cell& x, const Cell& y) {
    const int ba = p.cell_box[g.index(x)], bb = p.cell_box[g.index(y)];
    if (ba == bb) return;
    auto [it, fresh] = contacts.try_emplace({ba, bb, a, y[a]});
    Contact& c = it->second;
    if (fresh) {
      c.boxes = {ba, bb};
      c.axis = a;
      c.plane = y[a];
      c.lo = y;
      c.hi = y;
      for (int e = 0; e < 3; ++e)
        if (e != a) c.hi[e] = y[e] + 1;
    }
    for (int e = 0; e < 3; ++e)
      if (e != a) {
        c.lo[e] = std::min(c.lo[e], y[e]);
        c.hi[e] = std::max(c.hi[e], y[e] + 1);
      }
  });
  p.contacts.clear();
  for (auto& [key, c] : contacts) p.contacts.push_back(c);
}

OccupancyGrid occupancy_grid(const core::PolycubeMap& map, double tolerance) {
  if (map.tets.empty()) throw core::InputError("box partition: the map has no tets");
  const structure::PolycubeStructure s = structure::extract_structure(map);
  const double absolute = tolerance * core::bounding_box(map.polycube).diagonal();
  const mesh::TetLocator locator(map.tets, map.polycube, absolute);
  const mesh::Arrangement arr = mesh::build_arrangement(s, locator, absolute, kMaxCells);
  OccupancyGrid g;
  g.planes = arr.level;
  g.inside.assign(arr.inside.begin(), arr.inside.end());
  return g;
}

BoxPartition partition_boxes(const OccupancyGrid& g) {
  if (std::none_of(g.inside.begin(), g.inside.end(), [](std::uint8_t v) { return v != 0; }))
    throw core::InputError("box partition: no grid cell lies inside the polycube");
  BoxPartition p;
  p.concave_edges = scan_edges(g);
  const auto cut = cut_faces(g, p.cut_regions);
  core::DisjointSets uf(g.inside.size());
  for_each_interior_face(g, [&](int a, const Cell& x, const Cell& y) {
    if (!cut[a][g.index(x)]) uf.unite(g.index(x), g.index(y));
  });
  std::vector<int> label(g.inside.size(), -1);
  std::vector<int> id_of_root(g.inside.size(), -1);
  int count = 0;
  for (std::size_t c = 0; c < g.inside.size(); ++c) {  // ids in order of the lowest cell
    if (!g.inside[c]) continue;
    const int r = uf.find(static_cast<int>(c));
    if (id_of_root[r] < 0) id_of_root[r] = count++;
    label[c] = id_of_root[r];
  }
  p.boxes = boxes_of(g, label, count);
  index_boxes(g, p);
  return p;
}

void merge_boxes(const OccupancyGrid& g, BoxPartition& p,
                 const std::function<bool(const Box&)>& fits) {
  std::vector<Box> boxes = p.boxes;
  for (;;) {
    double best = -1.0;
    std::size_t bi = 0, bj = 0;
    Box merged;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      for (std::size_t j = i + 1; j < boxes.size(); ++j) {
        Box u;
        if (!union_box(boxes[i], boxes[j], u)) continue;
        const double v = cell_volume(g, u);
        if (v <= best || (fits && !fits(u))) continue;
        best = v;
        bi = i;
        bj = j;
        merged = u;
      }
    if (best < 0) break;
    boxes[bi] = merged;
    boxes.erase(boxes.begin() + static_cast<std::ptrdiff_t>(bj));
  }
  std::sort(boxes.begin(), boxes.end(),
            [&](const Box& x, const Box& y) { return g.index(x.lo) < g.index(y.lo); });
  p.boxes = std::move(boxes);
  index_boxes(g, p);
}

}  // namespace polycube::fabricate
