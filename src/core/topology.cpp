#include "core/topology.h"

#include "core/charts.h"
#include "core/disjoint_sets.h"
#include "core/errors.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>

namespace polycube::core {

namespace {

constexpr CellType kTri = CellType::Triangle;
constexpr CellType kQuad = CellType::Quad;
constexpr CellType kTet = CellType::Tetra;
constexpr CellType kHex = CellType::Hexa;

//! Number of slots (cell x local item), checked against int overflow.
int slot_count(std::size_t cells, int per_cell, const char* what) {
  const std::size_t n = cells * static_cast<std::size_t>(per_cell);
  if (n > static_cast<std::size_t>(INT_MAX)) {
    throw InputError(std::string("mesh too large for 32-bit ") + what + " indices (" +
                     std::to_string(cells) + " cells)");
  }
  return static_cast<int>(n);
}

//! Number components of n elements by first appearance of their root.
Components number_components(DisjointSets& ds, int n) {
  Components out;
  out.cell_component.assign(static_cast<std::size_t>(n), -1);
  std::vector<int> root_id(static_cast<std::size_t>(n), -1);
  for (int i = 0; i < n; ++i) {
    const int r = ds.find(i);
    if (root_id[r] < 0) root_id[r] = out.count++;
    out.cell_component[i] = root_id[r];
  }
  return out;
}

//! Slots grouped by equal sorted key.
//! order: slot ids sorted by (key, slot); run_start: #runs+1 offsets into order.
struct Grouping {
  std::vector<int> order;
  std::vector<int> run_start;
  [[nodiscard]] int num_runs() const { return static_cast<int>(run_start.size()) - 1; }
  [[nodiscard]] int run_size(int r) const { return run_start[r + 1] - run_start[r]; }
};

//! Group num_slots slots by key_of(slot) (a sorted std::array<int, K> of vertex ids in
//! [0, num_points)). Bucket (counting) sort on the first key entry, then a small sort inside each
//! bucket: O(n + V) plus tiny sorts, no per-slot allocation. Runs come out in lexicographic key
//! order, each run's slots in increasing order.
template <int K, class KeyFn>
Grouping group_slots(int num_slots, int num_points, KeyFn key_of) {
  Grouping g;
  std::vector<int> bucket(static_cast<std::size_t>(num_points) + 1, 0);
  for (int s = 0; s < num_slots; ++s) ++bucket[key_of(s)[0] + 1];
  for (int v = 0; v < num_points; ++v) bucket[v + 1] += bucket[v];
  g.order.resize(static_cast<std::size_t>(num_slots));
  {
    std::vector<int> fill(bucket.begin(), bucket.end() - 1);
    for (int s = 0; s < num_slots; ++s) g.order[fill[key_of(s)[0]]++] = s;
  }
  g.run_start.reserve(static_cast<std::size_t>(num_slots) / 2 + 2);
  // Inside a bucket key[0] is fixed: sort (key[1..K-1], slot) as one small int array.
  using Entry = std::array<int, K>;
  auto same_key = [](const Entry& a, const Entry& b) {
    for (int i = 0; i + 1 < K; ++i)
      if (a[i] != b[i]) return false;
    return true;
  };
  std::vector<Entry> buf;
  for (int v = 0; v < num_points; ++v) {
    const int b = bucket[v];
    const int e = bucket[v + 1];
    if (e - b == 1) {
      g.run_start.push_back(b);
      continue;
    }
    if (e == b) continue;
    buf.clear();
    for (int i = b; i < e; ++i) {
      const auto key = key_of(g.order[i]);
      Entry x;
      for (int j = 1; j < K; ++j) x[j - 1] = key[j];
      x[K - 1] = g.order[i];
      buf.push_back(x);
    }
    std::sort(buf.begin(), buf.end());
    for (int i = b; i < e; ++i) {
      g.order[i] = buf[i - b][K - 1];
      if (i == b || !same_key(buf[i - b], buf[i - b - 1])) g.run_start.push_back(i);
    }
  }
  g.run_start.push_back(num_slots);
  return g;
}

template <int K>
std::array<int, K> sorted_key(std::array<int, K> k) {
  // Small fixed-size insertion sort (faster than std::sort for 2..4 items).
  for (int i = 1; i < K; ++i) {
    const int x = k[i];
    int j = i - 1;
    while (j >= 0 && k[j] > x) {
      k[j + 1] = k[j];
      --j;
    }
    k[j + 1] = x;
  }
  return k;
}

//! Sorted vertex key of local edge k of cell c.
template <CellType T>
std::array<int, 2> edge_key(const Mesh<T>& m, int c, int k) {
  const auto& le = local_edges<T>()[k];
  const int a = m.cells[c][le[0]];
  const int b = m.cells[c][le[1]];
  return a < b ? std::array<int, 2>{a, b} : std::array<int, 2>{b, a};
}

//! Vertex ids of local face k of cell c, in local order.
template <CellType T>
std::array<int, face_vertex_count(T)> face_vertices(const Mesh<T>& m, int c, int k) {
  constexpr int kSize = face_vertex_count(T);
  std::array<int, kSize> f{};
  for (int i = 0; i < kSize; ++i) f[i] = m.cells[c][local_faces<T>()[k][i]];
  return f;
}

//! Faces of a volume mesh grouped by vertex set (slot = cell * kFacesPerCell + local face).
template <CellType T>
Grouping group_faces(const Mesh<T>& m) {
  constexpr int F = face_count(T);
  const int n = slot_count(m.cells.size(), F, "face");
  return group_slots<face_vertex_count(T)>(n, m.num_points(), [&m](int s) {
    return sorted_key<face_vertex_count(T)>(face_vertices(m, s / F, s % F));
  });
}

template <class Face>
std::string face_string(const Face& f) {
  std::string s = "(";
  for (std::size_t i = 0; i < f.size(); ++i) s += (i ? ", " : "") + std::to_string(f[i]);
  return s + ")";
}

//! Throw GeometryError for a face run with more than two cells.
template <CellType T>
[[noreturn]] void throw_nonmanifold_face(const Mesh<T>& m, const Grouping& g, int r) {
  constexpr int F = face_count(T);
  const int s0 = g.order[g.run_start[r]];
  std::string cells;
  for (int i = g.run_start[r]; i < g.run_start[r + 1]; ++i) {
    cells += (cells.empty() ? "" : ", ") + std::to_string(g.order[i] / F);
  }
  throw GeometryError("non-manifold volume mesh: face " +
                      face_string(face_vertices(m, s0 / F, s0 % F)) + " is shared by " +
                      std::to_string(g.run_size(r)) + " cells (" + cells +
                      "); a face may belong to at most two cells");
}

//! CSR of edge -> slots (cell * E + local edge), slots increasing.
template <CellType T>
Adjacency edge_slots(const EdgeTopology<T>& et) {
  constexpr int E = edge_count(T);
  Adjacency a;
  a.offsets.assign(et.edges.size() + 1, 0);
  for (const auto& ce : et.cell_edges)
    for (int e : ce) ++a.offsets[e + 1];
  for (std::size_t e = 0; e < et.edges.size(); ++e) a.offsets[e + 1] += a.offsets[e];
  a.items.resize(static_cast<std::size_t>(a.offsets.back()));
  std::vector<int> fill(a.offsets.begin(), a.offsets.end() - 1);
  for (std::size_t c = 0; c < et.cell_edges.size(); ++c)
    for (int k = 0; k < E; ++k) a.items[fill[et.cell_edges[c][k]]++] = static_cast<int>(c) * E + k;
  return a;
}

//! CSR from (key, value) pairs packed as uint64 (key high), sorted and deduplicated.
Adjacency csr_from_pairs(std::vector<std::uint64_t>& pairs, int n) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Adjacency a;
  a.offsets.assign(static_cast<std::size_t>(n) + 1, 0);
  a.items.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    ++a.offsets[static_cast<int>(pairs[i] >> 32) + 1];
    a.items[i] = static_cast<int>(pairs[i] & 0xffffffffu);
  }
  for (int i = 0; i < n; ++i) a.offsets[i + 1] += a.offsets[i];
  return a;
}

