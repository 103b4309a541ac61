//! `polycube hexmesh` and `polycube quadmesh`: grid a polycube map into a hex mesh (and its
//! polycube-space twin) or a quad surface mesh (thesis §2.1).
#include "cli/app.h"
#include "core/stopwatch.h"
#include "core/errors.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "mesh/grid.h"
#include "structure/validate.h"

#include <fmt/format.h>

#include <memory>
#include <sstream>
#include <string>

namespace polycube::cli {

namespace {

struct MeshOptions {
  std::string model;
  std::string polycube;
  std::string output;
  std::string polycube_out;    //!< optional polycube-space twin of the output
  bool allow_defects = false;  //!< write the mesh even when snapping broke the polycube
  mesh::GridOptions grid;
  structure::ValidateOptions validate;
  std::vector<std::string> refine_near;  //!< "x,y,z" model-space points (--refine-near)
};

//! A model-space point of --refine-near: three numbers separated by commas.
core::Vec3 parse_point(const std::string& text) {
  core::Vec3 p;
  std::istringstream in(text);
  char comma1 = 0;
  char comma2 = 0;
  if (!(in >> p.x() >> comma1 >> p.y() >> comma2 >> p.z()) || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() ||
      !p.allFinite())
    throw core::InputError(fmt::format("--refine-near: '{}' is not a point x,y,z (three numbers and two commas)", text));
  return p;
}

nlohmann::json snap_json(const mesh::SnapReport& r) {
  nlohmann::json defects = nlohmann::json::array();
  for (const auto& d : r.defects) {
    nlohmann::json pos = nlohmann::json::array();
    for (const auto& p : d.positions) pos.push_back({p.x(), p.y(), p.z()});
    defects.push_back({{"kind", mesh::defect_name(d.kind)},
                       {"corners", d.corners},
                       {"positions", pos},
                       {"lattice", {d.lattice.x(), d.lattice.y(), d.lattice.z()}},
                       {"edge", d.edge},
                       {"chart", d.chart},
                       {"count", d.count},
                       {"description", d.description}});
  }
  return {{"needed", r.needed},
          {"levels", r.levels},
          {"collapsed_levels", r.collapsed_levels},
          {"corners_moved", r.corners_moved},
          {"max_displacement", r.max_displacement},
          {"deformed", r.deformed},
          {"defects", defects}};
}

void run_mesh(const MeshOptions& o, bool hex) {
  const core::Stopwatch clock;
  const core::PolycubeMap map = io::read_polycube_map(o.model, o.polycube);
  structure::validate_map(map, o.validate);
  mesh::GridOptions go = o.grid;
  go.volume = hex;
  if (!o.refine_near.empty()) {
    std::vector<core::Vec3> model_points;
    for (const std::string& t : o.refine_near) model_points.push_back(parse_point(t));
    go.refine_near = mesh::polycube_points(map, model_points);
  }
  const mesh::GridResult r = mesh::grid_polycube(map, go);

  // refuse a broken mesh unless asked
  if (!r.snapping.ok() && !o.allow_defects)
    throw core::GeometryError(
        fmt::format("naive snapping at scale {:.6g} breaks the polycube: {} (choose another "
                    "scale, simplify the polycube first, or pass --allow-defects)",
                    r.scale, r.snapping.summary()));
  if (r.points_failed > 0 && !o.allow_defects)
    throw core::GeometryError(
        fmt::format("{} lattice points lie outside the polycube (by up to {:.3g}); pass "
                    "--allow-defects to write the mesh anyway",
                    r.points_failed, r.max_failed_distance));
  if (hex) {
    io::write_mesh(o.output, core::to_mesh_data(r.hex_model));
    if (!o.polycube_out.empty()) io::write_mesh(o.polycube_out, core::to_mesh_data(r.hex_polycube));
  } else {
    io::write_mesh(o.output, core::to_mesh_data(r.quad_model));
    if (!o.polycube_out.empty())
      io::write_mesh(o.polycube_out, core::to_mesh_data(r.quad_polycube));
  }
  const double seconds =
      clock.seconds();

  const int points = static_cast<int>(r.hex_polycube.points.size());
  nlohmann::json j = {{"output", o.output},
                      {"scale", r.scale},
                      {"lattice_min", r.lattice_min},
                      {"lattice_max", r.lattice_max},
                      {"hexes", r.hex_polycube.cells.size()},
                      {"quads", r.quad_polycube.cells.size()},
                      {"lattice_points", points},
                      {"points_located", r.points_located},
                      {"points_failed", r.points_failed},
                      {"snapping", snap_json(r.snapping)},
                      {"seconds_locate", r.seconds_locate},
                      {"seconds_grid", r.seconds_total},
                      {"seconds", seconds}};
  if (hex) j["inverted_model_hexes"] = r.inverted_model_hexes;
  if (!o.polycube_out.empty()) j["polycube_output"] = o.polycube_out;
  const char* scale_name = go.sizing == mesh::GridSizing::Map ? "cells per model length" : "scale";
  std::string text = fmt::format("{} {:.6g}: lattice [{}, {}] x [{}, {}] x [{}, {}]\n", scale_name, r.scale,
                                 r.lattice_min[0], r.lattice_max[0], r.lattice_min[1],
                                 r.lattice_max[1], r.lattice_min[2], r.lattice_max[2]);
  if (hex)
    text += fmt::format("hexes {}, boundary quads {}, lattice points {}\n",
                        r.hex_polycube.cells.size(), r.quad_polycube.cells.size(), points);
  else
    text += fmt::format("quads {}, lattice points on the surface {}\n",
                        r.quad_polycube.cells.size(), r.quad_polycube.points.size());
  text += fmt::format("points located {}, failed {}\n", r.points_located, r.points_failed);
  text += fmt::format("snapping: {}{}\n",
                      r.snapping.needed
                          ? fmt::format("levels moved by up to {:.3g} ({} corners moved), ",
                                        r.snapping.max_displacement, r.snapping.corners_moved)
                          : std::string("corners already on the lattice, "),
                      r.snapping.summary());
  if (hex && r.inverted_model_hexes > 0)
    text += fmt::format("inverted hexes in model space: {} (optimize the mesh before use)\n",
                        r.inverted_model_hexes);
  text +=
      fmt::format("wrote {}{}\n", o.output, o.polycube_out.empty() ? "" : " and " + o.polycube_out);
  text += fmt::format("time: locate {:.3f} s, grid {:.3f} s, total {:.3f} s\n", r.seconds_locate,
                      r.seconds_total, seconds);
  print_result(j, text);
}

CLI::App* add_common(CLI::App& app, const char* name, const char* help,
                     const std::shared_ptr<MeshOptions>& opts, bool hex) {
  CLI::App* sub = app.add_subcommand(name, help);
  sub->add_option("model", opts->model, "Model-space tet mesh of the map (.mesh)")
      ->required();
  sub->add_option("polycube", opts->polycube, "Polycube-space tet mesh with the same tets (.mesh)")
      ->required();
  sub->add_option("-o,--output", opts->output,
                  hex ? "Hex mesh in model space (.mesh .vtk .msh)"
                      : "Quad mesh in model space (.obj .off .ply .mesh .vtk)")
      ->required();
  sub->add_option("--polycube-out", opts->polycube_out,
                  "Also write the polycube-space twin (lattice coordinates)");
  auto* scale = sub->add_option("--scale", opts->grid.scale, "Lattice cells per polycube unit")
                    ->check(cli::positive());
  auto* hexes = sub->add_option("--hexes", opts->grid.target_hexes,
                                "Choose the scale for about this many hexes")
                    ->check(cli::positive());
  scale->excludes(hexes);
  if (!hex) {
    auto* quads = sub->add_option("--quads", opts->grid.target_quads,
                                  "Choose the scale for about this many quads")
                      ->check(cli::positive());
    quads->excludes(scale)->excludes(hexes);
  }
  add_sizing_option(*sub, opts->grid.sizing,
                  "Cells per interval between chart planes: 'uniform' (one scale, cubes in polycube space) or "
                  "'map' (follows the map's stretch: closer to one hex size in model space; --scale is then cells "
                  "per model length)");
  sub->add_option("--refine-near", opts->refine_near,
                  "Twice the cells (--refine-factor) around this model-space point x,y,z (repeatable): the slabs "
                  "of the polycube that hold it, on each axis (on a simplified polycube one unit thick, else the "
                  "interval between chart planes); a feature thinner than the hexes gets more of them");
  sub->add_option("--refine-factor", opts->grid.refine_factor, "How many times the cells around --refine-near")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  sub->add_flag(
      "--allow-defects", opts->allow_defects,
      "Write the mesh even when naive snapping breaks the polycube (merged corners, ...)");
  sub->add_option("--axis-tolerance", opts->validate.axis_tolerance,
                  "Axis-alignment tolerance of polycube boundary triangles, relative to the "
                  "bounding-box diagonal")
      ->check(cli::non_negative())
      ->capture_default_str();
  return sub;
}

}  // namespace

void register_hexmesh(CLI::App& app) {
  auto opts = std::make_shared<MeshOptions>();
  CLI::App* sub = add_common(
      app, "hexmesh",
      "Grid a polycube map into a hex mesh: scale, integer lattice, map back (scale 1 by default)",
      opts, true);
  sub->callback([opts] { run_mesh(*opts, true); });
}

void register_quadmesh(CLI::App& app) {
  auto opts = std::make_shared<MeshOptions>();
  CLI::App* sub = add_common(app, "quadmesh",
                             "Grid a polycube map's surface into a quad mesh (scale 1 by default)",
                             opts, false);
  sub->callback([opts] { run_mesh(*opts, false); });
}

}  // namespace polycube::cli
