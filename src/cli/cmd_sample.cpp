//! `polycube sample NAME -o FILE` and `polycube sample --list`: the built-in sample shapes.
#include "cli/app.h"
#include "io/mesh_io.h"
#include "samples/samples.h"

#include <fmt/format.h>

#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct SampleCliOptions {
  std::string name;
  std::string output;
  bool list = false;
  bool binary = false;
  samples::SampleOptions sample;
};

void print_list() {
  nlohmann::json items = nlohmann::json::array();
  std::string text;
  for (const samples::SampleInfo& s : samples::list_samples()) {
    items.push_back({{"name", s.name}, {"genus", s.genus}, {"description", s.description}});
    text += fmt::format("{:<14} genus {}  {}\n", s.name, s.genus, s.description);
  }
  print_result({{"samples", items}}, text);
}

}  // namespace

void register_sample(CLI::App& app) {
  auto opts = std::make_shared<SampleCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "sample",
      "Write a built-in sample shape (closed CAD-like surfaces, mm units); --list names them");
  sub->add_option("name", opts->name, "Sample name (see --list)");
  sub->add_option("-o,--output", opts->output,
                  "Output surface file: .obj .off .stl .ply .mesh (written atomically)");
  sub->add_flag("--list", opts->list, "List the samples (name, genus, description) and exit");
  sub->add_option("--edge-length", opts->sample.target_edge_length,
                  "Target edge length in mm (0: the sample's default, about 1/55 of its diagonal)");
  sub->add_flag("--binary", opts->binary, "Write binary STL or binary little-endian PLY");
  sub->callback([opts] {
    if (opts->list) {
      print_list();
      return;
    }
    if (opts->name.empty()) throw CLI::ValidationError("sample", "give a sample NAME, or --list");
    if (opts->output.empty()) throw CLI::ValidationError("sample", "give an output file with -o");
    const io::Format format = io::format_from_path(opts->output);  // fail before the work

    const core::TriMesh mesh = samples::make_sample(opts->name, opts->sample);
    io::WriteOptions wo;
    wo.binary = opts->binary;
    io::write_mesh(opts->output, core::to_mesh_data(mesh), wo);

    int genus = -1;
    for (const samples::SampleInfo& s : samples::list_samples())
      if (s.name == opts->name) genus = s.genus;
    const nlohmann::json j = {{"sample", opts->name},
                              {"output", opts->output},
                              {"format", io::format_name(format)},
                              {"vertices", mesh.num_points()},
                              {"triangles", mesh.num_cells()},
                              {"genus", genus}};
    print_result(
        j, fmt::format("wrote sample {} to {}: {} vertices, {} triangles, genus {}", opts->name,
                       opts->output, mesh.num_points(), mesh.num_cells(), genus));
  });
}

}  // namespace polycube::cli