std::uint64_t pack(int a, int b) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

//! Which points are referenced by a cell.
template <CellType T>
std::vector<char> referenced(const Mesh<T>& m) {
  std::vector<char> used(m.points.size(), 0);
  for (const auto& c : m.cells)
    for (int v : c) used[v] = 1;
  return used;
}

template <CellType T>
bool has_repeated_index(const typename Mesh<T>::Cell& c) {
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = i + 1; j < c.size(); ++j)
      if (c[i] == c[j]) return true;
  return false;
}

//! Vector area of a surface cell (quads: split 0-1-2, 0-2-3).
template <CellType T>
Vec3 vector_area(const Mesh<T>& m, int c) {
  const auto& f = m.cells[c];
  const Vec3& p0 = m.points[f[0]];
  Vec3 a = (m.points[f[1]] - p0).cross(m.points[f[2]] - p0);
  if constexpr (T == kQuad) a += (m.points[f[2]] - p0).cross(m.points[f[3]] - p0);
  return 0.5 * a;
}

template <CellType T>
bool is_degenerate_face(const Mesh<T>& m, int c) {
  const auto& f = m.cells[c];
  if (has_repeated_index<T>(f)) return true;
  constexpr int N = vertex_count(T);
  double longest2 = 0.0;
  for (int i = 0; i < N; ++i)
    longest2 = std::max(longest2, (m.points[f[(i + 1) % N]] - m.points[f[i]]).squaredNorm());
  return !(vector_area(m, c).norm() > 1e-12 * longest2);
}

