//! Benchmark of the sheet insertion (issue 18): global padding, and global padding crossed by
//! an interior sheet, of a ~50,000-hex grid, plus any hex meshes given on the command line
//! (global padding). Prints the median of 3 runs as a text table, or JSON with --json.
//!
//! usage: bench_padding [--json] [hex.mesh ...]
#include "core/topology.h"
#include "io/mesh_io.h"
#include "padding/sheet.h"
#include "support/fixtures.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace polycube;

constexpr int kRuns = 3;

struct Row {
  std::string model;
  int hexes = 0;
  int selected = 0;
  int added = 0;
  int crossing = 0;
  double seconds = 0;  // median
};

Row run(const std::string& name, const core::HexMesh& mesh, const std::vector<std::uint8_t>& selected) {
  Row r{name, mesh.num_cells(), static_cast<int>(std::count(selected.begin(), selected.end(), 1)), 0, 0, 0};
  std::vector<double> times;
  for (int i = 0; i < kRuns; ++i) {
    const padding::SheetResult s = padding::insert_sheet(mesh, selected);
    times.push_back(s.seconds);
    r.added = s.added_hexes;
    r.crossing = s.crossing_hexes;
  }
  std::sort(times.begin(), times.end());
  r.seconds = times[kRuns / 2];
  return r;
}

//! Global padding plus the interior plane x = n/2 of an n^3 grid: crossings along its boundary.
std::vector<std::uint8_t> global_and_plane(const core::HexMesh& grid, double x) {
  std::vector<std::uint8_t> sel = padding::boundary_selection(grid);
  const auto faces = core::unique_faces(grid);
  for (int f = 0; f < faces.num_faces(); ++f)
    if (std::all_of(faces.faces[f].begin(), faces.faces[f].end(), [&](int v) { return grid.points[v].x() == x; }))
      sel[f] = 1;
  return sel;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json") json = true;
    else files.push_back(a);
  }
  const core::HexMesh grid = test::hex_grid(37, 37, 37);  // 50,653 hexes
  std::vector<Row> rows;
  rows.push_back(run("grid 37^3, global", grid, padding::boundary_selection(grid)));
  rows.push_back(run("grid 37^3, global + plane", grid, global_and_plane(grid, 18.0)));
  for (const std::string& f : files) {
    const core::HexMesh m = core::hexes_of(io::read_mesh(f));
    rows.push_back(run(f + ", global", m, padding::boundary_selection(m)));
  }
  if (json) {
    nlohmann::json j = nlohmann::json::array();
    for (const Row& r : rows)
      j.push_back({{"model", r.model},
                   {"hexes", r.hexes},
                   {"selected_facets", r.selected},
                   {"added_hexes", r.added},
                   {"crossing_hexes", r.crossing},
                   {"seconds", r.seconds}});
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::printf("sheet insertion, median of %d runs (checks of the result included)\n", kRuns);
  std::printf("%-40s %8s %9s %8s %9s %9s\n", "mesh", "hexes", "selected", "added", "crossing", "seconds");
  for (const Row& r : rows)
    std::printf("%-40s %8d %9d %8d %9d %9.3f\n", r.model.c_str(), r.hexes, r.selected, r.added, r.crossing, r.seconds);
  return 0;
}
