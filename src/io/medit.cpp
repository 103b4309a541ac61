//! MEDIT ASCII `.mesh` (the INRIA/Gamma format of Medit, MMG, TetGen, cinolib): keywords and
//! numbers separated by any whitespace (so `Dimension 3` and `Dimension\n3` both work), `#`
//! comments, `MeshVersionFormatted 1..4`, `Dimension 3`, blocks `Vertices`, `Edges`,
//! `Triangles`, `Quadrilaterals`, `Tetrahedra`, `Hexahedra` (each item ending with its integer
//! reference, kept as a label), 1-based indices, `End`. Blocks of known size that polycube does
//! not use (Corners, Ridges, Required*, Normals, Tangents, NormalAt*, ...) are skipped; other
//! element kinds (Prisms, Pyramids, P2 elements) are refused. Written with version 2 and the
//! shortest exact decimal form of every coordinate.
#include "io/formats.h"
#include "io/parse.h"

#include <algorithm>
#include <cctype>
#include <climits>

namespace polycube::io::detail {

namespace {

//! Blocks polycube skips: keyword and number of whitespace-separated values per item.
struct SkippedBlock {
  std::string_view keyword;
  int values;
};
constexpr SkippedBlock kSkipped[] = {
    {"Corners", 1},          {"Ridges", 1},
    {"RequiredVertices", 1}, {"RequiredEdges", 1},
    {"RequiredTriangles", 1}, {"RequiredQuadrilaterals", 1},
    {"RequiredTetrahedra", 1}, {"RequiredHexahedra", 1},
    {"Normals", 3},          {"Tangents", 3},
    {"NormalAtVertices", 2}, {"NormalAtTriangleVertices", 3},
    {"NormalAtQuadrilateralVertices", 3}, {"TangentAtEdges", 3},
    {"TangentAtVertices", 2}, {"VertexOnGeometricVertex", 2},
    {"VertexOnGeometricEdge", 3}, {"VertexOnGeometricTriangle", 4},
    {"EdgeOnGeometricEdge", 2}, {"TriangleOnGeometricTriangle", 2},
    {"SubDomainFromMesh", 4}, {"SubDomainFromGeom", 4},
    {"Crack", 2},            {"Equivalences", 2},
    {"Identifier", 0},       {"Geometry", 0},
};

//! Element kinds polycube cannot hold.
constexpr std::string_view kRefused[] = {"Prisms", "Pyramids", "EdgesP2", "TrianglesP2", "QuadrilateralsQ2",
                                         "TetrahedraP2", "HexahedraQ2", "Pentahedra", "Polygons", "Polyhedra"};

//! An element or vertex reference (label), which must fit an int.
int reference(Scanner& s) {
  const long long r = s.integer("reference");
  if (r < INT_MIN || r > INT_MAX) s.fail("reference " + std::to_string(r) + " out of range");
  return static_cast<int>(r);
}

template <std::size_t N>
void read_block(Scanner& s, int n_points, std::vector<std::array<int, N>>& cells, std::vector<int>& labels) {
  const int n = s.count("elements", 2 * (N + 1) - 1);
  cells.reserve(cells.size() + static_cast<std::size_t>(n));
  labels.reserve(labels.size() + static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    std::array<int, N> c;
    for (std::size_t k = 0; k < N; ++k) {
      if (s.at_end()) s.fail("unexpected end of file inside a block of " + std::to_string(n) + " elements");
      c[k] = s.index(n_points, 1);
    }
    cells.push_back(c);
    labels.push_back(reference(s));
  }
}

}  // namespace

core::MeshData read_medit(std::string_view data, const std::string& name) {
  Scanner s(data, name, '#');
  core::MeshData d;
  bool have_version = false;
  bool have_dimension = false;
  for (;;) {
    const std::string_view kw = s.next();
    if (kw.empty()) break;  // End is optional in practice
    if (!have_version && !iequals(kw, "MeshVersionFormatted"))
      s.fail("not a MEDIT file (expected 'MeshVersionFormatted', found " + quote(kw) + ")");
    if (iequals(kw, "MeshVersionFormatted")) {
      const long long v = s.integer("MeshVersionFormatted");
      if (v < 1 || v > 4) s.fail("unsupported MeshVersionFormatted " + std::to_string(v) + " (expected 1 or 2)");
      have_version = true;
    } else if (iequals(kw, "Dimension")) {
      const long long dim = s.integer("Dimension");
      if (dim != 3) s.fail("unsupported Dimension " + std::to_string(dim) + " (only 3)");
      have_dimension = true;
    } else if (iequals(kw, "Vertices")) {
      if (!have_dimension) s.fail("'Vertices' before 'Dimension 3'");
      const int n = s.count("vertices", 7);
      d.points.reserve(d.points.size() + static_cast<std::size_t>(n));
      d.point_labels.reserve(d.points.capacity());
      for (int i = 0; i < n; ++i) {
        if (s.at_end()) s.fail("unexpected end of file: " + std::to_string(n) + " vertices declared, " + std::to_string(i) + " read");
        core::Vec3 p;
        for (int k = 0; k < 3; ++k) p[k] = s.real("vertex coordinate");
        d.points.push_back(p);
        d.point_labels.push_back(reference(s));
      }
    } else if (iequals(kw, "Edges")) {
      read_block(s, static_cast<int>(d.points.size()), d.edges, d.edge_labels);
    } else if (iequals(kw, "Triangles")) {
      read_block(s, static_cast<int>(d.points.size()), d.triangles, d.triangle_labels);
    } else if (iequals(kw, "Quadrilaterals")) {
      read_block(s, static_cast<int>(d.points.size()), d.quads, d.quad_labels);
    } else if (iequals(kw, "Tetrahedra")) {
      read_block(s, static_cast<int>(d.points.size()), d.tets, d.tet_labels);
    } else if (iequals(kw, "Hexahedra")) {
      read_block(s, static_cast<int>(d.points.size()), d.hexes, d.hex_labels);
    } else if (iequals(kw, "End")) {
      break;
    } else {
      const auto refused = std::find_if(std::begin(kRefused), std::end(kRefused),
                                        [&](std::string_view r) { return iequals(r, kw); });
      if (refused != std::end(kRefused))
        s.fail("MEDIT block " + quote(kw) + " holds elements polycube does not support "
               "(only triangles, quads, tets, hexes)");
      const auto skip = std::find_if(std::begin(kSkipped), std::end(kSkipped),
                                     [&](const SkippedBlock& b) { return iequals(b.keyword, kw); });
      if (skip == std::end(kSkipped)) s.fail("unknown MEDIT keyword " + quote(kw));
      if (skip->values == 0) {
        s.token("value");  // a single string or number
        continue;
      }
      const int n = s.count("items", 2 * static_cast<std::size_t>(skip->values) - 1);
      for (long long i = 0; i < static_cast<long long>(n) * skip->values; ++i) s.token("block value");
    }
  }
  if (!have_version) s.fail("not a MEDIT file (no 'MeshVersionFormatted')");
  return d;
}

std::string write_medit(const core::MeshData& d, const WriteOptions& /*options*/) {
  std::string out;
  out.reserve(d.points.size() * 70 + d.num_cells() * 48);
  TextWriter w(out);
  w << "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n" << d.points.size() << '\n';
  for (std::size_t i = 0; i < d.points.size(); ++i) {
    const core::Vec3& p = d.points[i];
    w << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << (d.point_labels.empty() ? 0 : d.point_labels[i]) << '\n';
  }
  auto block = [&](const char* keyword, const auto& cells, const std::vector<int>& labels) {
    if (cells.empty()) return;
    w << '\n' << keyword << '\n' << cells.size() << '\n';
    for (std::size_t c = 0; c < cells.size(); ++c) {
      for (const int v : cells[c]) w << v + 1 << ' ';
      w << (labels.empty() ? 0 : labels[c]) << '\n';
    }
  };
  block("Edges", d.edges, d.edge_labels);
  block("Triangles", d.triangles, d.triangle_labels);
  block("Quadrilaterals", d.quads, d.quad_labels);
  block("Tetrahedra", d.tets, d.tet_labels);
  block("Hexahedra", d.hexes, d.hex_labels);
  w << "\nEnd\n";
  return out;
}

}  // namespace polycube::io::detail