//! Signed volume contribution (times 6) of a surface cell, relative to the point o.
template <CellType T>
double volume6(const Mesh<T>& m, int c, const Vec3& o) {
  const auto& f = m.cells[c];
  const Vec3 p0 = m.points[f[0]] - o;
  const Vec3 p1 = m.points[f[1]] - o;
  const Vec3 p2 = m.points[f[2]] - o;
  double v = p0.dot(p1.cross(p2));
  if constexpr (T == kQuad) v += p0.dot(p2.cross(m.points[f[3]] - o));
  return v;
}

template <CellType T>
Vec3 box_centre(const Mesh<T>& m) {
  const BoundingBox b = bounding_box(m.points);
  return 0.5 * (b.min + b.max);
}

//! Reverse a surface cell keeping vertex 0.
template <class Cell>
void flip_cell(Cell& c) {
  std::reverse(c.begin() + 1, c.end());
}

//! Direction of local edge k in cell c: +1 when it runs from the lower to the higher vertex id.
template <CellType T>
int edge_direction(const Mesh<T>& m, int c, int k) {
  const auto& le = local_edges<T>()[k];
  return m.cells[c][le[0]] < m.cells[c][le[1]] ? 1 : -1;
}

//! Build the boundary surface of a volume mesh from its face grouping (faces of one cell).
template <CellType T, class Boundary>
Boundary build_boundary(const Mesh<T>& m, const Grouping& g) {
  constexpr int F = face_count(T);
  constexpr int kSize = face_vertex_count(T);
  Boundary out;
  const int n = static_cast<int>(g.order.size());
  std::vector<char> is_boundary(static_cast<std::size_t>(n), 0);
  for (int r = 0; r < g.num_runs(); ++r)
    if (g.run_size(r) == 1) is_boundary[g.order[g.run_start[r]]] = 1;

  std::vector<int> old_to_new(m.points.size(), -1);
  for (int s = 0; s < n; ++s) {
    if (!is_boundary[s]) continue;
    out.cell_of_face.push_back(s / F);
    out.local_face.push_back(s % F);
    for (int i = 0; i < kSize; ++i) old_to_new[m.cells[s / F][local_faces<T>()[s % F][i]]] = 0;
  }
  for (std::size_t v = 0; v < old_to_new.size(); ++v) {
    if (old_to_new[v] < 0) continue;
    old_to_new[v] = static_cast<int>(out.vertex_map.size());
    out.vertex_map.push_back(static_cast<int>(v));
    out.surface.points.push_back(m.points[v]);
  }
  out.surface.cells.resize(out.cell_of_face.size());
  for (std::size_t f = 0; f < out.cell_of_face.size(); ++f) {
    const auto fv = face_vertices(m, out.cell_of_face[f], out.local_face[f]);
    for (int i = 0; i < kSize; ++i) out.surface.cells[f][i] = old_to_new[fv[i]];
  }
  if (!m.labels.empty()) {
    out.surface.labels.resize(out.cell_of_face.size());
    for (std::size_t f = 0; f < out.cell_of_face.size(); ++f)
      out.surface.labels[f] = m.labels[out.cell_of_face[f]];
  }
  return out;
}

//! Components of a volume mesh from its face grouping.
template <CellType T>
Components volume_components(const Mesh<T>& m, const Grouping& g) {
  constexpr int F = face_count(T);
  DisjointSets ds(m.num_cells());
  for (int r = 0; r < g.num_runs(); ++r)
    for (int i = g.run_start[r] + 1; i < g.run_start[r + 1]; ++i)
      ds.unite(g.order[g.run_start[r]] / F, g.order[i] / F);
  return number_components(ds, m.num_cells());
}

//! Components of a surface mesh through shared edges.
template <CellType T>
Components surface_components(const Mesh<T>& m, const Adjacency& eslots) {
  constexpr int E = edge_count(T);
  DisjointSets ds(m.num_cells());
  for (int e = 0; e < eslots.size(); ++e) {
    const auto s = eslots[e];
    for (std::size_t i = 1; i < s.size(); ++i) ds.unite(s[0] / E, s[i] / E);
  }
  return number_components(ds, m.num_cells());
}

}  // namespace

