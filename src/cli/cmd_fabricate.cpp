//! `polycube fabricate INPUT [POLYCUBE] -o DIR [--chamber X Y Z] [--no-merge]`: cut a solid into
//! parts along the boxes of its simplified polycube map (thesis ch. 6). From a map
//! (`model.mesh polycube.mesh`) the parts go straight into DIR; from a surface or tet mesh the
//! chain's own stages build the map first (construct, simplify: `polycube run`'s, without the
//! hex meshing), into DIR/construct, DIR/simplify and the parts into DIR/parts.
#include "cli/app.h"
#include "core/errors.h"
#include "core/topology.h"
#include "fabricate/decompose.h"
#include "io/mesh_io.h"
#include "io/polycube_map_io.h"
#include "pipeline/parts_output.h"
#include "pipeline/pipeline.h"
#include "structure/validate.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace polycube::cli {

namespace {

struct FabricateOptions {
  std::string input;     //!< model.mesh of a map, or a surface / tet mesh
  std::string polycube;  //!< polycube.mesh of the map (empty: input is a shape)
  std::string output;
  std::string solid;  //!< the solid's surface; default: the boundary of the map's model tets
  std::vector<double> chamber;
  bool no_merge = false;
  bool keep_failed = false;
  fabricate::DecomposeOptions decompose;
  fabricate::PrintOptions print;
  pipeline::MillOptions mill;
  std::vector<double> axis;
};

//! From a map: decompose, check, write into the output folder.
void fabricate_map(const FabricateOptions& o) {
  const core::PolycubeMap map = io::read_polycube_map(o.input, o.polycube);
  structure::validate_map(map);
  const core::TriMesh solid =
      o.solid.empty() ? core::boundary(map.model_mesh()).surface : read_target_surface(o.solid);
  const pipeline::Fabrication f =
      pipeline::fabricate_solid(map, solid, o.decompose, o.print, o.mill);
  if (!o.keep_failed) pipeline::check_parts(f);
  const auto files = pipeline::write_parts(o.output, f);
  print_result(
      pipeline::parts_json(f),
      pipeline::parts_table(f) + fmt::format("wrote {} files to {} (print/ holds each part "
                                             "on its base for a slicer, parts.3mf the "
                                             "assembly, exploded.vtk opens in ParaView)\n",
                                             files.size(), o.output));
}

//! From a shape: run's stages input, construct, simplify, fabricate.
void fabricate_shape(const FabricateOptions& o) {
  pipeline::RunOptions run;
  run.hexmesh = false;
  run.fabricate = true;
  run.fabricate_options = o.decompose;
  run.fabricate_print = o.print;
  run.fabricate_mill_directions = o.mill.directions;
  if (o.mill.axis)
    throw core::InputError(
        "--axis applies to a map (MODEL.mesh POLYCUBE.mesh): the shape's "
        "model frame is only known once it is read");
  run.construct.on_attempt = attempt_progress();
  const bool show = !global_options().quiet && !global_options().json;
  run.on_stage = [show](int i, int n, const std::string& name) {
    if (show) print_status(fmt::format("[{}/{}] {}", i, n, name));
  };
  const pipeline::RunResult r = pipeline::run_pipeline(o.input, o.output, run);
  if (!r.ok()) {
    const std::string msg = fmt::format("stage {} failed: {} (earlier results are in {})",
                                        r.failed_stage, r.failure, o.output);
    if (r.bad_input) throw core::InputError(msg);
    throw core::GeometryError(msg);
  }
  const std::filesystem::path json = std::filesystem::path(o.output) / "parts" / "parts.json";
  std::ifstream in(json);
  print_result(nlohmann::json::parse(in, nullptr, false),
               fmt::format("{} boxes, {} parts in {:.1f} s; wrote {}/parts (parts.3mf, "
                           "part_NN.stl, exploded.vtk, parts.json)\n",
                           r.part_boxes, r.parts, r.total_seconds, o.output));
}

void run_fabricate(FabricateOptions o) {
  o.decompose.merge = !o.no_merge;
  if (!o.chamber.empty()) o.decompose.chamber = {o.chamber[0], o.chamber[1], o.chamber[2]};
  if (!o.axis.empty()) {
    const core::Vec3 d(o.axis[3], o.axis[4], o.axis[5]);
    if (!(d.norm() > 0))
      throw core::InputError("--axis: the direction (last three numbers) is zero");
    o.mill.axis = fabricate::Axis{{o.axis[0], o.axis[1], o.axis[2]}, d.normalized()};
  }
  if (o.polycube.empty()) {
    if (!o.solid.empty() || o.keep_failed)
      throw core::InputError("--solid and --keep-failed apply to a map (MODEL.mesh POLYCUBE.mesh)");
    fabricate_shape(o);
  } else {
    fabricate_map(o);
  }
}

}  // namespace

CLI::Option* add_chamber_option(CLI::App& sub, std::vector<double>& chamber) {
  return sub
      .add_option(
          "--chamber", chamber,
          "Build volume X Y Z (model units; the samples are in mm): parts too large to stand "
          "on one of their flat sides in it are split further in polycube space")
      ->expected(3)
      ->check(cli::positive());
}

void register_fabricate(CLI::App& app) {
  auto opts = std::make_shared<FabricateOptions>();
  CLI::App* sub = app.add_subcommand(
      "fabricate",
      "Cut a solid into parts with flat sides along the boxes of its polycube (thesis ch. 6), for "
      "3D printing or milling in parts: box partition at the concave edges, merging, exact cuts by "
      "planes. From a surface or tet mesh the map is built first (construct, simplify). Writes "
      "part_NN.stl, print/part_NN.stl (each on its best base), parts.3mf (the assembly), "
      "exploded.ply/.vtk and parts.json");
  sub->add_option("input", opts->input,
                  "A closed surface (.obj .off .stl .ply) or tet mesh to build the map of, or the "
                  "model-space tet mesh of a map (simplify/model.mesh of run) followed by POLYCUBE")
      ->required();
  sub->add_option("polycube", opts->polycube,
                  "With a map: its polycube-space tet mesh with the same tets (.mesh)");
  sub->add_option("-o,--output", opts->output,
                  "Output folder (from a map: the part files; from a shape: construct/, simplify/, "
                  "parts/)")
      ->required();
  add_chamber_option(*sub, opts->chamber);
  sub->add_option("--overhang", opts->print.overhang_degrees,
                  "Printing check: steepest overhang printed without support, in degrees from "
                  "the vertical")
      ->capture_default_str()
      ->check(cli::in_range(0.0, 90.0));
  sub->add_option("--axis", opts->axis,
                  "Milling check: the 4-axis rotation axis as a point and a direction, PX PY PZ DX "
                  "DY DZ (default: chosen per part, the principal direction of its normals that "
                  "lets the tool reach most)")
      ->expected(6);
  sub->add_option("--directions", opts->mill.directions,
                  "Milling check: 4-axis tool directions evenly spaced about the axis")
      ->capture_default_str()
      ->check(cli::in_range(1, 3600));
  sub->add_flag("--no-merge", opts->no_merge,
                "Keep the thesis's partition: no merging of boxes whose union is a box");
  sub->add_option(
      "--solid", opts->solid,
      "With a map: the solid's surface to cut (default: the boundary of the map's model tets; give "
      "the input surface to keep it exactly)");
  sub->add_flag("--keep-failed", opts->keep_failed,
                "With a map: write the parts even when some fail the checks or the chamber");
  sub->callback([opts] { run_fabricate(*opts); });
}

}  // namespace polycube::cli
