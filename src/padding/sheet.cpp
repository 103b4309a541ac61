#include "padding/sheet.h"

#include "core/disjoint_sets.h"
#include "core/elements.h"
#include "core/errors.h"
#include "core/stopwatch.h"
#include "core/topology.h"
#include "padding/padding_topology.h"
#include "quality/structure_topology.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <map>

namespace polycube::padding {

namespace {

using core::Vec3;
using detail::Topology;
using detail::build_topology;
using detail::cells_around;

//! The input must be a hex mesh whose boundary is a closed 2-manifold (the ghosts need it).
//! \return the input's report, which verify() compares the result with
core::VolumeReport require_closed_manifold(const core::HexMesh& mesh) {
  core::VolumeReport r = core::analyze_volume(mesh);
  if (r.nonmanifold_faces > 0 || !r.boundary.closed || !r.boundary.manifold)
    throw core::InputError(fmt::format(
        "padding needs a hex mesh whose boundary is a closed 2-manifold ({} non-manifold faces, {} open and {} "
        "non-manifold boundary edges, {} non-manifold boundary vertices); repair or regrid the mesh first",
        r.nonmanifold_faces, r.boundary.boundary_edges, r.boundary.nonmanifold_edges, r.boundary.nonmanifold_vertices));
  return r;
}

int selected_around(const Topology& tp, const std::vector<std::uint8_t>& sel, int e) {
  int n = 0;
  for (int f : tp.t.edge_faces[e]) n += sel[f] ? 1 : 0;
  return n;
}

//! Separations around edge e: its selected facets, plus the ghosts' own separation when an odd
//! number is selected at a boundary edge (the sheet ends there and reaches the outside).
int separations(const Topology& tp, const std::vector<std::uint8_t>& sel, int e) {
  const int n = selected_around(tp, sel, e);
  return n + ((tp.t.edge_on_boundary[e] && n % 2 == 1) ? 1 : 0);
}

//! The rule edge e breaks, or an empty string.
std::string broken_rule(const Topology& tp, const std::vector<std::uint8_t>& sel, int e) {
  const int n = selected_around(tp, sel, e);
  if (n == 0) return {};
  const int hexes = tp.t.edge_valence(e);
  if (!tp.t.edge_on_boundary[e]) {
    if (n % 2 == 1) return fmt::format("{} of its {} facets are selected; an interior edge needs an even number", n,
                                       tp.t.edge_faces[e].size());
  } else if (hexes >= 3) {
    if (n % 2 == 1)
      return fmt::format("{} of its {} facets are selected; a concave boundary edge ({} hexes) needs an even number",
                         n, tp.t.edge_faces[e].size(), hexes);
  } else if (hexes == 2 && n == 1) {
    const int f = tp.edge_boundary[e][sel[tp.edge_boundary[e][0]] ? 0 : 1];
    if (sel[f]) return "one surface facet alone is selected at a boundary edge of two hexes (it would notch the surface)";
  }
  if (separations(tp, sel, e) > 4) return "more than two sheets cross there";
  return {};
}

SelectionCheck check_rules(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& sel) {
  SelectionCheck c;
  for (int e = 0; e < tp.t.num_edges(); ++e) {
    const std::string why = broken_rule(tp, sel, e);
    if (why.empty()) continue;
    if (c.bad_edges++ == 0) {
      const auto [a, b] = tp.t.edges.edges[e];
      const Vec3 m = 0.5 * (mesh.points[a] + mesh.points[b]);
      c.first = fmt::format("edge ({}, {}) at ({:.6g}, {:.6g}, {:.6g}): {}", a, b, m.x(), m.y(), m.z(), why);
    }
  }
  return c;
}

//! The regions of one vertex: which copy each cell touching it takes.
struct VertexRegions {
  std::vector<int> keys;     //!< cell keys (hexes, then ghosts), sorted
  std::vector<int> region;   //!< region of each key, numbered by first appearance
  int count = 0;             //!< number of regions
  [[nodiscard]] int of(int key) const {
    const auto it = std::lower_bound(keys.begin(), keys.end(), key);
    return region[static_cast<std::size_t>(it - keys.begin())];
  }
};

//! Group the cells around v (file comment): selected facets separate, so do two ghosts at a
//! boundary edge with an odd number of selected facets.
VertexRegions vertex_regions(const Topology& tp, const std::vector<std::uint8_t>& sel, int v) {
  VertexRegions r;
  for (int h : tp.vertex_hexes[v]) r.keys.push_back(h);
  for (int f : tp.vertex_faces[v])
    if (tp.t.faces.is_boundary(f)) r.keys.push_back(tp.ghost(f));
  core::DisjointSets sets(r.keys.size());
  const auto local = [&](int key) {
    return static_cast<int>(std::lower_bound(r.keys.begin(), r.keys.end(), key) - r.keys.begin());
  };
  for (int f : tp.vertex_faces[v]) {
    if (sel[f]) continue;
    const auto [c0, c1] = tp.t.faces.face_cells[f];
    sets.unite(local(c0), local(c1 >= 0 ? c1 : tp.ghost(f)));
  }
  for (int e : tp.vertex_edges[v]) {
    if (!tp.t.edge_on_boundary[e] || selected_around(tp, sel, e) % 2 == 1) continue;
    sets.unite(local(tp.ghost(tp.edge_boundary[e][0])), local(tp.ghost(tp.edge_boundary[e][1])));
  }
  std::vector<int> id(r.keys.size(), -1);
  r.region.resize(r.keys.size());
  for (std::size_t i = 0; i < r.keys.size(); ++i) {
    const int root = sets.find(static_cast<int>(i));
    if (id[root] < 0) id[root] = r.count++;
    r.region[i] = id[root];
  }
  return r;
}

Vec3 facet_centroid(const core::HexMesh& mesh, const core::Quad& q) {
  return 0.25 * (mesh.points[q[0]] + mesh.points[q[1]] + mesh.points[q[2]] + mesh.points[q[3]]);
}

Vec3 facet_normal(const core::HexMesh& mesh, const core::Quad& q) {
  const Vec3 n = (mesh.points[q[2]] - mesh.points[q[0]]).cross(mesh.points[q[3]] - mesh.points[q[1]]);
  const double len = n.norm();
  return len > 0 ? Vec3(n / len) : Vec3::Zero();
}

Vec3 hex_centroid(const core::HexMesh& mesh, int h) {
  Vec3 c = Vec3::Zero();
  for (int v : mesh.cells[h]) c += mesh.points[v];
  return c / 8.0;
}

//! d without its components along the normals of the planes it must stay in (nearly parallel
//! planes count once): a region touching the outside moves along the surface, not off it.
Vec3 along_planes(const Vec3& d, const std::vector<Vec3>& normals) {
  Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
  for (const Vec3& n : normals) m += n * n.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(m);
  const double top = eig.eigenvalues()(2);
  Vec3 out = Vec3::Zero();
  for (int k = 0; k < 3; ++k)
    if (eig.eigenvalues()(k) <= 0.1 * top) {
      const Vec3 u = eig.eigenvectors().col(k);
      out += u.dot(d) * u;
    }
  return out;
}

//! Position of the copy of v for one region (SheetOptions::offset): a region of hexes only moves
//! towards their centroids; one touching the outside moves the same way along the surface; a
//! ghost region stays at v, unless several ghost regions meet at v (a sheet crossing the padded
//! surface), which then move apart along their facets.
Vec3 copy_position(const core::HexMesh& mesh, const Topology& tp, const VertexRegions& r, int v, int region,
                   double step) {
  Vec3 towards_hexes = Vec3::Zero(), towards_ghosts = Vec3::Zero();
  std::vector<Vec3> normals;
  int hexes = 0;
  for (std::size_t i = 0; i < r.keys.size(); ++i) {
    if (r.region[i] != region) continue;
    const int key = r.keys[i];
    if (key < tp.num_hexes) {
      towards_hexes += hex_centroid(mesh, key) - mesh.points[v];
      ++hexes;
    } else {
      const core::Quad& q = tp.t.faces.faces[key - tp.num_hexes];
      towards_ghosts += facet_centroid(mesh, q) - mesh.points[v];
      normals.push_back(facet_normal(mesh, q));
    }
  }
  Vec3 d;
  double length = step;
  if (hexes > 0) {
    d = normals.empty() ? towards_hexes : along_planes(towards_hexes, normals);
  } else {
    int ghost_regions = 0;
    std::vector<std::uint8_t> has_hex(static_cast<std::size_t>(r.count), 0);
    for (std::size_t i = 0; i < r.keys.size(); ++i)
      if (r.keys[i] < tp.num_hexes) has_hex[r.region[i]] = 1;
    for (int k = 0; k < r.count; ++k) ghost_regions += has_hex[k] ? 0 : 1;
    if (ghost_regions <= 1) return mesh.points[v];
    d = towards_ghosts;
    length = 0.5 * step;
  }
  const double n = d.norm();
  return n > 1e-12 * step ? Vec3(mesh.points[v] + (length / n) * d) : mesh.points[v];
}

//! Mean length of the edges at v.
double mean_edge_length(const core::HexMesh& mesh, const Topology& tp, int v) {
  double sum = 0;
  int n = 0;
  for (int e : tp.vertex_edges[v]) {
    const auto [a, b] = tp.t.edges.edges[e];
    sum += (mesh.points[a] - mesh.points[b]).norm();
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

//! Every vertex's regions and their copies: region 0 keeps the vertex's index, the others get
//! new indices after the input's points, vertex by vertex.
struct Copies {
  std::vector<VertexRegions> regions;    //!< #V (empty for vertices not on a selected facet)
  std::vector<std::vector<int>> index;   //!< #V: point index of each region's copy
  std::vector<Vec3> points;              //!< the output's points
  int split_vertices = 0;

  [[nodiscard]] int at(int v, int key) const {
    return index[v].empty() ? v : index[v][regions[v].of(key)];
  }
};

Copies make_copies(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& sel,
                   const SheetOptions& options) {
  Copies c;
  const int nv = mesh.num_points();
  c.regions.resize(nv);
  c.index.resize(nv);
  c.points = mesh.points;
  std::vector<std::uint8_t> touched(nv, 0);
  for (int f = 0; f < tp.t.num_faces(); ++f)
    if (sel[f])
      for (int v : tp.t.faces.faces[f]) touched[v] = 1;
  for (int v = 0; v < nv; ++v) {
    if (!touched[v]) continue;
    c.regions[v] = vertex_regions(tp, sel, v);
    const VertexRegions& r = c.regions[v];
    if (r.count > 1) ++c.split_vertices;
    const double step = options.offset * mean_edge_length(mesh, tp, v);
    c.index[v].resize(r.count);
    for (int k = 0; k < r.count; ++k) {
      c.index[v][k] = k == 0 ? v : static_cast<int>(c.points.size());
      const Vec3 p = copy_position(mesh, tp, r, v, k, step);
      if (k == 0)
        c.points[v] = p;
      else
        c.points.push_back(p);
    }
  }
  // Region 0 moved in place: copy_position read the input's points, not c.points.
  return c;
}

//! The hex filling the crossing at edge e (four regions around it), or an error.
core::Hex crossing_hex(const core::HexMesh& mesh, const Topology& tp, const Copies& copies, int e) {
  const auto [v, w] = tp.t.edges.edges[e];
  const std::vector<int> cycle = cells_around(mesh, tp, e);
  std::vector<int> groups;  // first cell of each run of one region at v, cyclically
  const VertexRegions& rv = copies.regions[v];
  const int n = static_cast<int>(cycle.size());
  for (int i = 0; i < n; ++i)
    if (rv.of(cycle[i]) != rv.of(cycle[(i + n - 1) % n])) groups.push_back(cycle[i]);
  if (groups.size() != 4)
    throw core::GeometryError(fmt::format("padding: the cells around edge ({}, {}) fall into {} regions instead of 4",
                                          v, w, groups.size()));
  core::Hex hex{};
  for (int k = 0; k < 4; ++k) {
    hex[k] = copies.at(v, groups[k]);
    hex[k + 4] = copies.at(w, groups[k]);
  }
  return hex;
}

int first_hex(const std::vector<int>& cycle, int num_hexes) {
  for (int c : cycle)
    if (c < num_hexes) return c;
  return 0;
}

//! The input's hexes on their copies, one hex per selected facet, one per crossing edge.
SheetResult build_mesh(const core::HexMesh& mesh, const Topology& tp, const std::vector<std::uint8_t>& sel,
                       const Copies& copies) {
  SheetResult r;
  r.mesh.points = copies.points;
  r.mesh.cells = mesh.cells;
  for (int h = 0; h < mesh.num_cells(); ++h)
    for (int& v : r.mesh.cells[h]) v = copies.at(v, h);
  r.source_hex.resize(mesh.cells.size());
  for (int h = 0; h < mesh.num_cells(); ++h) r.source_hex[h] = h;
  for (int f = 0; f < tp.t.num_faces(); ++f) {
    if (!sel[f]) continue;
    const core::Quad& q = tp.t.faces.faces[f];
    const auto [c0, c1] = tp.t.faces.face_cells[f];
    const int outer = c1 >= 0 ? c1 : tp.ghost(f);
    core::Hex hex{};
    for (int k = 0; k < 4; ++k) {
      hex[k] = copies.at(q[k], c0);
      hex[k + 4] = copies.at(q[k], outer);
    }
    r.mesh.cells.push_back(hex);
    r.source_hex.push_back(c0);
    ++r.facet_hexes;
  }
  for (int e = 0; e < tp.t.num_edges(); ++e) {
    if (separations(tp, sel, e) != 4) continue;
    r.mesh.cells.push_back(crossing_hex(mesh, tp, copies, e));
    r.source_hex.push_back(first_hex(cells_around(mesh, tp, e), tp.num_hexes));
    ++r.crossing_hexes;
  }
  if (!mesh.labels.empty()) {
    r.mesh.labels.reserve(r.mesh.cells.size());
    for (int s : r.source_hex) r.mesh.labels.push_back(mesh.labels[s]);
  }
  r.added_hexes = r.facet_hexes + r.crossing_hexes;
  r.padding_layer.assign(r.mesh.cells.size(), 0);
  std::fill(r.padding_layer.begin() + mesh.num_cells(), r.padding_layer.end(), 1);
  r.split_vertices = copies.split_vertices;
  return r;
}

//! The result is a valid hex mesh with the input's topology, or nothing is returned: every hex
//! has 8 distinct vertices and no two hexes the same, every face is shared by at most two hexes,
//! the boundary is a closed 2-manifold with the input's Euler characteristic.
void verify(const core::HexMesh& out, const core::VolumeReport& before) {
  std::vector<core::Hex> sorted = out.cells;
  for (core::Hex& h : sorted) {
    std::sort(h.begin(), h.end());
    if (std::adjacent_find(h.begin(), h.end()) != h.end())
      throw core::GeometryError("padding produced a hex with a repeated vertex; the facet set cannot be inflated");
  }
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
    throw core::GeometryError("padding produced two hexes on the same vertices; the facet set cannot be inflated");
  const core::VolumeReport after = core::analyze_volume(out);
  if (after.nonmanifold_faces > 0 || !after.boundary.closed || !after.boundary.manifold ||
      after.boundary.euler_characteristic != before.boundary.euler_characteristic ||
      after.components != before.components || after.isolated_vertices > before.isolated_vertices)
    throw core::GeometryError(fmt::format(
        "padding would break the mesh ({} faces of more than two hexes, boundary {} and {}, Euler characteristic {} "
        "instead of {}); this facet set is not supported (e.g. three sheets crossing at one vertex)",
        after.nonmanifold_faces, after.boundary.closed ? "closed" : "open",
        after.boundary.manifold ? "manifold" : "non-manifold", after.boundary.euler_characteristic,
        before.boundary.euler_characteristic));
}

void require_size(const Topology& tp, const std::vector<std::uint8_t>& sel) {
  if (static_cast<int>(sel.size()) != tp.t.num_faces())
    throw core::InputError(
        fmt::format("facet selection has {} flags for a mesh of {} facets", sel.size(), tp.t.num_faces()));
}

}  // namespace

SelectionCheck check_selection(const core::HexMesh& mesh, const std::vector<std::uint8_t>& selected) {
  const Topology tp = build_topology(mesh);
  require_size(tp, selected);
  return check_rules(mesh, tp, selected);
}

SheetResult insert_sheet(const core::HexMesh& mesh, const std::vector<std::uint8_t>& selected,
                         const SheetOptions& options) {
  const core::Stopwatch clock;
  if (!(options.offset > 0.0 && options.offset < 1.0))
    throw core::InputError(fmt::format("padding offset must be in (0, 1), got {}", options.offset));
  const core::VolumeReport input = require_closed_manifold(mesh);
  const Topology tp = build_topology(mesh);
  require_size(tp, selected);
  if (std::none_of(selected.begin(), selected.end(), [](std::uint8_t s) { return s != 0; }))
    throw core::InputError("no facet is selected for padding");
  const SelectionCheck check = check_rules(mesh, tp, selected);
  if (!check.ok())
    throw core::InputError(fmt::format("invalid padding facet set: {} edge{} break the rules of thesis §4.3.1; first: {}",
                                       check.bad_edges, check.bad_edges == 1 ? "" : "s", check.first));
  const Copies copies = make_copies(mesh, tp, selected, options);
  SheetResult r = build_mesh(mesh, tp, selected, copies);
  verify(r.mesh, input);
  r.seconds = clock.seconds();
  return r;
}

std::vector<std::uint8_t> select_facets(const core::HexMesh& mesh, const std::vector<core::Quad>& quads) {
  const auto faces = core::unique_faces(mesh);
  std::map<core::Quad, int> by_vertices;
  for (int f = 0; f < faces.num_faces(); ++f) {
    core::Quad key = faces.faces[f];
    std::sort(key.begin(), key.end());
    by_vertices.emplace(key, f);
  }
  std::vector<std::uint8_t> sel(faces.num_faces(), 0);
  for (std::size_t i = 0; i < quads.size(); ++i) {
    core::Quad key = quads[i];
    std::sort(key.begin(), key.end());
    const auto it = by_vertices.find(key);
    if (it == by_vertices.end())
      throw core::InputError(fmt::format("facet {} ({} {} {} {}) is not a facet of the hex mesh", i + 1, quads[i][0],
                                         quads[i][1], quads[i][2], quads[i][3]));
    sel[it->second] = 1;
  }
  return sel;
}

std::vector<std::uint8_t> boundary_selection(const core::HexMesh& mesh) {
  const auto faces = core::unique_faces(mesh);
  std::vector<std::uint8_t> sel(faces.num_faces(), 0);
  for (int f = 0; f < faces.num_faces(); ++f) sel[f] = faces.is_boundary(f) ? 1 : 0;
  return sel;
}

}  // namespace polycube::padding