TriangleCharts triangle_charts(const std::vector<Tri>& tris, const std::vector<int>& labels) {
  PC_REQUIRE(labels.size() == tris.size(), "triangle_charts: one label per triangle");
  const int nf = static_cast<int>(tris.size());
  int num_points = 0;
  for (const Tri& t : tris)
    for (int v : t) num_points = std::max(num_points, v + 1);
  // Edge slots (triangle, local edge) grouped by their sorted end points; a run of exactly two
  // is a manifold edge.
  const Grouping g = group_slots<2>(3 * nf, num_points, [&](int slot) {
    const Tri& t = tris[slot / 3];
    return sorted_key<2>({t[slot % 3], t[(slot + 1) % 3]});
  });
  DisjointSets ds(nf);
  for (int r = 0; r < g.num_runs(); ++r) {
    if (g.run_size(r) != 2) continue;
    const int a = g.order[g.run_start[r]] / 3, b = g.order[g.run_start[r] + 1] / 3;
    if (labels[a] == labels[b]) ds.unite(a, b);
  }
  const Components c = number_components(ds, nf);
  return {c.cell_component, c.count};
}

namespace {

bool tet_inverted(const TetMesh& m, int c) {
  const auto& t = m.cells[c];
  const Vec3& p0 = m.points[t[0]];
  return !((m.points[t[1]] - p0).dot((m.points[t[2]] - p0).cross(m.points[t[3]] - p0)) > 0.0);
}

bool hex_inverted(const HexMesh& m, int c) {
  const auto& h = m.cells[c];
  for (int i = 0; i < 8; ++i) {
    const Vec3& p = m.points[h[i]];
    const auto& nb = kHexCornerNeighbors[i];
    const double det =
        (m.points[h[nb[0]]] - p).dot((m.points[h[nb[1]]] - p).cross(m.points[h[nb[2]]] - p));
    if (!(det > 0.0)) return true;
  }
  return false;
}

template <CellType T>
VolumeReport analyze_volume_impl(const Mesh<T>& m) {
  check_indices(m);
  VolumeReport r;
  r.vertices = m.num_points();
  r.cells = m.num_cells();
  const Grouping g = group_faces(m);
  r.faces = g.num_runs();
  for (int k = 0; k < g.num_runs(); ++k) {
    if (g.run_size(k) == 1) ++r.boundary_faces;
    if (g.run_size(k) > 2) ++r.nonmanifold_faces;
  }
  r.edges = unique_edges(m).num_edges();
  r.components = volume_components(m, g).count;
  const auto used = referenced(m);
  const int vref = static_cast<int>(std::count(used.begin(), used.end(), 1));
  r.isolated_vertices = r.vertices - vref;
  r.euler_characteristic = vref - r.edges + r.faces - r.cells;
  for (int c = 0; c < m.num_cells(); ++c) {
    if constexpr (T == kTet)
      r.inverted_cells += tet_inverted(m, c) ? 1 : 0;
    else
      r.inverted_cells += hex_inverted(m, c) ? 1 : 0;
  }
  using B = std::conditional_t<T == kTet, TetBoundary, HexBoundary>;
  const B b = build_boundary<T, B>(m, g);
  r.boundary = analyze_surface(b.surface);
  return r;
}

}  // namespace

// --- validation -------------------------------------------------------------------------------

template <CellType T>
void check_indices(const Mesh<T>& m) {
  const int n = m.num_points();
  for (std::size_t c = 0; c < m.cells.size(); ++c) {
    for (int v : m.cells[c]) {
      if (v < 0 || v >= n) {
        throw InputError(std::string(cell_type_name(T)) + " " + std::to_string(c) +
                         " references vertex " + std::to_string(v) + ", but the mesh has " +
                         std::to_string(n) + " points");
      }
    }
  }
  if (!m.labels.empty() && m.labels.size() != m.cells.size()) {
    throw InputError("mesh has " + std::to_string(m.labels.size()) + " labels for " +
                     std::to_string(m.cells.size()) + " cells");
  }
}

template <CellType T>
std::vector<int> remove_unreferenced_points(Mesh<T>& m) {
  check_indices(m);
  const auto used = referenced(m);
  std::vector<int> old_to_new(m.points.size(), -1);
  int next = 0;
  for (std::size_t v = 0; v < m.points.size(); ++v) {
    if (!used[v]) continue;
    old_to_new[v] = next;
    m.points[next++] = m.points[v];
  }
  m.points.resize(static_cast<std::size_t>(next));
  for (auto& c : m.cells)
    for (int& v : c) v = old_to_new[v];
  return old_to_new;
}

// --- edges and faces --------------------------------------------------------------------------

template <CellType T>
EdgeTopology<T> unique_edges(const Mesh<T>& m) {
  check_indices(m);
  constexpr int E = edge_count(T);
  const int n = slot_count(m.cells.size(), E, "edge");
  const Grouping g =
      group_slots<2>(n, m.num_points(), [&m](int s) { return edge_key(m, s / E, s % E); });
  EdgeTopology<T> et;
  et.edges.resize(static_cast<std::size_t>(g.num_runs()));
  et.cell_edges.resize(m.cells.size());
  for (int r = 0; r < g.num_runs(); ++r) {
    const int s0 = g.order[g.run_start[r]];
    et.edges[r] = edge_key(m, s0 / E, s0 % E);
    for (int i = g.run_start[r]; i < g.run_start[r + 1]; ++i) {
      const int s = g.order[i];
      et.cell_edges[s / E][s % E] = r;
    }
  }
  return et;
}

