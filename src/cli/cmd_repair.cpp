//! `polycube repair IN -o OUT [--repair holes|wrap] [--largest-component]`: the repairs `run` and
//! `construct` apply on load (repair/repair.h), as a command of its own: the repaired surface is
//! written, each change is listed, and the result is checked as construct would check it.
#include "cli/app.h"
#include "construct/tetrahedralize.h"
#include "core/errors.h"
#include "io/mesh_io.h"
#include "repair/repair.h"

#include <fmt/format.h>

#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct RepairCliOptions {
  std::string input;
  std::string output;
  repair::RepairOptions repair;
};

//! The triangles of any surface or volume file (a volume file's boundary triangles as stored).
core::TriMesh read_triangles(const std::string& path) {
  if (!io::is_volume_format(io::format_from_path(path))) return io::read_surface(path);
  core::TriMesh m = core::triangles_of(io::read_mesh(path));
  if (m.cells.empty()) throw core::InputError(path, 0, "the file holds no triangle to repair");
  m.labels.clear();
  return m;
}

void run_repair(const RepairCliOptions& o) {
  core::TriMesh mesh = read_triangles(o.input);
  const std::size_t triangles_before = mesh.cells.size();
  const repair::RepairReport report = repair::repair_surface(mesh, o.repair);
  io::write_mesh(o.output, core::to_mesh_data(mesh));
  std::string problem;
  try {
    construct::check_closed_surface(mesh);
  } catch (const core::InputError& e) {
    problem = e.what();
  }
  std::string text = fmt::format("{}: {} triangles -> {}: {} triangles\n", o.input, triangles_before, o.output,
                                 mesh.cells.size());
  for (const std::string& line : report.lines()) text += "  " + line + "\n";
  if (!report.changed()) text += "  nothing to repair\n";
  text += problem.empty() ? "the result is a closed solid that construct and run accept\n"
                          : "the result is still not usable: " + problem + "\n";
  print_result({{"input", o.input},
                {"output", o.output},
                {"triangles_before", triangles_before},
                {"triangles_after", mesh.cells.size()},
                {"repairs", report.lines()},
                {"usable", problem.empty()},
                {"problem", problem.empty() ? nlohmann::json(nullptr) : nlohmann::json(problem)}},
               text);
  if (!problem.empty()) throw core::InputError(o.output, 0, "still not a closed solid after the repairs: " + problem);
}

}  // namespace

void register_repair(CLI::App& app) {
  auto opts = std::make_shared<RepairCliOptions>();
  CLI::App* sub = app.add_subcommand(
      "repair",
      "Repair a surface and write it: the repairs run and construct apply on load (merge equal vertices, drop "
      "degenerate and repeated triangles, split pinched vertices, orient outward), and on request holes, wrap and "
      "the largest component; then check it as construct would (exit 2 naming what is left)");
  sub->add_option("input", opts->input, "Surface or mesh file (.obj .off .stl .ply .mesh .vtk .msh)")->required();
  sub->add_option("-o,--output", opts->output, "Repaired surface (.obj .off .stl .ply .mesh .vtk .msh; written atomically)")
      ->required();
  add_expert_options(*sub, add_repair_options(*sub, opts->repair));
  sub->callback([opts] { run_repair(*opts); });
}

}  // namespace polycube::cli
