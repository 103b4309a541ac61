//! `polycube structure MODEL.mesh POLYCUBE.mesh [-o structure.vtk]`: validate a polycube map and
//! print its structure (charts, edges convex/concave, corners, faces with holes).
#include "cli/app.h"
#include "io/polycube_map_io.h"
#include "structure/structure.h"
#include "structure/structure_io.h"
#include "structure/validate.h"

#include <fmt/format.h>

#include <array>
#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct StructureOptions {
  std::string model;
  std::string polycube;
  std::string output;              //!< optional .vtk of charts, edges and corners
  std::string space = "polycube";  //!< where the .vtk is drawn: polycube or model
  structure::ValidateOptions validate;
};

void run_structure(const StructureOptions& o) {
  const core::PolycubeMap map = io::read_polycube_map(o.model, o.polycube);
  structure::validate_map(map, o.validate);
  const structure::PolycubeStructure s = structure::extract_structure(map);

  std::array<int, 6> charts_per_label{};
  for (const auto& c : s.charts) ++charts_per_label[static_cast<std::size_t>(c.label)];
  int holes = 0;
  for (const auto& f : s.faces) holes += f.num_holes();
  nlohmann::json j = {{"vertices", map.num_vertices()},
                      {"tets", map.num_tets()},
                      {"boundary_triangles", s.triangles.size()},
                      {"charts", s.charts.size()},
                      {"charts_per_label", charts_per_label},
                      {"edges", s.edges.size()},
                      {"convex_edges", s.num_convex_edges()},
                      {"concave_edges", s.num_concave_edges()},
                      {"corners", s.corners.size()},
                      {"faces", s.faces.size()},
                      {"faces_with_holes", s.num_faces_with_holes()},
                      {"holes", holes},
                      {"max_chart_deviation", s.max_chart_deviation()}};
  std::string text = fmt::format(
      "polycube map: {} vertices, {} tets, {} boundary triangles (valid)\n"
      "charts   {} (+X {}, -X {}, +Y {}, -Y {}, +Z {}, -Z {})\n"
      "edges    {} ({} convex, {} concave)\n"
      "corners  {}\n"
      "faces    {} ({} with holes, {} holes)\n",
      map.num_vertices(), map.num_tets(), s.triangles.size(), s.charts.size(), charts_per_label[0],
      charts_per_label[1], charts_per_label[2], charts_per_label[3], charts_per_label[4],
      charts_per_label[5], s.edges.size(), s.num_convex_edges(), s.num_concave_edges(),
      s.corners.size(), s.faces.size(), s.num_faces_with_holes(), holes);
  if (!o.output.empty()) {
    structure::write_structure_vtk(o.output, s, o.space == "model" ? map.model : map.polycube);
    j["output"] = o.output;
    text += fmt::format("wrote {} ({} space)\n", o.output, o.space);
  }
  print_result(j, text);
}

}  // namespace

void register_structure(CLI::App& app) {
  auto opts = std::make_shared<StructureOptions>();
  CLI::App* sub = app.add_subcommand("structure",
                                     "Validate a polycube map and print its structure: charts, "
                                     "edges (convex/concave), corners, faces");
  sub->add_option("model", opts->model, "Model-space tet mesh of the map (.mesh)")
      ->required();
  sub->add_option("polycube", opts->polycube, "Polycube-space tet mesh with the same tets (.mesh)")
      ->required();
  sub->add_option("-o,--output", opts->output,
                  "Write the charts, edges and corners as a legacy VTK file (.vtk)");
  sub->add_option("--space", opts->space, "Draw the structure in polycube or model space")
      ->transform(one_of({"polycube", "model"}))
      ->type_name("polycube|model")
      ->capture_default_str();
  sub->add_option("--axis-tolerance", opts->validate.axis_tolerance,
                  "Axis-alignment tolerance of polycube boundary triangles, relative to the "
                  "bounding-box diagonal")
      ->check(cli::non_negative())
      ->capture_default_str();
  sub->callback([opts] { run_structure(*opts); });
}

}  // namespace polycube::cli