template <CellType T>
FaceTopology<T> unique_faces(const Mesh<T>& m) {
  static_assert(dimension(T) == 3, "unique_faces: volume kinds only");
  check_indices(m);
  constexpr int F = face_count(T);
  const Grouping g = group_faces(m);
  const int n = static_cast<int>(g.order.size());
  std::vector<int> run_of_slot(static_cast<std::size_t>(n));
  for (int r = 0; r < g.num_runs(); ++r) {
    if (g.run_size(r) > 2) throw_nonmanifold_face(m, g, r);
    for (int i = g.run_start[r]; i < g.run_start[r + 1]; ++i) run_of_slot[g.order[i]] = r;
  }
  // Number faces by first appearance: a run's first slot is its lowest one.
  FaceTopology<T> ft;
  ft.faces.reserve(static_cast<std::size_t>(g.num_runs()));
  ft.face_cells.reserve(static_cast<std::size_t>(g.num_runs()));
  ft.face_local.reserve(static_cast<std::size_t>(g.num_runs()));
  ft.cell_faces.resize(m.cells.size());
  std::vector<int> run_face(static_cast<std::size_t>(g.num_runs()), -1);
  for (int s = 0; s < n; ++s) {
    const int r = run_of_slot[s];
    const int c = s / F;
    const int k = s % F;
    if (run_face[r] < 0) {
      run_face[r] = ft.num_faces();
      ft.faces.push_back(face_vertices(m, c, k));
      ft.face_cells.push_back({c, -1});
      ft.face_local.push_back({k, -1});
    } else {
      ft.face_cells[run_face[r]][1] = c;
      ft.face_local[run_face[r]][1] = k;
    }
    ft.cell_faces[c][k] = run_face[r];
  }
  return ft;
}

// --- adjacency --------------------------------------------------------------------------------

template <CellType T>
Adjacency vertex_cells(const Mesh<T>& m) {
  check_indices(m);
  const int nv = m.num_points();
  Adjacency a;
  a.offsets.assign(static_cast<std::size_t>(nv) + 1, 0);
  std::vector<int> last(static_cast<std::size_t>(nv), -1);
  for (int c = 0; c < m.num_cells(); ++c)
    for (int v : m.cells[c])
      if (last[v] != c) {
        last[v] = c;
        ++a.offsets[v + 1];
      }
  for (int v = 0; v < nv; ++v) a.offsets[v + 1] += a.offsets[v];
  a.items.resize(static_cast<std::size_t>(a.offsets.back()));
  std::vector<int> fill(a.offsets.begin(), a.offsets.end() - 1);
  std::fill(last.begin(), last.end(), -1);
  for (int c = 0; c < m.num_cells(); ++c)
    for (int v : m.cells[c])
      if (last[v] != c) {
        last[v] = c;
        a.items[fill[v]++] = c;
      }
  return a;
}

template <CellType T>
Adjacency edge_cells(const EdgeTopology<T>& et) {
  const int ne = et.num_edges();
  Adjacency a;
  a.offsets.assign(static_cast<std::size_t>(ne) + 1, 0);
  std::vector<int> last(static_cast<std::size_t>(ne), -1);
  const int nc = static_cast<int>(et.cell_edges.size());
  for (int c = 0; c < nc; ++c)
    for (int e : et.cell_edges[c])
      if (last[e] != c) {
        last[e] = c;
        ++a.offsets[e + 1];
      }
  for (int e = 0; e < ne; ++e) a.offsets[e + 1] += a.offsets[e];
  a.items.resize(static_cast<std::size_t>(a.offsets.back()));
  std::vector<int> fill(a.offsets.begin(), a.offsets.end() - 1);
  std::fill(last.begin(), last.end(), -1);
  for (int c = 0; c < nc; ++c)
    for (int e : et.cell_edges[c])
      if (last[e] != c) {
        last[e] = c;
        a.items[fill[e]++] = c;
      }
  return a;
}

