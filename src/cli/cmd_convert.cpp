//! `polycube convert IN OUT [--binary]`: any supported mesh format to any compatible one.
#include "cli/app.h"
#include "core/log.h"
#include "io/mesh_io.h"

#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct ConvertOptions {
  std::string input;
  std::string output;
  bool binary = false;
  bool double_precision = false;
};

std::string counts_text(const core::MeshData& d) {
  std::string s = std::to_string(d.points.size()) + " vertices";
  auto add = [&](std::size_t n, const char* what) {
    if (n > 0) s += ", " + std::to_string(n) + " " + what;
  };
  add(d.edges.size(), "edges");
  add(d.triangles.size(), "triangles");
  add(d.quads.size(), "quads");
  add(d.tets.size(), "tets");
  add(d.hexes.size(), "hexes");
  return s;
}

}  // namespace

void register_convert(CLI::App& app) {
  auto opts = std::make_shared<ConvertOptions>();
  CLI::App* sub = app.add_subcommand(
      "convert",
      "Convert a mesh file to another format, chosen by extension: .obj .off .stl .ply (surfaces), "
      ".mesh .vtk .msh (surfaces and volumes)");
  sub->add_option("input", opts->input, "Input mesh file")->required();
  sub->add_option("output", opts->output, "Output mesh file (written atomically)")->required();
  sub->add_flag("--binary", opts->binary, "Write binary STL or binary little-endian PLY");
  sub->add_flag("--double", opts->double_precision,
                "Binary PLY: double coordinates and fields (by default float, which every other tool reads)");
  sub->callback([opts] {
    const io::Format out_format = io::format_from_path(opts->output);
    if (opts->binary && out_format != io::Format::Stl && out_format != io::Format::Ply)
      core::logger().warn("--binary has no effect on .{} files (only .stl and .ply)", io::format_name(out_format));
    const core::MeshData d = io::read_mesh(opts->input);
    io::WriteOptions wo;
    wo.binary = opts->binary;
    wo.double_precision = opts->double_precision;
    io::write_mesh(opts->output, d, wo);
    const io::Format in = io::format_from_path(opts->input);
    const io::Format out = out_format;
    nlohmann::json j = {{"input", opts->input},
                        {"output", opts->output},
                        {"input_format", io::format_name(in)},
                        {"output_format", io::format_name(out)},
                        {"binary", opts->binary},
                        {"vertices", d.points.size()},
                        {"edges", d.edges.size()},
                        {"triangles", d.triangles.size()},
                        {"quads", d.quads.size()},
                        {"tets", d.tets.size()},
                        {"hexes", d.hexes.size()},
                        {"point_fields", d.point_data.size()},
                        {"cell_fields", d.cell_data.size()}};
    print_result(j, "converted " + opts->input + " (" + io::format_name(in) + ") to " + opts->output + " (" +
                        io::format_name(out) + "): " + counts_text(d));
  });
}

}  // namespace polycube::cli
