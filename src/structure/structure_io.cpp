#include "structure/structure_io.h"

#include "core/errors.h"
#include "io/mesh_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>

namespace polycube::structure {

std::string structure_to_vtk(const PolycubeStructure& s, const std::vector<core::Vec3>& positions) {
  // Cells: (vtk type, vertices, kind, id, axis, label, concave)
  struct Cell {
    int type;
    std::vector<int> v;
    std::array<int, 5> data;
  };
  std::vector<Cell> cells;
  for (std::size_t f = 0; f < s.triangles.size(); ++f) {
    const int c = s.triangle_chart[f];
    const Chart& ch = s.charts[static_cast<std::size_t>(c)];
    cells.push_back({5,
                     {s.triangles[f][0], s.triangles[f][1], s.triangles[f][2]},
                     {0, c, ch.axis, ch.label, 0}});
  }
  for (std::size_t e = 0; e < s.edges.size(); ++e) {
    const Edge& pe = s.edges[e];
    const std::size_t n = pe.vertices.size();
    const bool closed = pe.corners[0] < 0 && n > 2;
    for (std::size_t k = 0; k + 1 < n + (closed ? 1 : 0); ++k)
      cells.push_back({3,
                       {pe.vertices[k], pe.vertices[(k + 1) % n]},
                       {1, static_cast<int>(e), pe.axis, -1, pe.convex ? 0 : 1}});
  }
  for (std::size_t c = 0; c < s.corners.size(); ++c)
    cells.push_back({1, {s.corners[c].vertex}, {2, static_cast<int>(c), -1, -1, 0}});

  // Compact the used vertices (in increasing map id order).
  std::vector<int> used;
  for (const Cell& c : cells) used.insert(used.end(), c.v.begin(), c.v.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  for (int v : used)
    if (v < 0 || v >= static_cast<int>(positions.size()))
      throw core::InputError("structure_to_vtk: vertex " + std::to_string(v) + " has no position");
  auto local = [&](int v) {
    return static_cast<int>(std::lower_bound(used.begin(), used.end(), v) - used.begin());
  };

  std::string out =
      "# vtk DataFile Version 3.0\npolycube structure: charts, edges, corners\nASCII\n"
      "DATASET UNSTRUCTURED_GRID\n";
  out += fmt::format("POINTS {} double\n", used.size());
  for (int v : used) {
    const core::Vec3& p = positions[static_cast<std::size_t>(v)];
    out += fmt::format("{} {} {}\n", p.x(), p.y(), p.z());
  }
  std::size_t size = 0;
  for (const Cell& c : cells) size += c.v.size() + 1;
  out += fmt::format("CELLS {} {}\n", cells.size(), size);
  for (const Cell& c : cells) {
    out += std::to_string(c.v.size());
    for (int v : c.v) {
      out += ' ';
      out += std::to_string(local(v));
    }
    out += '\n';
  }
  out += fmt::format("CELL_TYPES {}\n", cells.size());
  for (const Cell& c : cells) out += std::to_string(c.type) + '\n';
  // FIELD arrays rather than several SCALARS: legacy readers keep only the first SCALARS
  // unless told otherwise, while every FIELD array is always read.
  out += fmt::format("CELL_DATA {}\nFIELD attributes 5\n", cells.size());
  constexpr const char* kNames[5] = {"kind", "id", "axis", "label", "concave"};
  for (int k = 0; k < 5; ++k) {
    out += fmt::format("{} 1 {} int\n", kNames[k], cells.size());
    for (const Cell& c : cells) out += std::to_string(c.data[static_cast<std::size_t>(k)]) + '\n';
  }
  return out;
}

void write_structure_vtk(const std::filesystem::path& path, const PolycubeStructure& s,
                         const std::vector<core::Vec3>& positions) {
  io::write_text_atomic(path, structure_to_vtk(s, positions));
}

}  // namespace polycube::structure