template <CellType T>
Adjacency vertex_vertices(const EdgeTopology<T>& et, int num_points) {
  Adjacency a;
  a.offsets.assign(static_cast<std::size_t>(num_points) + 1, 0);
  for (const auto& e : et.edges) {
    PC_REQUIRE(e[0] >= 0 && e[1] < num_points, "vertex_vertices: edge outside num_points");
    if (e[0] == e[1]) continue;
    ++a.offsets[e[0] + 1];
    ++a.offsets[e[1] + 1];
  }
  for (int v = 0; v < num_points; ++v) a.offsets[v + 1] += a.offsets[v];
  a.items.resize(static_cast<std::size_t>(a.offsets.back()));
  std::vector<int> fill(a.offsets.begin(), a.offsets.end() - 1);
  // Edges are sorted (a < b): for vertex v, edges (w, v) with w < v come first in increasing w,
  // then edges (v, w) in increasing w, so each list comes out sorted.
  for (const auto& e : et.edges) {
    if (e[0] == e[1]) continue;
    a.items[fill[e[0]]++] = e[1];
    a.items[fill[e[1]]++] = e[0];
  }
  return a;
}

template <CellType T>
Adjacency cell_cells(const Mesh<T>& m) {
  check_indices(m);
  std::vector<std::uint64_t> pairs;
  auto add_run = [&pairs](auto begin, auto end, int per_cell) {
    for (auto i = begin; i != end; ++i)
      for (auto j = begin; j != end; ++j) {
        const int a = *i / per_cell;
        const int b = *j / per_cell;
        if (a != b) pairs.push_back(pack(a, b));
      }
  };
  if constexpr (dimension(T) == 2) {
    const auto et = unique_edges(m);
    const Adjacency es = edge_slots(et);
    pairs.reserve(es.items.size());
    for (int e = 0; e < es.size(); ++e) add_run(es[e].begin(), es[e].end(), edge_count(T));
  } else {
    const Grouping g = group_faces(m);
    pairs.reserve(g.order.size());
    for (int r = 0; r < g.num_runs(); ++r)
      add_run(g.order.begin() + g.run_start[r], g.order.begin() + g.run_start[r + 1],
              face_count(T));
  }
  return csr_from_pairs(pairs, m.num_cells());
}

// --- boundary and components ------------------------------------------------------------------

std::vector<Tri> boundary_triangles(const TetBoundary& b) {
  std::vector<Tri> tris(b.surface.cells.size());
  for (std::size_t f = 0; f < tris.size(); ++f) {
    const Tri& s = b.surface.cells[f];
    tris[f] = {b.vertex_map[s[0]], b.vertex_map[s[1]], b.vertex_map[s[2]]};
  }
  return tris;
}

TetBoundary boundary(const TetMesh& m) {
  check_indices(m);
  const Grouping g = group_faces(m);
  for (int r = 0; r < g.num_runs(); ++r)
    if (g.run_size(r) > 2) throw_nonmanifold_face(m, g, r);
  return build_boundary<kTet, TetBoundary>(m, g);
}

HexBoundary boundary(const HexMesh& m) {
  check_indices(m);
  const Grouping g = group_faces(m);
  for (int r = 0; r < g.num_runs(); ++r)
    if (g.run_size(r) > 2) throw_nonmanifold_face(m, g, r);
  return build_boundary<kHex, HexBoundary>(m, g);
}

template <CellType T>
Components connected_components(const Mesh<T>& m) {
  check_indices(m);
  if constexpr (dimension(T) == 2) {
    return surface_components(m, edge_slots(unique_edges(m)));
  } else {
    return volume_components(m, group_faces(m));
  }
}

// --- surfaces ---------------------------------------------------------------------------------

