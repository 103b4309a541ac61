//! `polycube fabricate MODEL.mesh POLYCUBE.mesh -o DIR [--solid SURFACE] [--no-merge]`: cut a
//! solid into parts along the boxes of its (simplified) polycube map (thesis ch. 6): box
//! partition, merging, cut plan, model-space planes, exact cuts; one STL per part and parts.json.
#include "cli/app.h"
#include "core/errors.h"
#include "core/topology.h"
#include "fabricate/box_partition.h"
#include "fabricate/cut_plan.h"
#include "fabricate/cut_planes.h"
#include "fabricate/parts.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "structure/validate.h"

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

namespace polycube::cli {

namespace {

struct FabricateOptions {
  std::string model;
  std::string polycube;
  std::string output;
  std::string solid;  //!< the solid's surface; default: the boundary of the map's model tets
  bool no_merge = false;
  bool keep_failed = false;
};

//! Why a part fails the checks, or "" when it passes.
std::string part_problem(const fabricate::Part& p) {
  if (p.mesh.cells.empty()) return "empty (its box's material went to a neighbour)";
  if (!p.closed) return "not closed";
  if (!p.outward) return "not outward";
  if (p.self_intersecting) return "self-intersecting";
  return "";
}

void run_fabricate(const FabricateOptions& o) {
  const core::PolycubeMap map = io::read_polycube_map(o.model, o.polycube);
  structure::validate_map(map);
  const core::TriMesh solid =
      o.solid.empty() ? core::boundary(map.model_mesh()).surface : read_target_surface(o.solid);

  const fabricate::OccupancyGrid grid = fabricate::occupancy_grid(map);
  fabricate::BoxPartition partition = fabricate::partition_boxes(grid);
  const std::size_t boxes = partition.boxes.size();
  if (!o.no_merge) fabricate::merge_boxes(grid, partition);
  const fabricate::CutPlan plan = fabricate::plan_cuts(grid, partition);
  const std::vector<fabricate::CutPlane> planes = fabricate::fit_cut_planes(map, grid, plan);
  const fabricate::Parts parts =
      fabricate::cut_parts(solid, plan, planes, fabricate::box_lookup(map, grid, plan.partition));

  int failing = 0;
  std::string first_problem;
  for (const auto& p : parts.parts) {
    const std::string why = part_problem(p);
    if (!why.empty() && failing++ == 0)
      first_problem = fmt::format("part of box {}: {}", p.box, why);
  }
  if (failing > 0 && !o.keep_failed)
    throw core::GeometryError(
        fmt::format("{} of {} parts fail the checks ({}); nothing written "
                    "(--keep-failed writes them anyway)",
                    failing, parts.parts.size(), first_problem));

  std::filesystem::create_directories(o.output);
  nlohmann::json list = nlohmann::json::array();
  std::size_t written = 0;
  std::string text = fmt::format(
      "{} boxes, {} after merging, {} cuts; {} parts (solid volume {:.6g}, parts {:.6g})\n", boxes,
      plan.partition.boxes.size(), plan.cuts.size(), parts.parts.size(), parts.solid_volume,
      parts.volume_sum);
  text += "  part  box  triangles      volume  components  check\n";
  for (std::size_t i = 0; i < parts.parts.size(); ++i) {
    const fabricate::Part& p = parts.parts[i];
    const std::string file = fmt::format("part_{:02d}.stl", i);
    if (!p.mesh.cells.empty()) {
      io::write_mesh(std::filesystem::path(o.output) / file, core::to_mesh_data(p.mesh));
      ++written;
    }
    const std::string why = part_problem(p);
    const fabricate::Box& b = plan.partition.boxes[static_cast<std::size_t>(p.box)];
    list.push_back({{"file", p.mesh.cells.empty() ? "" : file},
                    {"box", p.box},
                    {"box_cells", {{"lo", b.lo}, {"hi", b.hi}}},
                    {"triangles", p.mesh.num_cells()},
                    {"volume", p.volume},
                    {"components", p.components},
                    {"closed", p.closed},
                    {"outward", p.outward},
                    {"self_intersecting", p.self_intersecting},
                    {"ok", why.empty()}});
    text += fmt::format("  {:4d} {:4d} {:10d} {:11.6g} {:11d}  {}\n", i, p.box, p.mesh.num_cells(),
                        p.volume, p.components, why.empty() ? "ok" : why);
  }
  nlohmann::json j = {{"boxes", boxes},
                      {"merged_boxes", plan.partition.boxes.size()},
                      {"cuts", plan.cuts.size()},
                      {"pinwheel_splits", plan.split_boxes},
                      {"solid_volume", parts.solid_volume},
                      {"parts_volume", parts.volume_sum},
                      {"failing_parts", failing},
                      {"seconds", parts.seconds},
                      {"parts", list}};
  io::write_text_atomic(std::filesystem::path(o.output) / "parts.json", j.dump(2) + "\n");
  text += fmt::format("wrote {} part STL files and parts.json to {}\n", written, o.output);
  print_result(j, text);
}

}  // namespace

void register_fabricate(CLI::App& app) {
  auto opts = std::make_shared<FabricateOptions>();
  CLI::App* sub = app.add_subcommand("fabricate",
                                     "Cut a solid into parts along the boxes of its polycube map "
                                     "(thesis ch. 6): box partition at the concave "
                                     "edges, merging, exact cuts by planes; one STL per part and "
                                     "parts.json (work in progress: no chamber, 3MF "
                                     "or printability checks yet)");
  sub->add_option("model", opts->model,
                  "Model-space tet mesh of the map (.mesh; simplify/model.mesh of run)")
      ->required();
  sub->add_option("polycube", opts->polycube, "Polycube-space tet mesh with the same tets (.mesh)")
      ->required();
  sub->add_option("-o,--output", opts->output, "Output folder for part_NN.stl and parts.json")
      ->required();
  sub->add_option(
      "--solid", opts->solid,
      "The solid's surface to cut (default: the boundary of the map's model tets; give the input "
      "surface to keep it exactly)");
  sub->add_flag("--no-merge", opts->no_merge,
                "Keep the thesis's partition: no merging of boxes whose union is a box");
  sub->add_flag("--keep-failed", opts->keep_failed,
                "Write the parts even when some fail the checks");
  sub->callback([opts] { run_fabricate(*opts); });
}

}  // namespace polycube::cli
