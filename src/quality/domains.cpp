#include "quality/domains.h"

#include "core/errors.h"

#include <vector>

namespace polycube::quality {

namespace {

//! True when the two faces belong to a common hex.
bool faces_share_cell(const std::array<int, 2>& a, const std::array<int, 2>& b) {
  for (int x : a) {
    if (x < 0) continue;
    if (x == b[0] || x == b[1]) return true;
  }
  return false;
}

//! True when the two edges belong to a common quad.
bool edges_share_cell(std::span<const int> a, std::span<const int> b) {
  for (int x : a)
    for (int y : b)
      if (x == y) return true;
  return false;
}

}  // namespace

core::Field HexDomains::field(const std::string& name) const {
  PC_REQUIRE(!block_id.empty() || domains == 0, "block ids were not kept");
  return core::Field{name, std::vector<double>(block_id.begin(), block_id.end())};
}

core::Field QuadDomains::field(const std::string& name) const {
  PC_REQUIRE(!patch_id.empty() || domains == 0, "patch ids were not kept");
  return core::Field{name, std::vector<double>(patch_id.begin(), patch_id.end())};
}

HexDomains hex_domains(const core::HexMesh& mesh, const DomainOptions& options) {
  const HexTopology t = hex_topology(mesh);
  return hex_domains(mesh, t, hex_singularities(mesh, t), options);
}

HexDomains hex_domains(const core::HexMesh& mesh, const HexTopology& t, const HexSingularities& s,
                       const DomainOptions& options) {
  const int nf = t.num_faces();
  const auto& face_cells = t.faces.face_cells;

  // Trace sheets: one breadth-first search over the "continues straight across a regular edge"
  // relation (symmetric), seeded with every face of every singular edge. Its closure is the
  // union of cinolib's face_sheet() over the same seeds.
  std::vector<std::uint8_t> traced(nf, 0);
  std::vector<int> queue;
  queue.reserve(nf);
  for (int e = 0; e < t.num_edges(); ++e) {
    if (!s.edge_singular[e]) continue;
    for (int f : t.edge_faces[e])
      if (!traced[f]) {
        traced[f] = 1;
        queue.push_back(f);
      }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int f = queue[head];
    for (int e : t.face_edges[f]) {
      if (s.edge_singular[e]) continue;
      for (int g : t.edge_faces[e]) {
        if (traced[g] || faces_share_cell(face_cells[f], face_cells[g])) continue;
        traced[g] = 1;
        queue.push_back(g);
      }
    }
  }

  // Flood hexes across untraced interior faces.
  HexDomains d;
  const int nc = mesh.num_cells();
  std::vector<int> block(nc, -1);
  std::vector<int> stack;
  for (int seed = 0; seed < nc; ++seed) {
    if (block[seed] >= 0) continue;
    const int id = d.domains++;
    block[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      for (int f : t.faces.cell_faces[c]) {
        if (traced[f]) continue;
        const auto& fc = face_cells[f];
        const int other = fc[0] == c ? fc[1] : fc[0];
        if (other < 0 || block[other] >= 0) continue;
        block[other] = id;
        stack.push_back(other);
      }
    }
  }
  for (int f = 0; f < nf; ++f)
    if (traced[f] && !t.faces.is_boundary(f)) ++d.separating_faces;
  if (options.keep_labels) {
    d.block_id = std::move(block);
    d.face_traced = std::move(traced);
  }
  return d;
}

QuadDomains quad_domains(const core::QuadMesh& mesh, const DomainOptions& options) {
  const QuadTopology t = quad_topology(mesh);
  return quad_domains(mesh, t, quad_singularities(mesh, t), options);
}

QuadDomains quad_domains(const core::QuadMesh& mesh, const QuadTopology& t,
                         const QuadSingularities& s, const DomainOptions& options) {
  const int ne = t.num_edges();

  // Trace separatrices from every singular vertex (breadth-first over edges).
  std::vector<std::uint8_t> traced(ne, 0);
  std::vector<int> queue;
  for (std::size_t v = 0; v < s.vertex_singular.size(); ++v) {
    if (!s.vertex_singular[v]) continue;
    for (int e : t.vertex_edges[static_cast<int>(v)])
      if (!traced[e]) {
        traced[e] = 1;
        queue.push_back(e);
      }
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int e = queue[head];
    for (int v : t.edges.edges[e]) {
      if (s.vertex_singular[v]) continue;
      for (int e2 : t.vertex_edges[v]) {
        if (traced[e2] || edges_share_cell(t.edge_cells[e], t.edge_cells[e2])) continue;
        traced[e2] = 1;
        queue.push_back(e2);
      }
    }
  }

  // Flood quads across untraced edges.
  QuadDomains d;
  const int nc = mesh.num_cells();
  std::vector<int> patch(nc, -1);
  std::vector<int> stack;
  for (int seed = 0; seed < nc; ++seed) {
    if (patch[seed] >= 0) continue;
    const int id = d.domains++;
    patch[seed] = id;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      for (int e : t.edges.cell_edges[c]) {
        if (traced[e]) continue;
        for (int other : t.edge_cells[e]) {
          if (patch[other] >= 0) continue;
          patch[other] = id;
          stack.push_back(other);
        }
      }
    }
  }
  for (int e = 0; e < ne; ++e)
    if (traced[e] && t.edge_cells.degree(e) >= 2) ++d.separating_edges;
  if (options.keep_labels) {
    d.patch_id = std::move(patch);
    d.edge_traced = std::move(traced);
  }
  return d;
}

}  // namespace polycube::quality