template <CellType T>
SurfaceReport analyze_surface(const Mesh<T>& m) {
  static_assert(dimension(T) == 2, "analyze_surface: surface kinds only");
  check_indices(m);
  constexpr int N = vertex_count(T);
  constexpr int E = edge_count(T);
  SurfaceReport r;
  r.vertices = m.num_points();
  r.faces = m.num_cells();
  const EdgeTopology<T> et = unique_edges(m);
  const Adjacency es = edge_slots(et);
  r.edges = et.num_edges();

  // Edge classes, boundary loops, consistent orientation.
  DisjointSets loops(r.vertices);
  std::vector<char> on_boundary(static_cast<std::size_t>(r.vertices), 0);
  r.consistently_oriented = true;
  for (int e = 0; e < r.edges; ++e) {
    const auto s = es[e];
    if (s.size() == 1) {
      ++r.boundary_edges;
      loops.unite(et.edges[e][0], et.edges[e][1]);
      on_boundary[et.edges[e][0]] = on_boundary[et.edges[e][1]] = 1;
    } else if (s.size() == 2) {
      if (edge_direction(m, s[0] / E, s[0] % E) == edge_direction(m, s[1] / E, s[1] % E))
        r.consistently_oriented = false;
    } else {
      ++r.nonmanifold_edges;
    }
  }
  for (int v = 0; v < r.vertices; ++v)
    if (on_boundary[v] && loops.find(v) == v) ++r.boundary_loops;

  // Orientability: 2-colouring of flips through manifold edges.
  {
    std::vector<signed char> flip(m.cells.size(), -1);
    std::vector<int> queue;
    r.orientable = true;
    for (int f0 = 0; f0 < r.faces && r.orientable; ++f0) {
      if (flip[f0] >= 0) continue;
      flip[f0] = 0;
      queue.assign(1, f0);
      for (std::size_t q = 0; q < queue.size() && r.orientable; ++q) {
        const int f = queue[q];
        for (int k = 0; k < E; ++k) {
          const auto s = es[et.cell_edges[f][k]];
          if (s.size() != 2) continue;
          const int other = (s[0] == f * E + k) ? s[1] : s[0];
          const int g = other / E;
          if (g == f) continue;
          const bool same = edge_direction(m, f, k) == edge_direction(m, g, other % E);
          const signed char want = static_cast<signed char>(flip[f] ^ (same ? 1 : 0));
          if (flip[g] < 0) {
            flip[g] = want;
            queue.push_back(g);
          } else if (flip[g] != want) {
            r.orientable = false;
            break;
          }
        }
      }
    }
  }

  // Vertex fans: the corners around a vertex, joined through shared neighbours (edges) and
  // through being corners of the same face.
  {
    std::vector<int> offsets(static_cast<std::size_t>(r.vertices) + 1, 0);
    for (const auto& c : m.cells)
      for (int v : c) ++offsets[v + 1];
    for (int v = 0; v < r.vertices; ++v) offsets[v + 1] += offsets[v];
    std::vector<int> corners(static_cast<std::size_t>(offsets.back()));
    {
      std::vector<int> fill(offsets.begin(), offsets.end() - 1);
      for (int f = 0; f < r.faces; ++f)
        for (int i = 0; i < N; ++i) corners[fill[m.cells[f][i]]++] = f * N + i;
    }
    std::vector<std::pair<int, int>> nbr;  // (neighbour vertex, local corner index)
    std::vector<int> parent;
    auto find = [&parent](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (int v = 0; v < r.vertices; ++v) {
      const int b = offsets[v];
      const int n = offsets[v + 1] - b;
      if (n <= 1) continue;
      parent.resize(static_cast<std::size_t>(n));
      std::iota(parent.begin(), parent.end(), 0);
      nbr.clear();
      int groups = n;
      auto unite = [&](int x, int y) {
        x = find(x);
        y = find(y);
        if (x != y) {
          parent[std::max(x, y)] = std::min(x, y);
          --groups;
        }
      };
      for (int i = 0; i < n; ++i) {
        const int f = corners[b + i] / N;
        const int k = corners[b + i] % N;
        nbr.emplace_back(m.cells[f][(k + 1) % N], i);
        nbr.emplace_back(m.cells[f][(k + N - 1) % N], i);
        if (i > 0 && corners[b + i - 1] / N == f) unite(i - 1, i);
      }
      std::sort(nbr.begin(), nbr.end());
      for (std::size_t j = 1; j < nbr.size(); ++j)
        if (nbr[j].first == nbr[j - 1].first) unite(nbr[j].second, nbr[j - 1].second);
      if (groups > 1) ++r.nonmanifold_vertices;
    }
  }

  for (int f = 0; f < r.faces; ++f)
    if (is_degenerate_face(m, f)) ++r.degenerate_faces;

  const auto used = referenced(m);
  const int vref = static_cast<int>(std::count(used.begin(), used.end(), 1));
  r.isolated_vertices = r.vertices - vref;
  r.euler_characteristic = vref - r.edges + r.faces;

  const Components comp = surface_components(m, es);
  r.components = comp.count;
  r.closed = r.faces > 0 && r.boundary_edges == 0;
  r.manifold = r.nonmanifold_edges == 0 && r.nonmanifold_vertices == 0;

  if (r.closed && r.manifold && r.orientable) {
    // chi per component; on a manifold surface every vertex and edge lies in one component.
    std::vector<int> chi(static_cast<std::size_t>(comp.count), 0);
    std::vector<int> vcomp(static_cast<std::size_t>(r.vertices), -1);
    for (int f = 0; f < r.faces; ++f) {
      const int c = comp.cell_component[f];
      ++chi[c];
      for (int v : m.cells[f]) vcomp[v] = c;
    }
    for (int v = 0; v < r.vertices; ++v)
      if (vcomp[v] >= 0) ++chi[vcomp[v]];
    for (int e = 0; e < r.edges; ++e) --chi[comp.cell_component[es[e][0] / E]];
    r.genus = 0;
    for (int c : chi) r.genus += (2 - c) / 2;
  }
  return r;
}

template <CellType T>
bool orient_consistently(Mesh<T>& m) {
  static_assert(dimension(T) == 2, "orient_consistently: surface kinds only");
  check_indices(m);
  constexpr int E = edge_count(T);
  const int nf = m.num_cells();
  const EdgeTopology<T> et = unique_edges(m);
  const Adjacency es = edge_slots(et);
  for (int e = 0; e < es.size(); ++e)
    if (es.degree(e) > 2) return false;

  // BFS from the lowest face of each component; comp = component by edge adjacency.
  std::vector<signed char> flip(static_cast<std::size_t>(nf), -1);
  std::vector<int> comp(static_cast<std::size_t>(nf), -1);
  std::vector<char> comp_open;
  std::vector<int> queue;
  int ncomp = 0;
  for (int f0 = 0; f0 < nf; ++f0) {
    if (flip[f0] >= 0) continue;
    flip[f0] = 0;
    comp[f0] = ncomp;
    comp_open.push_back(0);
    queue.assign(1, f0);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const int f = queue[q];
      for (int k = 0; k < E; ++k) {
        const auto s = es[et.cell_edges[f][k]];
        if (s.size() == 1) {
          comp_open[ncomp] = 1;
          continue;
        }
        const int other = (s[0] == f * E + k) ? s[1] : s[0];
        const int g = other / E;
        if (g == f) continue;
        const bool same = edge_direction(m, f, k) == edge_direction(m, g, other % E);
        const signed char want = static_cast<signed char>(flip[f] ^ (same ? 1 : 0));
        if (flip[g] < 0) {
          flip[g] = want;
          comp[g] = ncomp;
          queue.push_back(g);
        } else if (flip[g] != want) {
          return false;  // non-orientable; nothing changed yet
        }
      }
    }
    ++ncomp;
  }

  // Closed components: make the enclosed volume positive.
  std::vector<double> vol(static_cast<std::size_t>(ncomp), 0.0);
  const Vec3 o = box_centre(m);
  for (int f = 0; f < nf; ++f) {
    const double v = volume6(m, f, o);
    vol[comp[f]] += flip[f] ? -v : v;
  }
  for (int f = 0; f < nf; ++f) {
    const bool outward_flip = !comp_open[comp[f]] && vol[comp[f]] < 0.0;
    if ((flip[f] != 0) != outward_flip) flip_cell(m.cells[f]);
  }
  return true;
}

double signed_volume(const TriMesh& m) {
  check_indices(m);
  const Vec3 o = box_centre(m);
  double v = 0.0;
  for (int f = 0; f < m.num_cells(); ++f) v += volume6(m, f, o);
  return v / 6.0;
}

double signed_volume(const QuadMesh& m) {
  check_indices(m);
  const Vec3 o = box_centre(m);
  double v = 0.0;
  for (int f = 0; f < m.num_cells(); ++f) v += volume6(m, f, o);
  return v / 6.0;
}

VolumeReport analyze_volume(const TetMesh& m) { return analyze_volume_impl(m); }
VolumeReport analyze_volume(const HexMesh& m) { return analyze_volume_impl(m); }

// --- explicit instantiations ------------------------------------------------------------------

#define PC_TOPOLOGY_ALL(T)                                         \
  template void check_indices(const Mesh<T>&);                     \
  template std::vector<int> remove_unreferenced_points(Mesh<T>&);  \
  template EdgeTopology<T> unique_edges(const Mesh<T>&);           \
  template Adjacency vertex_cells(const Mesh<T>&);                 \
  template Adjacency edge_cells(const EdgeTopology<T>&);           \
  template Adjacency vertex_vertices(const EdgeTopology<T>&, int); \
  template Adjacency cell_cells(const Mesh<T>&);                   \
  template Components connected_components(const Mesh<T>&);

PC_TOPOLOGY_ALL(CellType::Triangle)
PC_TOPOLOGY_ALL(CellType::Quad)
PC_TOPOLOGY_ALL(CellType::Tetra)
PC_TOPOLOGY_ALL(CellType::Hexa)
#undef PC_TOPOLOGY_ALL

template FaceTopology<CellType::Tetra> unique_faces(const TetMesh&);
template FaceTopology<CellType::Hexa> unique_faces(const HexMesh&);
template SurfaceReport analyze_surface(const TriMesh&);
template SurfaceReport analyze_surface(const QuadMesh&);
template bool orient_consistently(TriMesh&);
template bool orient_consistently(QuadMesh&);

Adjacency adjacency_from_pairs(int entries, std::vector<std::pair<int, int>> pairs) {
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Adjacency a;
  a.offsets.assign(static_cast<std::size_t>(entries) + 1, 0);
  a.items.reserve(pairs.size());
  for (const auto& [e, i] : pairs) {
    ++a.offsets[static_cast<std::size_t>(e) + 1];
    a.items.push_back(i);
  }
  for (int e = 0; e < entries; ++e) a.offsets[e + 1] += a.offsets[e];
  return a;
}

}  // namespace polycube::core
